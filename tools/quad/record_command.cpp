#include "bag_commands.hpp"

#include <signal.h>

#include <atomic>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <set>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "connection.hpp"
#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/common/payload_header.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/node.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "quad/dds/waker.hpp"
#include "quad/introspection/idl.hpp"

namespace quad::tools {

namespace {

std::atomic<int> g_stop{0};

/// One recorded topic.
struct Recorded {
  std::unique_ptr<dds::RawSubscriber> subscriber;
  std::uint16_t channel = 0;
  bag::SequenceAudit audit;
};

/// The recording's file, or files when it is split by size or duration: each part is a
/// whole MCAP file with every schema and channel (same ids in every part).
class RecordingFiles {
public:
  RecordingFiles(const RecordOptions& options, std::map<std::string, std::string> recording)
      : options_(options), recording_(std::move(recording))
  {
    base_ = options.output.empty() ? fmt::format("quad-{:%Y%m%d-%H%M%S}", fmt::localtime(std::time(nullptr)))
                                   : options.output;
    if (base_.ends_with(".mcap")) {
      base_.resize(base_.size() - 5);
    }
    open();
  }

  const std::string& current() const { return name_; }
  int parts() const { return part_ + 1; }
  std::uint64_t messages() const { return messages_; }

  std::uint16_t addSchema(const std::string& type, const std::string& idl)
  {
    schemas_.emplace_back(type, idl);
    return writer_->addSchema(type, "omgidl", idl);
  }

  std::uint16_t addChannel(std::uint16_t schema, const std::string& topic, const std::map<std::string, std::string>& md)
  {
    channels_.push_back({schema, topic, md});
    return writer_->addChannel(schema, topic, "cdr", md);
  }

  void write(std::uint16_t channel, std::uint32_t seq, std::uint64_t log_time, std::uint64_t publish,
             const std::vector<std::uint8_t>& payload)
  {
    const bool by_size = options_.split_size_mb > 0 &&
                         static_cast<double>(writer_->bytesWritten()) >= options_.split_size_mb * 1e6;
    const bool by_time = options_.split_duration_s > 0 && file_start_ != 0 &&
                         static_cast<double>(log_time - file_start_) * 1e-9 >= options_.split_duration_s;
    if (by_size || by_time) {
      writer_->close();
      ++part_;
      open();
      for (const auto& [type, idl] : schemas_) {
        writer_->addSchema(type, "omgidl", idl);
      }
      for (const auto& c : channels_) {
        writer_->addChannel(c.schema, c.topic, "cdr", c.metadata);
      }
    }
    if (file_start_ == 0) {
      file_start_ = log_time;
    }
    writer_->write(channel, seq, log_time, publish, payload.data(), payload.size());
    ++messages_;
  }

  void finish(const std::map<std::string, std::string>& loss)
  {
    writer_->addMetadata(std::string(bag::kLossMetadata), loss);
    writer_->close();
  }

private:
  void open()
  {
    name_ = split() ? fmt::format("{}_{:03d}.mcap", base_, part_) : base_ + ".mcap";
    writer_ = std::make_unique<bag::McapWriter>(name_, options_.chunk_size, options_.compression);
    auto md = recording_;
    md["part"] = std::to_string(part_);
    writer_->addMetadata("quad.recording", md);
    file_start_ = 0;
  }
  bool split() const { return options_.split_size_mb > 0 || options_.split_duration_s > 0; }

  struct ChannelDef {
    std::uint16_t schema;
    std::string topic;
    std::map<std::string, std::string> metadata;
  };
  const RecordOptions& options_;
  std::map<std::string, std::string> recording_;
  std::string base_;
  std::string name_;
  int part_ = 0;
  std::unique_ptr<bag::McapWriter> writer_;
  std::vector<std::pair<std::string, std::string>> schemas_;
  std::vector<ChannelDef> channels_;
  std::uint64_t file_start_ = 0;
  std::uint64_t messages_ = 0;
};

}  // namespace

int record(const RecordOptions& options)
{
  dds::SignalWatcher signals;  // before any thread exists
  signals.onSignal([](int s) { g_stop.store(s); });

  dds::Participant participant(participantOptions("quad_record", options.connection));
  std::unique_ptr<RecordingFiles> files;
  try {
    files = std::make_unique<RecordingFiles>(options, std::map<std::string, std::string>{
        {"domain", std::to_string(participant.options().domain_id)},
        {"started_ns", std::to_string(common::wallTimeNs())},
        {"recorder", "quad record"}});
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "record: %s\n", e.what());
    return 1;
  }
  dds::Waker waker;
  const auto& schema = introspection::quadSchema();
  std::map<std::string, std::uint16_t> schemas;  // type -> schema id
  std::map<std::string, Recorded> recorded;      // topic -> its reader and channel
  std::set<std::string> refused;
  std::fprintf(stderr, "record: domain %d to %s\n", participant.options().domain_id, files->current().c_str());

  // Subscribes with the QoS of the topic's contract (the writers' own, so reliable writers
  // are recorded reliably) and a deep history: a "newest only" topic keeps one sample per
  // instance, and a recorder that falls a few samples behind must not lose them.
  const auto subscribe = [&](const dds::TopicInfo& contract) {
    const std::string topic(contract.name);
    const std::string type(contract.type_name);
    auto qos = participant.readerQos(contract.qos_profile);
    if (qos.history().kind == eprosima::fastdds::dds::KEEP_LAST_HISTORY_QOS && qos.history().depth < 4096) {
      qos.history().depth = 4096;
      auto& limits = qos.resource_limits();
      if (limits.max_samples_per_instance > 0 && limits.max_samples_per_instance < 4096) {
        limits.max_samples_per_instance = 4096;
      }
      const std::int32_t needed = limits.max_samples_per_instance * std::max(1, limits.max_instances);
      if (limits.max_samples > 0 && limits.max_samples < needed) {
        limits.max_samples = needed;
      }
    }
    std::unique_ptr<dds::RawSubscriber> subscriber;
    try {
      subscriber = std::make_unique<dds::RawSubscriber>(participant, contract, &waker, qos);
    } catch (const std::exception& ex) {
      refused.insert(topic);
      std::fprintf(stderr, "record: not recording %s: %s\n", topic.c_str(), ex.what());
      return;
    }
    if (!schemas.contains(type)) {
      schemas[type] = files->addSchema(type, schema.flattenedIdl(type));
    }
    Recorded& r = recorded[topic];
    r.subscriber = std::move(subscriber);
    r.channel = files->addChannel(
        schemas[type], topic,
        {{"qos_profile", std::string(contract.qos_profile)},
         {"reliable", qos.reliability().kind == eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS ? "true" : "false"},
         {"transient_local", qos.durability().kind != eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS ? "true" : "false"},
         {"rate_hz", fmt::format("{}", contract.rate_hz)}});
  };
  // Topics named outright are subscribed to at once, so that no first sample is missed.
  for (const auto& t : options.topics) {
    const auto contract = dds::topics::find(t);
    if (contract && t.find_first_of("*?[") == std::string::npos && !matchesAnyGlob(t, options.exclude)) {
      subscribe(*contract);
    }
  }

  const std::int64_t start = common::steadyTimeNs();
  std::int64_t next_discovery = 0;
  std::int64_t next_progress = start + common::kNanosecondsPerSecond;
  std::uint64_t bytes = 0;
  dds::RawSample sample;  // one buffer for every take: a 1 MiB payload is not allocated anew each time
  // Writes every sample the readers hold.
  const auto takeAll = [&] {
    for (auto& [topic, r] : recorded) {
      std::uint64_t writer_id = 0;
      while (r.subscriber->take(sample, writer_id)) {
        const auto log_time = static_cast<std::uint64_t>(common::wallTimeNs());
        const auto header = common::payloadHeader(sample.payload);
        const std::uint64_t publish = header && header->publish_ns > 0 ? static_cast<std::uint64_t>(header->publish_ns)
                                                                        : log_time;
        if (header) {
          r.audit.add(writer_id, header->seq);
        }
        files->write(r.channel, header ? static_cast<std::uint32_t>(header->seq) : 0, log_time, publish,
                     sample.payload);
        bytes += sample.payload.size();
      }
    }
  };
  int code = 0;
  try {
    while (g_stop.load() == 0) {
      const std::int64_t now = common::steadyTimeNs();
      if (options.duration_s > 0 && now - start >= common::toNanoseconds(options.duration_s)) {
        break;
      }
      if (now >= next_discovery) {
        // Subscribe to every selected topic a writer appeared on, with the QoS of its
        // contract (the writers' own, so reliable writers are recorded reliably).
        for (const auto& e : participant.remoteEndpoints()) {
          if (!e.writer || recorded.contains(e.topic) || refused.contains(e.topic)) {
            continue;
          }
          if ((!options.topics.empty() && !matchesAnyGlob(e.topic, options.topics)) || matchesAnyGlob(e.topic, options.exclude)) {
            continue;
          }
          const auto contract = dds::topics::find(e.topic);
          if (!contract || contract->type_name != e.type_name) {
            refused.insert(e.topic);
            std::fprintf(stderr, "record: not recording %s (type %s): %s\n", e.topic.c_str(), e.type_name.c_str(),
                         contract ? "its type differs from the contract's" : "no quad topic contract names it");
            continue;
          }
          subscribe(*contract);
        }
        next_discovery = now + 200'000'000;
      }
      takeAll();
      if (now >= next_progress) {
        if (!options.quiet) {
          const double seconds = common::toSeconds(now - start);
          std::fprintf(stderr, "\rrecord: %zu topics, %llu messages, %.1f MB, %.0f msg/s   ", recorded.size(),
                       static_cast<unsigned long long>(files->messages()), static_cast<double>(bytes) / 1e6,
                       static_cast<double>(files->messages()) / std::max(seconds, 1e-9));
        }
        next_progress = now + common::kNanosecondsPerSecond;  // also quiet: it bounds the wait below
      }
      waker.waitUntil(std::min(next_discovery, next_progress));
    }
    takeAll();  // on a stop, what the readers already hold is written, not dropped
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "\nrecord: %s: stopping\n", e.what());
    code = 1;
  }
  // Loss figures of the recording, for quad bag info.
  std::map<std::string, std::string> loss;
  for (const auto& [topic, r] : recorded) {
    loss[topic] = bag::toText(r.audit.figures(), r.audit.writers());
  }
  try {
    files->finish(loss);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "\nrecord: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "\nrecord: %llu messages on %zu topics in %s%s\n",
               static_cast<unsigned long long>(files->messages()), recorded.size(), files->current().c_str(),
               files->parts() > 1 ? fmt::format(" (the last of {} parts)", files->parts()).c_str() : "");
  return code;
}

}  // namespace quad::tools
