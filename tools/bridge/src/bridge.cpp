// SPDX-License-Identifier: BSD-3-Clause
#include "quad/bridge/bridge.hpp"

#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "quad/common/time.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "quad/dds/waker.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"
#include "server.hpp"

namespace quad::bridge {

namespace {

using ClientPtr = std::shared_ptr<Client>;

/// A topic the bridge serves: its channel, its reader once a client subscribed, and the
/// clients subscribed with their subscription ids.
struct Served {
  dds::TopicInfo contract;
  Channel channel;
  bool latched = false;  // transient local: a late subscriber gets the newest sample
  std::unique_ptr<dds::RawSubscriber> reader;
  SharedBytes newest;
  std::map<std::uint64_t, std::pair<ClientPtr, std::uint32_t>> subscribers;  // client id -> (client, subscription)
};

/// What one client publishes: its channel ids to the operator topics they name.
struct Publishing {
  std::map<std::uint32_t, const dds::TopicInfo*> channels;
};

class Bridge {
public:
  Bridge(const BridgeOptions& options) : options_(options), participant_(topic::participantOptions("quad_bridge", options.connection))
  {
    const auto& schema = introspection::quadSchema();
    std::uint32_t id = 1;
    for (const auto& t : dds::topics::kAll) {
      Served s;
      s.contract = t;
      s.channel = {id++, std::string(t.name), std::string(t.type_name), schema.flattenedIdl(t.type_name)};
      s.latched = participant_.readerQos(t).durability().kind != eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS;
      served_.push_back(std::move(s));
      if (t.owner == dds::Owner::kOperator) {
        publishable_[std::string(t.name)] = t;
      }
    }
  }

  int run(const std::atomic<int>& stop)
  {
    ServerCallbacks callbacks;
    callbacks.opened = [this](const ClientPtr& c) { opened(c); };
    callbacks.text = [this](const ClientPtr& c, std::string_view text) { onText(c, text); };
    callbacks.binary = [this](const ClientPtr& c, std::span<const std::uint8_t> bytes) { onBinary(c, bytes); };
    callbacks.closed = [this](const ClientPtr& c) { closed(c); };
    std::optional<Server> server;
    try {
      server.emplace(options_.address, options_.port, options_.client_queue_bytes, std::move(callbacks));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 1;
    }
    std::printf("bridge: listening on ws://%s:%u (domain %d, %zu topics)\n", options_.address.c_str(), server->port(),
                participant_.options().domain_id, served_.size());
    std::fflush(stdout);
    dds::RawSample sample;
    std::int64_t next_progress = common::steadyTimeNs() + common::kNanosecondsPerSecond;
    while (stop.load() == 0) {
      waker_.waitUntil(common::steadyTimeNs() + 100'000'000);
      std::lock_guard lock(mutex_);
      for (auto& s : served_) {
        if (!s.reader) {
          continue;
        }
        while (s.reader->take(sample)) {
          auto payload = std::make_shared<const std::vector<std::uint8_t>>(std::move(sample.payload));
          sample.payload = {};
          const auto now = static_cast<std::uint64_t>(common::wallTimeNs());
          for (const auto& [cid, sub] : s.subscribers) {
            sub.first->sendMessage(messageHeader(sub.second, now), payload);
          }
          ++forwarded_;
          if (s.latched) {
            s.newest = std::move(payload);
          }
        }
      }
      if (!options_.quiet && common::steadyTimeNs() >= next_progress) {
        next_progress += common::kNanosecondsPerSecond;
        std::fprintf(stderr, "\rbridge: %zu clients, %llu samples forwarded, %llu published   ", clients_.size(),
                     static_cast<unsigned long long>(forwarded_), static_cast<unsigned long long>(published_));
      }
    }
    if (!options_.quiet) {
      std::fprintf(stderr, "\n");
    }
    server->stop();
    // What each client still connected missed, then the clients go before the server's I/O
    // context does.
    std::lock_guard lock(mutex_);
    std::map<std::uint64_t, ClientPtr> connected;
    for (auto& s : served_) {
      for (const auto& [id, sub] : s.subscribers) {
        connected[id] = sub.first;
      }
      s.subscribers.clear();
    }
    for (const auto& [id, c] : connected) {
      std::printf("bridge: client %s: %llu messages dropped (its queue was full)\n", c->peer().c_str(),
                  static_cast<unsigned long long>(c->dropped()));
    }
    return 0;
  }

private:
  void opened(const ClientPtr& c)
  {
    std::vector<Channel> channels;
    for (const auto& s : served_) {
      channels.push_back(s.channel);
    }
    c->sendText(serverInfo("quad bridge", true, std::to_string(common::wallTimeNs())));
    c->sendText(advertise(channels));
    std::lock_guard lock(mutex_);
    clients_[c->id()] = Publishing{};
  }

  void closed(const ClientPtr& c)
  {
    std::lock_guard lock(mutex_);
    for (auto& s : served_) {
      s.subscribers.erase(c->id());
    }
    clients_.erase(c->id());
    if (c->dropped() > 0) {
      std::printf("bridge: client %s left: %llu messages dropped (its queue was full)\n", c->peer().c_str(),
                  static_cast<unsigned long long>(c->dropped()));
      std::fflush(stdout);
    }
  }

  void onText(const ClientPtr& c, std::string_view text)
  {
    ClientRequest request;
    try {
      request = parseClientText(text);
    } catch (const ProtocolError& e) {
      c->sendText(status(StatusLevel::kError, e.what()));
      return;
    }
    std::lock_guard lock(mutex_);
    if (const auto* s = std::get_if<Subscribe>(&request)) {
      subscribe(c, *s);
    } else if (const auto* u = std::get_if<Unsubscribe>(&request)) {
      for (const auto id : u->subscription_ids) {
        for (auto& served : served_) {
          const auto it = served.subscribers.find(c->id());
          if (it != served.subscribers.end() && it->second.second == id) {
            served.subscribers.erase(it);
          }
        }
      }
    } else if (const auto* a = std::get_if<ClientAdvertise>(&request)) {
      clientAdvertise(c, *a);
    } else if (const auto* d = std::get_if<ClientUnadvertise>(&request)) {
      for (const auto id : d->channel_ids) {
        clients_[c->id()].channels.erase(id);
      }
    } else if (const auto* x = std::get_if<Unsupported>(&request)) {
      c->sendText(status(StatusLevel::kWarning, "op '" + x->op + "' is not served by quad bridge"));
    }
  }

  void subscribe(const ClientPtr& c, const Subscribe& request)
  {
    for (const auto& sub : request.subscriptions) {
      if (sub.channel_id == 0 || sub.channel_id > served_.size()) {
        c->sendText(status(StatusLevel::kError, fmt::format("subscribe: no channel {}", sub.channel_id)));
        continue;
      }
      Served& s = served_[sub.channel_id - 1];
      if (!s.reader) {
        try {
          s.reader = std::make_unique<dds::RawSubscriber>(
              participant_, s.contract, &waker_, dds::withDepth(participant_.readerQos(s.contract), 256));
        } catch (const std::exception& e) {
          c->sendText(status(StatusLevel::kError, fmt::format("subscribe: {}: {}", s.channel.topic, e.what())));
          continue;
        }
      }
      s.subscribers[c->id()] = {c, sub.id};
      if (s.newest) {
        c->sendMessage(messageHeader(sub.id, static_cast<std::uint64_t>(common::wallTimeNs())), s.newest);
      }
    }
  }

  void clientAdvertise(const ClientPtr& c, const ClientAdvertise& request)
  {
    for (const auto& ch : request.channels) {
      const auto it = publishable_.find(ch.topic);
      std::string refused;
      if (it == publishable_.end()) {
        std::string names;
        for (const auto& [name, t] : publishable_) {
          names += (names.empty() ? "" : ", ") + name;
        }
        refused = "the stack takes only " + names + " from outside";
      } else if (ch.encoding != "cdr") {
        refused = "encoding '" + ch.encoding + "': only cdr";
      } else if (ch.schema_name != it->second.type_name) {
        refused = "schema '" + ch.schema_name + "': the topic's is " + std::string(it->second.type_name);
      }
      if (!refused.empty()) {
        c->sendText(status(StatusLevel::kError, fmt::format("advertise {}: {}: refused", ch.topic, refused)));
        continue;
      }
      if (!writers_.contains(ch.topic)) {
        writers_[ch.topic] = std::make_unique<dds::RawPublisher>(participant_, it->second);
      }
      clients_[c->id()].channels[ch.id] = &it->second;
    }
  }

  void onBinary(const ClientPtr& c, std::span<const std::uint8_t> bytes)
  {
    ClientMessage m;
    try {
      m = parseClientBinary(bytes);
    } catch (const ProtocolError& e) {
      c->sendText(status(StatusLevel::kError, e.what()));
      return;
    }
    std::lock_guard lock(mutex_);
    const auto& channels = clients_[c->id()].channels;
    const auto it = channels.find(m.channel_id);
    if (it == channels.end()) {
      c->sendText(status(StatusLevel::kError, fmt::format("message on channel {}: not advertised", m.channel_id)));
      return;
    }
    const dds::TopicInfo& t = *it->second;
    const std::string fault = introspection::checkBounds(introspection::quadSchema(), t.type_name, m.payload);
    if (!fault.empty()) {
      c->sendText(status(StatusLevel::kError, fmt::format("{}: a message that does not keep to {}: {}; not published",
                                                          t.name, t.type_name, fault)));
      return;
    }
    dds::RawSample sample;
    sample.payload.assign(m.payload.begin(), m.payload.end());
    if (!writers_.at(std::string(t.name))->write(sample)) {
      c->sendText(status(StatusLevel::kError, fmt::format("{}: the middleware refused the sample", t.name)));
      return;
    }
    ++published_;
  }

  BridgeOptions options_;
  dds::Participant participant_;
  dds::Waker waker_;
  std::mutex mutex_;  // the tables below: the I/O thread and the DDS loop both use them
  std::vector<Served> served_;
  std::map<std::string, dds::TopicInfo> publishable_;
  std::map<std::string, std::unique_ptr<dds::RawPublisher>> writers_;
  std::map<std::uint64_t, Publishing> clients_;
  std::uint64_t forwarded_ = 0;
  std::uint64_t published_ = 0;
};

}  // namespace

int runBridge(const BridgeOptions& options, const std::atomic<int>& stop)
{
  try {
    Bridge bridge(options);
    return bridge.run(stop);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bridge: %s\n", e.what());
    return 1;
  }
}

}  // namespace quad::bridge
