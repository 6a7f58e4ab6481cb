// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// quad bridge: a live Foxglove WebSocket server (foxglove.websocket.v1) for a running stack.
/// It advertises every topic of quad's contracts (the display topics among them) with its
/// schema from the IDL and CDR messages, subscribes to a topic in the domain when the first
/// client subscribes to it, and sends each sample to every subscribed client. Clients may
/// publish (clientPublish) on the topics the stack takes from outside, the operator's: the
/// goal, commands, the operator's heartbeat. It listens on localhost unless told otherwise.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

#include "quad/topic/connection.hpp"

namespace quad::bridge {

struct BridgeOptions {
  topic::ConnectionOptions connection;
  std::string address = "127.0.0.1";  ///< where to listen; 0.0.0.0 for every interface
  std::uint16_t port = 8765;          ///< Foxglove's default; 0: any free port
  std::size_t client_queue_bytes = 16u << 20U;  ///< per client: past it, what it is sent is dropped
  bool quiet = false;                 ///< no progress line
};

/// Serves until `stop` is set (a signal); the exit status. Prints "bridge: listening on
/// ws://ADDRESS:PORT" once it listens.
int runBridge(const BridgeOptions& options, const std::atomic<int>& stop);

}  // namespace quad::bridge
