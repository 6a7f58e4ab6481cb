// SPDX-License-Identifier: BSD-3-Clause
#include "quad/record/recorder.hpp"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <thread>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/topic/connection.hpp"
#include "recording_files.hpp"
#include "start_gate.hpp"
#include "quad/common/payload_header.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "quad/dds/waker.hpp"
#include "quad/introspection/idl.hpp"
#include "quad/runtime/node.hpp"

namespace quad::record {

namespace {

/// One recorded topic.
struct Recorded {
  std::unique_ptr<dds::RawSubscriber> subscriber;
  /// Added with its first message: a topic nobody wrote leaves no channel.
  std::optional<std::uint16_t> channel;
  dds::TopicInfo contract;
  std::map<std::string, std::string> channel_metadata;
  bag::SequenceAudit audit;
  bool has_header = true;  ///< a display schema has none: no seq to audit, no publish time
};

/// How long samples gather after one arrives before they are taken. The recorder's thread
/// woke for every sample before, some five times a 4 ms round of the demo, for a process
/// that needs no latency (docs/recording.md).
constexpr std::chrono::milliseconds kGather{10};
}  // namespace

struct Recorder::State {
  State(dds::Participant& p, const RecordOptions& o, dds::Waker* w) : participant(p), options(o), waker(w) {}
  dds::Participant& participant;
  RecordOptions options;
  dds::Waker* waker;
  std::unique_ptr<RecordingFiles> files;
  std::map<std::string, std::uint16_t> schemas;  // type -> schema id
  std::map<std::string, Recorded> recorded;      // topic -> its reader and channel
  std::set<std::string> refused;
  std::optional<StartGate> start_gate;
  std::int64_t start_ns = common::steadyTimeNs();
  std::int64_t next_discovery_ns = 0;
  std::int64_t next_progress_ns = start_ns + common::kNanosecondsPerSecond;
  std::uint64_t bytes = 0;
  dds::RawSample sample;  // one buffer for every take: a 1 MiB payload is not allocated anew each time
  bool finished = false;
  bool write_failed = false;  // a file refused a write: nothing more goes to it but its end

  void subscribe(const dds::TopicInfo& contract);
  std::uint16_t channelOf(Recorded& r);
  std::size_t topicsWritten() const
  {
    return static_cast<std::size_t>(
        std::count_if(recorded.begin(), recorded.end(), [](const auto& kv) { return kv.second.channel.has_value(); }));
  }
  bool plantMatched() const
  {
    return std::all_of(recorded.begin(), recorded.end(), [](const auto& kv) {
      return kv.second.contract.owner != dds::Owner::kPlant || kv.second.subscriber->matchedWriters() > 0;
    });
  }
  void takeAll();
  void reportRefusedWriters();
};

// Subscribes with the QoS of the topic's contract (the writers' own, so reliable writers are
// recorded reliably) and a deep history: a "newest only" topic keeps one sample per instance,
// and a recorder that falls a few samples behind must not lose them.
void Recorder::State::subscribe(const dds::TopicInfo& contract)
{
  const std::string topic(contract.name);
  const auto qos = dds::withDepth(participant.readerQos(contract.qos_profile), 4096);
  std::unique_ptr<dds::RawSubscriber> subscriber;
  try {
    subscriber = std::make_unique<dds::RawSubscriber>(participant, contract, waker, qos);
  } catch (const std::exception& ex) {
    refused.insert(topic);
    std::fprintf(stderr, "record: not recording %s: %s\n", topic.c_str(), ex.what());
    return;
  }
  Recorded& r = recorded[topic];
  r.subscriber = std::move(subscriber);
  r.has_header = contract.has_header;
  r.contract = contract;
  r.channel_metadata = {
      {"qos_profile", std::string(contract.qos_profile)},
      {"reliable", qos.reliability().kind == eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS ? "true" : "false"},
      {"transient_local", qos.durability().kind != eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS ? "true" : "false"},
      {"rate_hz", fmt::format("{}", contract.rate_hz)}};
}

std::uint16_t Recorder::State::channelOf(Recorded& r)
{
  if (!r.channel) {
    const std::string type(r.contract.type_name);
    if (!schemas.contains(type)) {
      schemas[type] = files->addSchema(type, introspection::quadSchema().flattenedIdl(type));
    }
    r.channel = files->addChannel(schemas[type], std::string(r.contract.name), r.channel_metadata);
  }
  return *r.channel;
}

// Writes every sample the readers hold.
void Recorder::State::takeAll()
{
  for (auto& [topic, r] : recorded) {
    std::uint64_t writer_id = 0;
    std::int64_t received_ns = 0;
    while (r.subscriber->take(sample, writer_id, received_ns)) {
      // The middleware's time of reception: the take comes up to kGather later.
      const auto log_time = static_cast<std::uint64_t>(received_ns > 0 ? received_ns : common::wallTimeNs());
      if (r.has_header && !topic::selectedVehicle(options.connection, sample.payload)) {
        continue;  // another vehicle's (--vehicle)
      }
      const auto header = r.has_header ? common::payloadHeader(sample.payload) : std::nullopt;
      const std::uint64_t publish =
          header && header->publish_ns > 0 ? static_cast<std::uint64_t>(header->publish_ns) : log_time;
      if (header) {
        r.audit.add(writer_id, header->vehicle_id, header->seq);
        if (start_gate && r.contract.name == dds::topics::kSimClock.info.name) {
          start_gate->clockSeen(header->vehicle_id, header->stamp_ns);
        }
      }
      files->write(channelOf(r), header ? static_cast<std::uint32_t>(header->seq) : 0, log_time, publish,
                   sample.payload);
      bytes += sample.payload.size();
    }
  }
}

// Writers the recording leaves out, said once each: on a topic no contract names, or with
// another type than the contract's (every contract's topic is subscribed at the start).
void Recorder::State::reportRefusedWriters()
{
  for (const auto& e : participant.remoteEndpoints()) {
    if (!e.writer || refused.contains(e.topic) ||
        (!options.topics.empty() && !topic::matchesAnyGlob(e.topic, options.topics)) ||
        topic::matchesAnyGlob(e.topic, options.exclude)) {
      continue;
    }
    const auto contract = dds::topics::find(e.topic);
    if (!contract || contract->type_name != e.type_name) {
      refused.insert(e.topic);
      std::fprintf(stderr, "record: not recording %s (type %s): %s\n", e.topic.c_str(), e.type_name.c_str(),
                   contract ? "its type differs from the contract's" : "no quad topic contract names it");
    }
  }
}

Recorder::Recorder(dds::Participant& participant, const RecordOptions& options, dds::Waker* waker)
    : s_(std::make_unique<State>(participant, options, waker))
{
  // The files keep the options: the recorder's own copy, which lives as long as they do.
  s_->files = std::make_unique<RecordingFiles>(s_->options, std::map<std::string, std::string>{
      {"domain", std::to_string(participant.options().domain_id)},
      {"started_ns", std::to_string(common::wallTimeNs())},
      {"recorder", "quad record"}});
  std::fprintf(stderr, "record: domain %d to %s\n", participant.options().domain_id, s_->files->current().c_str());
  // Every selected topic of the contracts is subscribed to at once, before any module writes
  // it: a reader made only when discovery shows a writer can match after that writer's first
  // samples (an answer written once, early on) and miss them.
  for (const auto& contract : dds::topics::kAll) {
    const std::string name(contract.name);
    if ((options.topics.empty() || topic::matchesAnyGlob(name, options.topics)) &&
        !topic::matchesAnyGlob(name, options.exclude)) {
      s_->subscribe(contract);
    }
  }
  // In a lockstep run the launcher records, the plant's first round waits for this recorder.
  if (participant.options().lockstep && participant.options().lockstep_recorder) {
    if (s_->recorded.contains(std::string(dds::topics::kSimClock.info.name))) {
      s_->start_gate.emplace(participant);
    } else {
      std::fprintf(stderr, "record: %s is not recorded: the lockstep run's start does not wait for this recorder\n",
                   std::string(dds::topics::kSimClock.info.name).c_str());
    }
  }
}

Recorder::~Recorder() = default;

void Recorder::poll()
{
  if (s_->write_failed) {
    return;
  }
  const std::int64_t now = common::steadyTimeNs();
  if (now >= s_->next_discovery_ns) {
    s_->reportRefusedWriters();
    s_->next_discovery_ns = now + 200'000'000;
  }
  try {
    s_->takeAll();
  } catch (const bag::BagError&) {
    s_->write_failed = true;
    throw;
  }
  if (s_->start_gate && s_->start_gate->waiting()) {
    s_->start_gate->release(s_->plantMatched());
  }
  if (now >= s_->next_progress_ns) {
    if (!s_->options.quiet) {
      const double seconds = common::toSeconds(now - s_->start_ns);
      std::fprintf(stderr, "\rrecord: %zu topics, %llu messages, %.1f MB, %.0f msg/s   ", s_->topicsWritten(),
                   static_cast<unsigned long long>(s_->files->messages()), static_cast<double>(s_->bytes) / 1e6,
                   static_cast<double>(s_->files->messages()) / std::max(seconds, 1e-9));
    }
    s_->next_progress_ns = now + common::kNanosecondsPerSecond;  // also quiet: it bounds the wait
  }
}

std::int64_t Recorder::nextDueNs() const { return std::min(s_->next_discovery_ns, s_->next_progress_ns); }

bool Recorder::finish()
{
  if (s_->finished) {
    return true;
  }
  s_->finished = true;
  bool ok = !s_->write_failed;
  try {
    if (ok) {
      s_->takeAll();  // on a stop, what the readers already hold is written, not dropped
    }
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "\nrecord: %s: stopping\n", e.what());
    ok = false;
  }
  // Loss figures of the recording, for quad bag info (a display schema has no seq to count).
  std::map<std::string, std::string> loss;
  for (const auto& [topic, r] : s_->recorded) {
    if (r.has_header && r.channel) {
      loss[topic] = bag::toText(r.audit.figures(), r.audit.writers());
    }
  }
  try {
    s_->files->finish(loss);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "\nrecord: %s\n", e.what());
    return false;
  }
  std::fprintf(stderr, "\nrecord: %llu messages on %zu topics in %s%s\n",
               static_cast<unsigned long long>(s_->files->messages()), s_->topicsWritten(),
               s_->files->current().c_str(),
               s_->files->parts() > 1 ? fmt::format(" (the last of {} parts)", s_->files->parts()).c_str() : "");
  return ok;
}

int record(const RecordOptions& options, const std::atomic<int>& stop)
{
  dds::Participant participant(topic::participantOptions("quad_record", options.connection));
  dds::Waker waker;
  std::unique_ptr<Recorder> recorder;
  try {
    recorder = std::make_unique<Recorder>(participant, options, &waker);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "record: %s\n", e.what());
    return 1;
  }
  const std::int64_t start = common::steadyTimeNs();
  int code = 0;
  try {
    while (stop.load() == 0) {
      if (options.duration_s > 0 && common::steadyTimeNs() - start >= common::toNanoseconds(options.duration_s)) {
        break;
      }
      recorder->poll();
      // A round's samples come in a burst: gathered for a while after the first, they are
      // taken with one wake-up of this thread instead of one each (every reader holds 4,096).
      if (waker.waitUntil(recorder->nextDueNs()) && stop.load() == 0) {
        std::this_thread::sleep_for(kGather);
      }
    }
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "\nrecord: %s: stopping\n", e.what());
    code = 1;
  }
  return recorder->finish() ? code : 1;
}

}  // namespace quad::record
