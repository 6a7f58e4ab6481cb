// SPDX-License-Identifier: BSD-3-Clause
// quad replay RECORDING --inputs-of MODULE --compare: the module in the loop of its recorded
// inputs, in lockstep, and what it writes compared with what it wrote in the run.
#include "quad/replay/replay.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "quad/bag/compare.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/bag/rounds.hpp"
#include "quad/common/payload_header.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/environment.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "quad/dds/waker.hpp"
#include "quad/launch/manifest.hpp"
#include "quad/process/spawn.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"

namespace quad::tools {

namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kClockResendNs = 20'000'000;  // as a waiting plant resends its clock
constexpr std::int64_t kMatchSettleNs = 500'000'000;
constexpr std::int64_t kDrainNs = 500'000'000;       // outputs still on their way at the end

/// Cannot run: said on standard error, exit status 2.
struct ReplayError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The command line the run started `module` with (run.json), ${run_state} replaced by
/// `state_dir`, then the caller's --set entries.
std::vector<std::string> moduleCommand(const fs::path& run_json, const std::string& module, const fs::path& state_dir,
                                       const std::vector<std::string>& sets)
{
  std::ifstream in(run_json);
  if (!in) {
    throw ReplayError(fmt::format("{}: cannot read the run's record (give the run's folder with --run)", run_json.string()));
  }
  const auto record = nlohmann::json::parse(in, nullptr, false);
  if (record.is_discarded() || !record.contains("modules") || !record["modules"].is_object()) {
    throw ReplayError(fmt::format("{}: not a run record: no 'modules' object", run_json.string()));
  }
  for (const auto& [name, m] : record["modules"].items()) {
    // A module of its own, or one a container hosted (the command its own program takes).
    const bool hosted = m.contains("hosted") && m["hosted"].is_object() && m["hosted"].contains(module);
    if (m.value("kind", "") != module && !hosted) {
      continue;
    }
    const auto& command = hosted ? m["hosted"][module] : m["command"];
    const std::string key = hosted ? "modules." + name + ".hosted." + module : "modules." + name + ".command";
    if (!command.is_array() || command.empty()) {
      throw ReplayError(fmt::format("{}: {}: missing: the run did not record how it started {}", run_json.string(), key,
                                    module));
    }
    std::vector<std::string> argv;
    for (const auto& a : command) {
      argv.push_back(launch::withRunState(a.get<std::string>(), state_dir));
    }
    for (const auto& s : sets) {
      argv.insert(argv.end(), {"--set", s});
    }
    return argv;
  }
  throw ReplayError(fmt::format("{}: the run started no {} module", run_json.string(), module));
}

/// The module as a child process, its output kept in a log file.
class ModuleProcess {
public:
  ModuleProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env, fs::path log)
      : log_path_(std::move(log)), log_(log_path_), child_(argv, env)
  {
  }

  /// Keeps what it wrote; throws when it ended.
  void check()
  {
    drain();
    if (const auto status = child_.poll()) {
      drain();
      throw ReplayError(fmt::format("the module ended ({}); its output: {}", process::describeStatus(*status),
                                    log_path_.string()));
    }
  }

  void stop()
  {
    child_.signal(SIGTERM);
    const std::int64_t deadline = common::steadyTimeNs() + 5 * common::kNanosecondsPerSecond;
    while (!child_.poll() && common::steadyTimeNs() < deadline) {
      drain();
      usleep(10'000);
    }
    drain();
  }

private:
  void drain()
  {
    std::string out;
    child_.readOutput(out);
    log_ << out;
    log_.flush();
  }

  fs::path log_path_;
  std::ofstream log_;
  process::Spawned child_;
};

/// What the module writes, as messages on the recording's channels.
class Outputs {
public:
  Outputs(dds::Participant& participant, const bag::McapContents& c, const std::string& module, dds::Waker* waker)
  {
    for (const auto& ch : c.channels) {
      const auto contract = dds::topics::find(ch.topic);
      if (!contract || dds::toString(contract->owner) != module || !dds::topics::isSimPaced(ch.topic) ||
          channels_.contains(ch.topic)) {
        continue;
      }
      channels_[ch.topic] = ch.id;
      readers_.push_back({ch.id, std::make_unique<dds::RawSubscriber>(
                                     participant, *contract, waker,
                                     dds::withDepth(participant.readerQos(contract->qos_profile), 4096))});
    }
  }

  bool empty() const { return readers_.empty(); }
  bool allMatched() const
  {
    return std::all_of(readers_.begin(), readers_.end(), [](const auto& r) { return r.second->matchedWriters() > 0; });
  }
  bool owns(const std::string& topic) const { return channels_.contains(topic); }

  /// Takes what arrived; the newest stamp on `topic` is kept for newestStamp().
  void collect()
  {
    for (auto& [channel, reader] : readers_) {
      while (reader->take(sample_)) {
        if (const auto header = common::payloadHeader(sample_.payload)) {
          newest_[channel] = std::max(newest_[channel], header->stamp_ns);
        }
        messages_.push_back({channel, 0, ++log_time_, 0, sample_.payload});
      }
    }
  }

  std::int64_t newestStamp(const std::string& topic) const
  {
    const auto ch = channels_.find(topic);
    const auto it = ch == channels_.end() ? newest_.end() : newest_.find(ch->second);
    return it == newest_.end() ? -1 : it->second;
  }

  std::vector<bag::Message> take() { return std::move(messages_); }

private:
  std::map<std::string, std::uint16_t> channels_;
  std::vector<std::pair<std::uint16_t, std::unique_ptr<dds::RawSubscriber>>> readers_;
  std::map<std::uint16_t, std::int64_t> newest_;
  std::vector<bag::Message> messages_;
  dds::RawSample sample_;
  std::uint64_t log_time_ = 0;
};

bool comparable(const std::string& module) { return module == "planning" || module == "mapping" || module == "control"; }

int run(const ReplayOptions& options)
{
  const std::string& module = options.inputs_of;
  if (!comparable(module)) {
    throw ReplayError(fmt::format("--compare works for planning, mapping and control, not '{}'", module));
  }
  bag::McapContents c;
  try {
    c = bag::readMcap(options.file);
  } catch (const bag::BagError& e) {
    throw ReplayError(e.what());
  }
  const std::string clock_topic(dds::topics::kSimClock.info.name);
  // The module's inputs: what others wrote and it may read, paced by sim time; the map's
  // snapshots too (a planner joining reads one).
  const auto is_input = [&](const std::string& topic) {
    const auto contract = dds::topics::find(topic);
    return contract && dds::toString(contract->owner) != module && topic != clock_topic &&
           (dds::topics::isSimPaced(topic) || topic == dds::topics::kMapSnapshot.info.name);
  };
  std::vector<bag::Round> rounds;
  try {
    rounds = bag::lockstepRounds(c, clock_topic, is_input);
  } catch (const bag::BagError& e) {
    throw ReplayError(options.file + ": " + e.what());
  }
  if (rounds.empty()) {
    throw ReplayError(fmt::format("{}: no {} samples: not a lockstep recording", options.file, clock_topic));
  }
  if (rounds.front().sim_ns > 0) {
    // The module would start from what it read before then, which the recording lacks.
    throw ReplayError(fmt::format("{}: its first {} sample is at sim time {:.3f} s, not 0: the recording missed the "
                                  "run's start, and {} cannot be driven from the middle of a run",
                                  options.file, clock_topic, common::toSeconds(rounds.front().sim_ns), module));
  }
  const fs::path run_dir = options.run_dir.empty() ? fs::absolute(options.file).parent_path() : fs::path(options.run_dir);
  const fs::path work = fs::temp_directory_path() / fmt::format("quad_replay_{}_{}", module, getpid());
  fs::remove_all(work);
  fs::create_directories(work / "state");
  const auto argv = moduleCommand(run_dir / "run.json", module, work / "state", options.sets);

  runtime::SignalWatcher signals;
  dds::Participant participant(topic::participantOptions("quad_replay", options.connection));
  dds::Waker waker;
  std::map<std::uint16_t, std::unique_ptr<dds::RawPublisher>> publishers;  // by input channel
  for (const auto& ch : c.channels) {
    if (is_input(ch.topic)) {
      publishers[ch.id] = std::make_unique<dds::RawPublisher>(participant, *dds::topics::find(ch.topic));
    }
  }
  dds::RawPublisher clock(participant, dds::topics::kSimClock.info);
  Outputs outputs(participant, c, module, &waker);
  if (outputs.empty()) {
    throw ReplayError(fmt::format("{}: holds nothing {} wrote to compare with", options.file, module));
  }
  std::unique_ptr<runtime::LockstepBarrier> barrier;
  if (module != "control") {
    barrier = std::make_unique<runtime::LockstepBarrier>(participant, std::vector<std::string>{module}, &waker);
  }

  ModuleProcess child(argv,
                      {{dds::environment::kDomainId, std::to_string(participant.options().domain_id)},
                       {dds::environment::kLockstep, "1"}},
                      work / (module + ".log"));
  std::fprintf(stderr, "replay: %s started alone (output in %s); %zu rounds to drive\n", module.c_str(),
               (work / (module + ".log")).c_str(), rounds.size());

  // Its readers and writers matched ours, and no more come for a while: a sample written
  // before a reader matched would be lost to it.
  const double match_s = std::max(options.wait_match_s, 20.0);  // the module starts up first
  const std::int64_t match_deadline = common::steadyTimeNs() + common::toNanoseconds(match_s);
  std::int64_t settled_since = common::steadyTimeNs();
  std::map<std::uint16_t, int> matched;
  while (signals.received() == 0) {
    child.check();
    std::map<std::uint16_t, int> now;
    for (const auto& [id, p] : publishers) {
      now[id] = p->matchedReaders();
    }
    now[0xffff] = clock.matchedReaders();
    if (now != matched) {
      matched = now;
      settled_since = common::steadyTimeNs();
    }
    const bool ready = outputs.allMatched() && clock.matchedReaders() > 0 &&
                       common::steadyTimeNs() - settled_since >= kMatchSettleNs;
    if (ready) {
      break;
    }
    if (common::steadyTimeNs() >= match_deadline) {
      throw ReplayError(fmt::format("{} did not match the replay's readers and writers within {:g} s", module, match_s));
    }
    waker.waitUntil(common::steadyTimeNs() + 10'000'000);
  }

  // Past an input the recorder lost, the module would wait for it, or go on without what it had.
  // Only what the module reads counts: the topics whose writers here matched its readers.
  std::set<std::string> read;
  for (const auto& ch : c.channels) {
    if (const auto p = publishers.find(ch.id); p != publishers.end() && p->second->matchedReaders() > 0) {
      read.insert(ch.topic);
    }
  }
  if (const auto lost = bag::firstLostInput(c, [&](const std::string& topic) { return read.contains(topic); })) {
    std::erase_if(rounds, [&](const bag::Round& r) { return r.sim_ns > lost->last_whole_ns; });
    std::fprintf(stderr, "replay: the recording lost a sample of %s after t = %.3f s (its loss figures): %s is "
                 "driven and compared up to there\n", lost->topic.c_str(), common::toSeconds(lost->last_whole_ns),
                 module.c_str());
    if (rounds.empty()) {
      throw ReplayError(fmt::format("{}: lost {} from its start: nothing to drive", options.file, lost->topic));
    }
  }

  // Round by round, as the plant's lockstep: the inputs up to the clock's time, the clock,
  // then wait until the module finished that time (its report, or the controller's command
  // answering the state of that time).
  const auto done = [&](const bag::Round& r) {
    if (barrier) {
      return barrier->poll(r.sim_ns);
    }
    return !r.state_sent || outputs.newestStamp(std::string(dds::topics::kActuators.info.name)) >= r.sim_ns;
  };
  std::vector<bag::Message> clocks;
  const auto round_timeout = std::chrono::milliseconds(static_cast<std::int64_t>(options.round_timeout_s * 1e3));
  for (const auto& r : rounds) {
    std::set<dds::RawPublisher*> written;
    for (const bag::Message* m : r.inputs) {
      dds::RawSample s{m->data};
      dds::RawPublisher* p = publishers.at(m->channel_id).get();
      p->write(s);
      written.insert(p);
    }
    // What the round's inputs on reliable topics (a path, a goal, a map update) were in the
    // module's hands before anything of the next round: across writers DDS keeps no order.
    for (dds::RawPublisher* p : written) {
      if (!p->waitForAcknowledgments(round_timeout)) {
        throw ReplayError(fmt::format("{} did not take {} at sim time {:.3f} s within {:g} s", module, p->info().name,
                                      common::toSeconds(r.sim_ns), options.round_timeout_s));
      }
    }
    dds::RawSample tick{r.clock->data};
    clock.write(tick);
    clocks.push_back(*r.clock);
    const std::int64_t round_start = common::steadyTimeNs();
    std::int64_t resend = round_start + kClockResendNs;
    while (true) {
      outputs.collect();
      if (done(r)) {
        break;
      }
      if (signals.received() != 0) {
        throw ReplayError("stopped");
      }
      child.check();
      const std::int64_t now = common::steadyTimeNs();
      if (now - round_start >= common::toNanoseconds(options.round_timeout_s)) {
        throw ReplayError(fmt::format("{} did not finish sim time {:.3f} s within {:g} s", module,
                                      common::toSeconds(r.sim_ns), options.round_timeout_s));
      }
      if (now >= resend) {
        clock.write(tick);  // a clock sample lost would stall the round for good
        resend = now + kClockResendNs;
      }
      waker.waitUntil(std::min(resend, now + 10'000'000));
    }
  }
  const std::int64_t drain_until = common::steadyTimeNs() + kDrainNs;
  while (common::steadyTimeNs() < drain_until) {
    outputs.collect();
    waker.waitUntil(std::min(drain_until, common::steadyTimeNs() + 10'000'000));
  }
  child.stop();
  outputs.collect();

  // The replay's side as a recording: the module's outputs and the clock it was driven by.
  bag::McapContents replayed;
  replayed.schemas = c.schemas;
  replayed.channels = c.channels;
  replayed.messages = outputs.take();
  replayed.messages.insert(replayed.messages.end(), clocks.begin(), clocks.end());
  const bag::Comparison result = bag::compareRecordings(
      c, replayed, simPacedComparison([&](const std::string& topic) { return outputs.owns(topic); }));
  printComparison(result, options.json);
  if (result.differences.empty()) {
    fs::remove_all(work);
    return 0;
  }
  std::fprintf(stderr, "replay: the module's output is kept in %s\n", (work / (module + ".log")).c_str());
  return 1;
}

}  // namespace

int replayCompare(const ReplayOptions& options)
{
  try {
    return run(options);
  } catch (const ReplayError& e) {
    std::fprintf(stderr, "replay: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "replay: %s\n", e.what());
  }
  return 2;
}

}  // namespace quad::tools
