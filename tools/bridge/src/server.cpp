// SPDX-License-Identifier: BSD-3-Clause
#include "server.hpp"

#include <deque>
#include <mutex>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <spdlog/spdlog.h>

namespace quad::bridge {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

/// One frame queued for a client: a text, or a message header and its shared payload.
struct Frame {
  bool text = false;
  std::string body;  // the text
  MessageHeader header{};
  SharedBytes payload;
  std::size_t size() const { return text ? body.size() : header.size() + payload->size(); }
};

class Connection : public Client, public std::enable_shared_from_this<Connection> {
public:
  Connection(tcp::socket socket, std::uint64_t id, std::size_t limit, const ServerCallbacks& callbacks)
      : ws_(std::move(socket)), id_(id), limit_(limit), callbacks_(callbacks)
  {
    beast::error_code ec;
    // Small frames, sent as samples arrive: without this, Nagle's algorithm holds a frame
    // back until the client acknowledges the one before, which the client's delayed
    // acknowledgement postpones by up to 40 ms.
    beast::get_lowest_layer(ws_).socket().set_option(tcp::no_delay(true), ec);
    const auto ep = beast::get_lowest_layer(ws_).socket().remote_endpoint(ec);
    peer_ = ec ? "?" : ep.address().to_string() + ":" + std::to_string(ep.port());
  }

  void start()
  {
    http::async_read(beast::get_lowest_layer(ws_), buffer_, request_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->onRequest(ec); });
  }

  bool sendText(std::string text) override
  {
    auto frame = std::make_shared<Frame>();
    frame->text = true;
    frame->body = std::move(text);
    return post(std::move(frame));
  }

  bool sendMessage(const MessageHeader& header, SharedBytes payload) override
  {
    auto frame = std::make_shared<Frame>();
    frame->header = header;
    frame->payload = std::move(payload);
    return post(std::move(frame));
  }

  std::uint64_t id() const override { return id_; }
  std::string peer() const override { return peer_; }
  std::uint64_t dropped() const override { return dropped_.load(); }

  void close()
  {
    net::post(ws_.get_executor(), [self = shared_from_this()] {
      beast::error_code ec;
      beast::get_lowest_layer(self->ws_).socket().close(ec);
    });
  }

private:
  /// The byte count is kept outside the strand, so that a full queue is refused at once,
  /// from the caller's thread, without a handler queued for it.
  bool post(std::shared_ptr<Frame> frame)
  {
    const std::size_t size = frame->size();
    if (!open_.load() || queued_.load() + size > limit_) {
      ++dropped_;
      return false;
    }
    queued_ += size;
    net::post(ws_.get_executor(), [self = shared_from_this(), frame = std::move(frame)]() mutable {
      self->queue_.push_back(std::move(frame));
      if (self->queue_.size() == 1) {
        self->writeNext();
      }
    });
    return true;
  }

  void onRequest(beast::error_code ec)
  {
    if (ec) {
      return;
    }
    if (!websocket::is_upgrade(request_)) {
      respond(http::status::bad_request, "quad bridge: a WebSocket server (subprotocol foxglove.websocket.v1)\n");
      return;
    }
    const std::string offered(request_[http::field::sec_websocket_protocol]);
    if (offered.find(kSubprotocol) == std::string::npos) {
      spdlog::warn("bridge: {} asked for subprotocols '{}', not {}: refused", peer_, offered, kSubprotocol);
      respond(http::status::bad_request, std::string("quad bridge: ask for subprotocol ") + kSubprotocol + "\n");
      return;
    }
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& res) {
      res.set(http::field::sec_websocket_protocol, kSubprotocol);
      res.set(http::field::server, "quad bridge");
    }));
    // The WebSocket stream keeps its own timeouts: the TCP stream's are turned off.
    beast::get_lowest_layer(ws_).expires_never();
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.async_accept(request_, [self = shared_from_this()](beast::error_code e) {
      if (e) {
        return;
      }
      self->open_ = true;
      if (self->callbacks_.opened) {
        self->callbacks_.opened(self);
      }
      self->read();
    });
  }

  void respond(http::status status, std::string body)
  {
    auto res = std::make_shared<http::response<http::string_body>>(status, request_.version());
    res->set(http::field::content_type, "text/plain");
    res->body() = std::move(body);
    res->prepare_payload();
    http::async_write(beast::get_lowest_layer(ws_), *res, [self = shared_from_this(), res](beast::error_code, std::size_t) {
      beast::error_code ec;
      beast::get_lowest_layer(self->ws_).socket().shutdown(tcp::socket::shutdown_send, ec);
    });
  }

  void read()
  {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        self->finish();
        return;
      }
      const auto data = self->buffer_.cdata();
      const std::span<const std::uint8_t> bytes(static_cast<const std::uint8_t*>(data.data()), data.size());
      if (self->ws_.got_text()) {
        if (self->callbacks_.text) {
          self->callbacks_.text(self, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
        }
      } else if (self->callbacks_.binary) {
        self->callbacks_.binary(self, bytes);
      }
      self->buffer_.consume(self->buffer_.size());
      self->read();
    });
  }

  void writeNext()
  {
    const std::shared_ptr<Frame>& f = queue_.front();
    ws_.text(f->text);
    const auto done = [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->queued_ -= self->queue_.front()->size();
      self->queue_.pop_front();
      if (ec) {
        self->finish();
        return;
      }
      if (!self->queue_.empty()) {
        self->writeNext();
      }
    };
    if (f->text) {
      ws_.async_write(net::buffer(f->body), done);
    } else {
      const std::array<net::const_buffer, 2> parts{net::buffer(f->header), net::buffer(*f->payload)};
      ws_.async_write(parts, done);
    }
  }

  void finish()
  {
    if (open_.exchange(false) && callbacks_.closed) {
      callbacks_.closed(shared_from_this());
    }
  }

  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
  std::uint64_t id_;
  std::size_t limit_;
  const ServerCallbacks& callbacks_;
  std::string peer_;
  std::deque<std::shared_ptr<Frame>> queue_;  // on the strand
  std::atomic<std::size_t> queued_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<bool> open_{false};
};

}  // namespace

struct Server::Impl {
  net::io_context io{1};
  tcp::acceptor acceptor{io};
  std::size_t limit = 0;
  ServerCallbacks callbacks;
  std::uint64_t next_id = 1;
  std::mutex mutex;
  std::vector<std::weak_ptr<Connection>> connections;
  std::thread thread;

  void accept()
  {
    acceptor.async_accept(net::make_strand(io), [this](beast::error_code ec, tcp::socket socket) {
      if (ec) {
        return;  // the acceptor closed
      }
      auto c = std::make_shared<Connection>(std::move(socket), next_id++, limit, callbacks);
      {
        std::lock_guard lock(mutex);
        connections.push_back(c);
      }
      c->start();
      accept();
    });
  }
};

Server::Server(const std::string& address, std::uint16_t port, std::size_t queue_limit_bytes, ServerCallbacks callbacks)
    : impl_(std::make_unique<Impl>())
{
  impl_->limit = queue_limit_bytes;
  impl_->callbacks = std::move(callbacks);
  beast::error_code ec;
  const auto ip = net::ip::make_address(address, ec);
  if (ec) {
    throw std::runtime_error("bridge: '" + address + "' is no IP address");
  }
  const tcp::endpoint endpoint(ip, port);
  impl_->acceptor.open(endpoint.protocol(), ec);
  if (!ec) {
    impl_->acceptor.set_option(net::socket_base::reuse_address(true), ec);
    impl_->acceptor.bind(endpoint, ec);
  }
  if (!ec) {
    impl_->acceptor.listen(net::socket_base::max_listen_connections, ec);
  }
  if (ec) {
    throw std::runtime_error("bridge: cannot listen on " + address + ":" + std::to_string(port) + ": " + ec.message());
  }
  impl_->accept();
  impl_->thread = std::thread([this] { impl_->io.run(); });
}

Server::~Server() { stop(); }

std::uint16_t Server::port() const { return impl_->acceptor.local_endpoint().port(); }

void Server::stop()
{
  if (!impl_->thread.joinable()) {
    return;
  }
  net::post(impl_->io, [this] {
    beast::error_code ec;
    impl_->acceptor.close(ec);
    std::lock_guard lock(impl_->mutex);
    for (auto& w : impl_->connections) {
      if (auto c = w.lock()) {
        c->close();
      }
    }
  });
  // Lets the closes run, then ends the loop.
  net::post(impl_->io, [this] { net::post(impl_->io, [this] { impl_->io.stop(); }); });
  impl_->thread.join();
}

}  // namespace quad::bridge
