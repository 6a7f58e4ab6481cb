// SPDX-License-Identifier: BSD-3-Clause
#include "driver.hpp"

#include <signal.h>

#include <algorithm>
#include <span>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "quad/bag/audit.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/fault_messages.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/fault/judge.hpp"
#include "quad/fault/scenario.hpp"
#include "quad/plant_messages/faults.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"
#include "quad/topic/samples.hpp"

namespace quad::fault {

namespace fs = std::filesystem;
namespace topics = dds::topics;

namespace {

constexpr double kAckTimeoutS = 5.0;  // wall seconds for a module to acknowledge a fault
constexpr int kDeepHistory = 1000;         // samples a reader keeps between the run's ticks

/// The reader QoS of `qos_class` with a history deep enough that no sample is replaced
/// before the next tick takes it.
eprosima::fastdds::dds::DataReaderQos deepReader(dds::Participant& p, std::string_view qos_class)
{
  return dds::withDepth(p.readerQos(qos_class), kDeepHistory);
}

/// `values` with each list field of `lengths` repeated to its length.
nlohmann::ordered_json stretched(nlohmann::ordered_json values, const std::map<std::string, std::size_t>& lengths)
{
  for (const auto& [field, n] : lengths) {
    auto& list = values[field];
    const nlohmann::ordered_json pattern = list;
    list = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < n; ++i) {
      list.push_back(pattern[i % pattern.size()]);
    }
  }
  return values;
}

/// Applies a scenario's steps to a launch::LaunchRun and feeds the Judge with what the stack does.
class FaultDriver : public launch::RunExtension {
public:
  FaultDriver(const Scenario& scenario, fs::path recording)
      : scenario_(scenario), judge_(scenario), recording_(std::move(recording))
  {
  }

  void tick(launch::LaunchRun& run) override
  {
    if (!endpoints_) {
      setUp(run);
    }
    const std::int64_t now = common::steadyTimeNs();
    takeSamples(run, now);
    for (const std::size_t step : judge_.due(t_)) {
      apply(run, step, now);
    }
    publishDue(now);
    clearDue(run);
    checkAcks(now);
    judge_.clock(t_, now);
  }

  bool done() const override { return scenario_.end_s && t_ >= *scenario_.end_s && judge_.settled(); }

  /// Datagram faults still active are cleared while their modules run, so that what each
  /// did reaches the report.
  void ending(launch::LaunchRun& run) override
  {
    if (const auto& by = run.endedBy()) {
      judge_.runEnded(by->module, by->wall_ns);
    }
    if (!endpoints_) {
      return;
    }
    for (const auto& c : clears_) {
      clear(run, c.step);
    }
    clears_.clear();
    for (std::size_t step = 0; step < scenario_.steps.size(); ++step) {
      const Action& a = scenario_.steps[step].action;
      if (a.lasts() && !a.duration_s && judge_.isApplied(step)) {
        clear(run, step);
      }
    }
    const std::int64_t deadline = common::steadyTimeNs() + common::toNanoseconds(kAckTimeoutS);
    while (!allCleared() && common::steadyTimeNs() < deadline && run.service(20)) {
      takeSamples(run, common::steadyTimeNs());
    }
  }

  int finish(launch::LaunchRun& run, int /*code*/) override
  {
    // The endpoints live on the run's participant: gone before it is.
    jobs_.clear();
    injector_.reset();
    endpoints_.reset();
    fault::RunFacts facts;
    if (const auto& s = run.summary()) {
      facts.mission_known = true;
      facts.mission_success = s->success;
      facts.mission_outcome = s->outcome;
      facts.mission_end = std::string(launch::toString(s->end));
      facts.collisions = s->collisions;
      for (const auto& v : s->vehicles) {
        facts.vehicle_missions[v.vehicle_id.value_or(0)] = {v.success, v.outcome};
      }
    }
    facts.run_failure = run.failure();
    facts.actuator_commands = actuator_commands_;
    facts.nonfinite_actuator_commands = nonfinite_actuators_;
    for (const auto& [name, seen] : seen_) {
      facts.module_loss[name] = seen.lost_earlier + seen.lost;
    }
    readRecording(facts, run.observer().participant());
    const auto rows = judge_.finish(facts);
    const std::string table = fault::toTable(scenario_.name, rows);
    std::printf("\n%s", table.c_str());
    std::ofstream(run.logDir() / "fault_report.txt") << table;
    std::ofstream(run.logDir() / "fault_report.json") << fault::toJson(scenario_.name, rows);
    std::fflush(stdout);
    return fault::passed(rows) ? 0 : 1;
  }

private:
  struct Endpoints {
    explicit Endpoints(dds::Participant& p)
        : command(p, topics::kFault),
          events(p, topics::kFaultEvents),
          status(p, topics::kControlStatus, nullptr, deepReader(p, topics::kControlStatus.info.qos_profile)),
          path(p, topics::kPath, nullptr, deepReader(p, topics::kPath.info.qos_profile)),
          actuators(p, topics::kActuators, nullptr, deepReader(p, topics::kActuators.info.qos_profile)),
          heartbeat(p, topics::kHeartbeat, nullptr, deepReader(p, topics::kHeartbeat.info.qos_profile)),
          sim_events(p, topics::kSimEvents, nullptr, deepReader(p, topics::kSimEvents.info.qos_profile)),
          fault_events(p, topics::kFaultEvents, nullptr, deepReader(p, topics::kFaultEvents.info.qos_profile)),
          estimate(p, topics::kEstimatedState, nullptr, deepReader(p, topics::kEstimatedState.info.qos_profile))
    {
    }
    dds::Publisher<msg::FaultCommand> command;
    dds::Publisher<msg::SimEvent> events;
    dds::Subscriber<msg::ControlStatus> status;
    dds::Subscriber<msg::Path> path;
    dds::Subscriber<msg::ActuatorCommand> actuators;
    dds::Subscriber<msg::Heartbeat> heartbeat;
    dds::Subscriber<msg::SimEvent> sim_events;
    dds::Subscriber<msg::SimEvent> fault_events;  // our own, and the modules' fault layers'
    // Its counts of outliers: the newest sample says them all, but the first to grow says when.
    dds::Subscriber<msg::EstimatedState> estimate;
  };
  struct PublishJob {
    dds::TopicInfo info;
    nlohmann::ordered_json values;
    std::unique_ptr<dds::RawPublisher> writer;
    bool active = false;
    int sent = 0;
    std::int64_t next_ns = 0;
  };
  struct ModuleSeen {
    int pid = 0;
    std::uint64_t errors = 0;
    std::uint64_t lost = 0;          // this process's
    std::uint64_t lost_earlier = 0;  // the module's earlier processes'
  };

  void setUp(launch::LaunchRun& run)
  {
    endpoints_ = std::make_unique<Endpoints>(run.observer().participant());
    // Bad inputs go out raw, from a participant of their own (one participant cannot hold
    // typed and raw endpoints of a type). Their writers exist from the start, so readers
    // have matched them when the step comes (a volatile reader drops what an unmatched
    // writer sent).
    for (std::size_t i = 0; i < scenario_.steps.size(); ++i) {
      const Action& a = scenario_.steps[i].action;
      if (a.kind != Action::Kind::kPublish) {
        continue;
      }
      if (!injector_) {
        dds::intraprocessDeliveryOff();  // two participants in one process: see its comment
        injector_ = std::make_unique<dds::Participant>(dds::optionsFromEnvironment("quad_fault"));
      }
      PublishJob job{topic::requireTopic(a.topic), stretched(topic::sampleValues(topic::requireTopic(a.topic), a.values), a.lengths),
                     nullptr};
      job.writer = std::make_unique<dds::RawPublisher>(*injector_, job.info);
      jobs_.emplace(i, std::move(job));
    }
    for (const auto* m : run.manifest().hostedModules()) {
      kinds_.emplace(m->name, m->kind);
      vehicle_of_.emplace(m->name, m->vehicle.value_or(0));
    }
    // The vehicle the expectations watch: the scenario's, else the run's first.
    watched_ = scenario_.vehicle.value_or(run.observer().vehicleId(0));
    for (std::size_t i = 0; i < run.observer().vehicleCount(); ++i) {
      if (run.observer().vehicleId(i) == watched_) {
        watched_index_ = i;
      }
    }
  }

  /// The manifest's module a heartbeat comes from: the only one of its kind, else by pid.
  std::string moduleOf(launch::LaunchRun& run, const msg::Heartbeat& hb) const
  {
    std::string found;
    int candidates = 0;
    for (const auto& [name, kind] : kinds_) {
      if (kind == hb.module_name().to_string()) {
        ++candidates;
        found = name;
      }
    }
    if (candidates <= 1) {
      return found;
    }
    for (const auto& [name, kind] : kinds_) {
      if (kind == hb.module_name().to_string() && run.pid(name) == hb.pid()) {
        return name;
      }
    }
    return "";
  }

  void takeSamples(launch::LaunchRun& run, std::int64_t now)
  {
    // Sim time is the plant's clock, as the launcher's observer follows it (a state could
    // be a bad input stamped anywhere).
    t_ = common::toSeconds(run.observer().simTimeNs());
    p_W_ = dds::toMessage(run.observer().position(watched_index_));
    if (run.observer().lastStateNs() > 0) {
      judge_.altitude(t_, run.observer().position(watched_index_).z());  // sampled at the tick's rate
    }
    const std::span<const std::uint32_t> watched(&watched_, 1);
    // Paths before modes: a HOVER measured from the last path must not miss one stamped before it.
    for (const auto& p : endpoints_->path.takeAll(watched)) {
      const bool flyable = p.status() == msg::PLAN_OK && !p.waypoints_W().empty() &&
                           std::all_of(p.waypoints_W().begin(), p.waypoints_W().end(),
                                       [](const msg::Vector3& w) { return dds::toVector(w).allFinite(); });
      if (flyable) {
        judge_.path(common::toSeconds(p.header().stamp_ns()));
      }
    }
    for (const auto& s : endpoints_->status.takeAll(watched)) {
      judge_.mode(common::toSeconds(s.header().stamp_ns()), launch::controlModeName(static_cast<int>(s.mode())));
    }
    for (const auto& e : endpoints_->estimate.takeAll(watched)) {
      const double t = common::toSeconds(e.header().stamp_ns());
      const std::array<std::pair<const char*, std::uint64_t>, 3> counts = {
          {{"position", e.position_rejected()}, {"baro", e.baro_rejected()}, {"mag", e.mag_rejected()}}};
      for (std::size_t i = 0; i < counts.size(); ++i) {
        if (counts[i].second > outliers_[i]) {
          outliers_[i] = counts[i].second;
          judge_.outliers(counts[i].first, t);
        }
      }
    }
    // Every vehicle's commands, events and modules'.
    while (const auto a = endpoints_->actuators.takeAnyVehicle()) {
      ++actuator_commands_;
      for (const double w : a->rotor_speed()) {
        if (!std::isfinite(w)) {
          ++nonfinite_actuators_;
          break;
        }
      }
    }
    std::uint64_t writer = 0;
    while (const auto hb = endpoints_->heartbeat.takeAnyVehicle(&writer)) {
      const std::string name = moduleOf(run, *hb);
      if (name.empty()) {
        continue;
      }
      writers_[writer] = name;
      auto [it, first] = seen_.try_emplace(name, ModuleSeen{hb->pid(), hb->errors()});
      if (!first && it->second.pid != hb->pid()) {
        judge_.back(name, now);
        it->second = {hb->pid(), hb->errors(), 0, it->second.lost_earlier + it->second.lost};
      } else if (hb->errors() > it->second.errors) {
        judge_.rejected(name, now);
        it->second.errors = hb->errors();
      }
      it->second.lost = hb->samples_lost();
    }
    for (const auto& change : endpoints_->heartbeat.takeLivelinessChanges()) {
      const auto it = writers_.find(change.writer);
      if (!change.alive && it != writers_.end()) {
        judge_.lost(it->second, change.steady_ns);
      }
    }
    while (const auto e = endpoints_->sim_events.takeAnyVehicle()) {
      // The plant stamps its acknowledgement with the sim time the fault took effect.
      takeAck(*e, common::toSeconds(e->header().stamp_ns()), now);
    }
    while (const auto fault_event = endpoints_->fault_events.takeAnyVehicle()) {
      const msg::SimEvent& e = *fault_event;
      if (e.kind() == msg::SIM_EVENT_FAULT_CLEARED && e.subject_id() >= fault::kDatagramIdBase) {
        const auto step = static_cast<std::size_t>(e.subject_id() / fault::kDatagramIdBase) - 1;
        if (step < scenario_.steps.size()) {
          noteCleared(step, e.detail().to_string());
        }
      }
      // A fault layer has no clock of its own: it took effect by the time we hear of it.
      takeAck(e, t_, now);
    }
  }

  /// Each of a step's faults that lasts acknowledges its end once.
  static std::size_t clearsOf(const Action& a) { return a.kind == Action::Kind::kDds ? a.datagrams.size() : 1; }

  void noteCleared(std::size_t step, const std::string& detail)
  {
    cleared_[step].push_back(detail);
    if (cleared_[step].size() == clearsOf(scenario_.steps[step].action)) {
      judge_.cleared(step, t_, fmt::format("{}", fmt::join(cleared_[step], "; ")));
    }
  }

  /// An acknowledgement of a fault we asked a module for (others are ignored).
  void takeAck(const msg::SimEvent& e, double t, std::int64_t now)
  {
    const auto it = acks_.find(static_cast<std::uint32_t>(e.subject_id()));
    if (it == acks_.end()) {
      return;
    }
    const std::size_t step = it->second.step;
    if (e.kind() == msg::SIM_EVENT_FAULT_APPLIED) {
      acks_.erase(it);
      const bool all = std::none_of(acks_.begin(), acks_.end(), [&](const auto& a) { return a.second.step == step; });
      if (all) {
        judge_.applied(step, t, now, "acknowledged by " + scenario_.steps[step].action.module);
      }
    } else if (e.kind() == msg::SIM_EVENT_FAULT_REJECTED) {
      judge_.refused(step, e.detail().to_string());
      std::erase_if(acks_, [&](const auto& a) { return a.second.step == step; });
    }
  }

  void apply(launch::LaunchRun& run, std::size_t step, std::int64_t now)
  {
    const Action& a = scenario_.steps[step].action;
    run.say(fmt::format("fault step {} at t = {:.2f} s: {}", step + 1, t_, a.describe()));
    const auto signal = [&](int sig, bool exit_expected, const char* what) {
      const auto pid = run.pid(a.module);
      if (!run.signalModule(a.module, sig, exit_expected)) {
        refuse(step, a.module + " is not running");
        return;
      }
      acknowledge(step, now, fmt::format("{} to pid {}", what, *pid));
    };
    switch (a.kind) {
      case Action::Kind::kKill:
        signal(SIGKILL, true, "SIGKILL");
        break;
      case Action::Kind::kPause:
        signal(SIGSTOP, false, "SIGSTOP");
        break;
      case Action::Kind::kResume:
        signal(SIGCONT, false, "SIGCONT");
        break;
      case Action::Kind::kRestart:
        run.restartModule(a.module);
        acknowledge(step, common::steadyTimeNs(), fmt::format("started again as pid {}", *run.pid(a.module)));
        break;
      case Action::Kind::kPlant: {
        msg::FaultCommand c = plant::toCommand(a.plant);
        c.header().stamp_ns(common::toNanoseconds(t_));
        if (!endpoints_->command.writeFor(watched_, c)) {
          refuse(step, "the fault command could not be written");
          break;
        }
        acks_[a.plant.id] = {step, now + common::toNanoseconds(kAckTimeoutS)};
        break;
      }
      case Action::Kind::kDds:
        for (const auto& d : a.datagrams) {
          msg::FaultCommand c = dds::toCommand(d, kinds_.at(a.module));
          c.header().stamp_ns(common::toNanoseconds(t_));
          if (!endpoints_->command.writeFor(vehicle_of_.at(a.module), c)) {
            refuse(step, "the fault command could not be written");
            std::erase_if(acks_, [&](const auto& ack) { return ack.second.step == step; });
            return;
          }
          acks_[d.id] = {step, now + common::toNanoseconds(kAckTimeoutS)};
        }
        if (a.duration_s) {
          clears_.push_back({scenario_.steps[step].at_s + *a.duration_s, step});
        }
        break;
      case Action::Kind::kLink:
        try {
          run.network().applyLinkFault(a.link);
        } catch (const std::runtime_error& e) {
          refuse(step, e.what());
          break;
        }
        acknowledge(step, common::steadyTimeNs(), "applied in " + run.network().namespaceOf(a.link.host));
        if (a.duration_s) {
          clears_.push_back({scenario_.steps[step].at_s + *a.duration_s, step});
        }
        break;
      case Action::Kind::kMark:
        acknowledge(step, now, "marked");
        break;
      case Action::Kind::kOperatorLink:
        run.observer().setOperatorLink(false);
        acknowledge(step, now, "the operator's heartbeat stopped");
        if (a.duration_s) {
          clears_.push_back({scenario_.steps[step].at_s + *a.duration_s, step});
        }
        break;
      case Action::Kind::kPublish: {
        PublishJob& job = jobs_.at(step);
        job.active = true;
        job.next_ns = now;
        break;
      }
    }
  }

  void publishDue(std::int64_t now)
  {
    for (auto& [step, job] : jobs_) {
      const Action& a = scenario_.steps[step].action;
      while (job.active && job.sent < a.count && job.next_ns <= now) {
        ++job.sent;
        dds::RawSample raw = topic::encodeSample(job.info, job.values, common::toNanoseconds(t_),
                                          static_cast<std::uint64_t>(job.sent), injector_->options().vehicle_id,
                                          a.lengths.empty());
        if (!job.writer->write(raw)) {
          refuse(step, fmt::format("sample {} could not be written", job.sent));
          job.active = false;
          break;
        }
        if (job.sent == 1) {
          acknowledge(step, now, fmt::format("sample 1 of {} written, {} reader(s)", a.count, job.writer->matchedReaders()));
        }
        job.next_ns += common::toNanoseconds(1.0 / a.rate_hz);
      }
    }
  }

  void checkAcks(std::int64_t now)
  {
    for (auto it = acks_.begin(); it != acks_.end();) {
      if (now > it->second.deadline_ns) {
        const std::size_t step = it->second.step;
        refuse(step, fmt::format("no acknowledgement from {} within {:.0f} s", scenario_.steps[step].action.module,
                                 kAckTimeoutS));
        std::erase_if(acks_, [&](const auto& a) { return a.second.step == step; });
        it = acks_.begin();
      } else {
        ++it;
      }
    }
  }

  /// Ends the faults whose duration is over.
  void clearDue(launch::LaunchRun& run)
  {
    for (auto it = clears_.begin(); it != clears_.end();) {
      if (t_ < it->t_s) {
        ++it;
        continue;
      }
      clear(run, it->step);
      it = clears_.erase(it);
    }
  }

  /// Heals a link at once; asks a module's fault layer to clear datagram faults (it
  /// acknowledges each).
  void clear(launch::LaunchRun& run, std::size_t step)
  {
    const Action& a = scenario_.steps[step].action;
    if (a.kind == Action::Kind::kOperatorLink) {
      run.observer().setOperatorLink(true);
      noteCleared(step, "the operator's heartbeat resumed");
      event(step, msg::SIM_EVENT_FAULT_CLEARED, "the operator's heartbeat resumed");
      return;
    }
    if (a.kind == Action::Kind::kLink) {
      try {
        run.network().healLinkFault(a.link);
      } catch (const std::runtime_error& e) {
        run.say(fmt::format("fault step {}: cannot heal: {}", step + 1, e.what()));
        return;
      }
      noteCleared(step, "healed");
      event(step, msg::SIM_EVENT_FAULT_CLEARED, "healed");
      return;
    }
    for (const auto& d : a.datagrams) {
      msg::FaultCommand c;
      c.header().stamp_ns(common::toNanoseconds(t_));
      c.kind(msg::FAULT_CLEAR);
      c.fault_id(d.id);
      c.module_name(kinds_.at(a.module));
      endpoints_->command.writeFor(vehicle_of_.at(a.module), c);
    }
  }

  /// Every applied datagram fault's clearing was acknowledged.
  bool allCleared() const
  {
    for (std::size_t step = 0; step < scenario_.steps.size(); ++step) {
      const Action& a = scenario_.steps[step].action;
      if (!a.lasts() || !judge_.isApplied(step)) {
        continue;
      }
      const auto it = cleared_.find(step);
      if (it == cleared_.end() || it->second.size() < clearsOf(a)) {
        return false;
      }
    }
    return true;
  }

  /// The fault took effect: tell the judge, and the recording (quad/system/fault_events).
  void acknowledge(std::size_t step, std::int64_t wall_ns, const std::string& detail)
  {
    judge_.applied(step, t_, wall_ns, detail);
    event(step, msg::SIM_EVENT_FAULT_APPLIED, detail);
  }

  void refuse(std::size_t step, const std::string& why)
  {
    judge_.refused(step, why);
    event(step, msg::SIM_EVENT_FAULT_REJECTED, why);
  }

  void event(std::size_t step, msg::SimEventKind kind, const std::string& detail)
  {
    msg::SimEvent e;
    e.header().stamp_ns(common::toNanoseconds(t_));
    e.kind(kind);
    e.p_W(p_W_);
    e.subject_id(static_cast<std::int64_t>(step + 1));
    e.detail(fmt::format("step {}: {}: {}", step + 1, scenario_.steps[step].action.describe(), detail).substr(0, 256));
    endpoints_->events.write(e);
  }

  /// Loss figures of the reliable topics, from the recorder's own audit in the file. A
  /// topic whose writers keep only their newest sample (KEEP_LAST 1: the clock, latched
  /// state, actuator commands) promises that sample, not every one: it is not judged.
  void readRecording(fault::RunFacts& facts, dds::Participant& participant) const
  {
    if (!scenario_.outcome.zero_loss) {
      return;
    }
    try {
      const bag::McapContents c = bag::readMcap(recording_, true);
      const auto loss = bag::metadataValues(c, bag::kLossMetadata);
      if (loss.empty()) {
        facts.recording_problem = recording_.string() + ": no loss figures (the recorder did not finish)";
        return;
      }
      for (const auto& ch : c.channels) {
        const auto reliable = ch.metadata.find("reliable");
        if (reliable == ch.metadata.end() || reliable->second != "true") {
          continue;
        }
        const auto contract = topics::find(ch.topic);
        if (contract && !contract->has_header) {
          continue;  // a display topic: no seq to audit
        }
        if (contract) {
          const auto history = participant.writerQos(contract->qos_profile).history();
          if (history.kind == eprosima::fastdds::dds::KEEP_LAST_HISTORY_QOS && history.depth == 1) {
            ++facts.latest_only_topics;
            continue;
          }
        }
        const auto text = loss.find(ch.topic);
        const auto figures = text == loss.end() ? std::nullopt : bag::parseLossFigures(text->second);
        if (!figures) {
          facts.recording_problem = recording_.string() + ": no loss figures for " + ch.topic;
          return;
        }
        facts.reliable_loss[ch.topic] = figures->missing + figures->duplicated + figures->reordered;
      }
    } catch (const std::exception& e) {
      facts.recording_problem = e.what();
    }
  }

  struct Ack {
    std::size_t step;
    std::int64_t deadline_ns;
  };
  struct Clear {
    double t_s;
    std::size_t step;
  };

  const Scenario& scenario_;
  Judge judge_;
  fs::path recording_;
  std::unique_ptr<Endpoints> endpoints_;
  std::unique_ptr<dds::Participant> injector_;
  std::map<std::size_t, PublishJob> jobs_;
  std::map<std::string, std::string> kinds_;     // manifest module name -> kind
  std::map<std::string, std::uint32_t> vehicle_of_;  // manifest module name -> the vehicle it serves (0: the run)
  std::uint32_t watched_ = 0;        // the vehicle the expectations watch
  std::size_t watched_index_ = 0;    // its place among the observer's vehicles
  std::map<std::uint64_t, std::string> writers_; // heartbeat writer -> module
  std::map<std::string, ModuleSeen> seen_;
  std::map<std::uint32_t, Ack> acks_;  // by fault id
  std::vector<Clear> clears_;
  std::map<std::size_t, std::vector<std::string>> cleared_;  // acknowledgements by step
  double t_ = 0.0;
  std::array<std::uint64_t, 3> outliers_{};  // the estimator's refused position, baro and mag samples so far
  msg::Vector3 p_W_;
  std::uint64_t actuator_commands_ = 0;
  std::uint64_t nonfinite_actuators_ = 0;
};

}  // namespace

std::unique_ptr<launch::RunExtension> makeDriver(const Scenario& scenario, std::filesystem::path recording)
{
  return std::make_unique<FaultDriver>(scenario, std::move(recording));
}

}  // namespace quad::fault
