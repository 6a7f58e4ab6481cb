// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The bridge's WebSocket server (Boost.Beast): accepts clients that ask for the Foxglove
/// subprotocol, hands their messages to callbacks, and sends to each through a queue of its
/// own on one I/O thread. A client that reads slower than it is sent to fills its queue; past
/// the queue's byte limit what is sent to it is dropped (and counted), so a slow client never
/// holds back the stack or the other clients.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "quad/bridge/protocol.hpp"

namespace quad::bridge {

/// A payload shared by every client it goes to.
using SharedBytes = std::shared_ptr<const std::vector<std::uint8_t>>;

class Client {
public:
  virtual ~Client() = default;
  /// Thread-safe; never blocks. False when the message was dropped (queue full, or closed).
  virtual bool sendText(std::string text) = 0;
  virtual bool sendMessage(const MessageHeader& header, SharedBytes payload) = 0;
  virtual std::uint64_t id() const = 0;
  virtual std::string peer() const = 0;
  virtual std::uint64_t dropped() const = 0;
};

struct ServerCallbacks {
  std::function<void(const std::shared_ptr<Client>&)> opened;
  std::function<void(const std::shared_ptr<Client>&, std::string_view)> text;
  std::function<void(const std::shared_ptr<Client>&, std::span<const std::uint8_t>)> binary;
  std::function<void(const std::shared_ptr<Client>&)> closed;
};

class Server {
public:
  /// Listens on address:port (port 0: any free one); throws std::runtime_error naming the
  /// address when it cannot.
  Server(const std::string& address, std::uint16_t port, std::size_t queue_limit_bytes, ServerCallbacks callbacks);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  std::uint16_t port() const;
  /// Closes every client and stops the I/O thread.
  void stop();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace quad::bridge
