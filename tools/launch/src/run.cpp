// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/run.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <set>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "quad/common/layout.hpp"
#include "quad/common/params.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/environment.hpp"
#include "quad/dds/topics.hpp"
#include "quad/launch/estimate_plot.hpp"
#include "quad/launch/shm.hpp"
#include "quad/plan/known_map.hpp"
#include "quad/report/report.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/runtime/node.hpp"
#include "quad/runtime/state_input.hpp"
#include "quad/vehicle/vehicle.hpp"
#include "quad/world/world_file.hpp"

namespace quad::launch {

namespace fs = std::filesystem;

std::atomic<int> LaunchRun::received_signal{0};

std::string runFolderName(const std::string& name)
{
  const std::time_t now = std::time(nullptr);
  return fmt::format("{}-{:%Y%m%d-%H%M%S}-{}", name, fmt::localtime(now), getpid());
}

namespace {

/// "a,b,c": a list as the QUAD_* variables take it.
template <class Strings>
std::string commaList(const Strings& items)
{
  std::string list;
  for (const auto& item : items) {
    list += (list.empty() ? "" : ",") + item;
  }
  return list;
}

/// What a run's processes get in their environment, before a module's own entries.
std::map<std::string, std::string> runEnvironment(const Manifest& m, int domain, const launch::HostNetwork& net)
{
  std::map<std::string, std::string> env = m.environment;
  const char* own_tunables = std::getenv(kGlibcTunables);
  const auto manifest_tunables = m.environment.find(kGlibcTunables);
  env[kGlibcTunables] = moduleTunables(manifest_tunables != m.environment.end() ? manifest_tunables->second
                                       : own_tunables != nullptr                 ? own_tunables
                                                                                 : "");
  env[dds::environment::kDomainId] = std::to_string(domain);
  env[dds::environment::kTransport] = m.transport;
  env[dds::environment::kLockstep] = m.mode == "lockstep" ? "1" : "0";
  if (m.participant_lease_s > 0) {
    env[dds::environment::kParticipantLease] = std::to_string(m.participant_lease_s);
  }
  if (!m.security_dir.empty()) {
    env[dds::environment::kSecurityDir] = m.security_dir.string();
  }
  if (m.restrict_interfaces) {
    env[dds::environment::kInterfaces] = commaList(net.interfaces(""));  // the launcher's side; each module gets its host's
  }
  if (m.discovery == launch::Discovery::kInitialPeers) {
    std::set<std::string> peers;
    for (const auto& h : m.hosts) {
      peers.insert(net.address(h.name));
    }
    env[dds::environment::kInitialPeers] = commaList(peers);
  } else if (m.discovery == launch::Discovery::kServer) {
    env[dds::environment::kDiscoveryServer] = net.address(m.discovery_host) + ":" + std::to_string(m.discovery_port);
  }
  return env;
}

}  // namespace

LaunchRun::LaunchRun(const Manifest& m, const LaunchOptions& o, fs::path dir, int domain)
    : m_(m), options_(o), domain_(domain), supervisor_(std::move(dir), stdout, !o.quiet),
      state_dir_(fs::absolute(supervisor_.logDir() / "state")), start_ns_(common::steadyTimeNs())
{
  // What a module keeps for its next start within this run (${run_state}); a folder reused
  // from an earlier run must not hand that run's state to this one.
  fs::remove_all(state_dir_);
  fs::create_directories(state_dir_);
  if (!m.vehicles.empty()) {
    for (const auto& v : m.vehicles) {
      fs::create_directories(state_dir_ / vehicleFolder(v.id));
    }
    std::ofstream(state_dir_ / kFleetFile) << fleetFileText(m.vehicles);
  }
  record_.manifest = m.file.string();
  record_.world = m.world.empty() ? std::string() : fs::absolute(m.world).string();
  record_.domain = domain;
  for (const auto& mod : m.modules) {
    record_.order.push_back(mod.name);
    record_.modules[mod.name] = {mod.kind, mod.host};
    record_.modules[mod.name].command = processCommand(mod, kRunStateVariable);
    for (const auto& hosted : mod.hosted) {
      record_.modules[mod.name].hosted[hosted.kind] = processCommand(hosted, kRunStateVariable);
    }
  }
}

int LaunchRun::endedBeforeStart(int code)
{
  record_.phase = RunPhase::kEnded;
  record_.exit_code = code;
  saveRecord();
  return code;
}

void LaunchRun::saveRecord()
{
  record_.failure = failure_;
  if (!launch::writeRunRecord(supervisor_.logDir() / "run.json", record_)) {
    say("cannot write " + (supervisor_.logDir() / "run.json").string());
  }
}

LaunchRun::~LaunchRun() = default;

const Module& LaunchRun::module(const std::string& name) const
{
  const Module* found = m_.findModule(name);
  if (found == nullptr) {
    throw std::invalid_argument("no module '" + name + "' in " + m_.file.string());
  }
  return *found;
}

namespace {

/// Composed, the run's recorder is hosted in the container of the plant, the writer of the
/// 250 Hz topics, whose samples then reach it with no socket between: when that container
/// runs on the launcher's machine (the recording is the launcher's file). Otherwise, and in
/// the distributed layout, quad record runs as a process of its own.
std::optional<std::string> recorderHost(const Manifest& m)
{
  for (const Module& mod : m.modules) {
    const bool plant = std::any_of(mod.hosted.begin(), mod.hosted.end(), [](const Module& h) { return h.kind == "plant"; });
    if (mod.kind == kContainerKind && plant && m.host(mod.host).kind == HostKind::kLocal) {
      return mod.name;
    }
  }
  return std::nullopt;
}

}  // namespace

void LaunchRun::startModule(const Module& mod)
{
  std::map<std::string, std::string> env = env_;
  if (m_.restrict_interfaces) {
    env[dds::environment::kInterfaces] = commaList(net_->interfaces(mod.host));
  }
  for (const auto& [k, v] : mod.environment) {
    env[k] = withRunState(v, state_dir_);
  }
  if (mod.vehicle) {
    env[dds::environment::kVehicleId] = std::to_string(*mod.vehicle);
  }
  const auto& host = m_.host(mod.host);
  Module started = mod;
  if (recorder_host_ == mod.name && !states_[mod.name].started) {
    // Its first start only: a container started again within the run (a fault's restart, a
    // respawn) would begin the recording anew; it comes back without the recorder, whose
    // file ends where the container's first life did.
    Module recorder;
    recorder.name = recorder.kind = runtime::kRecorderParticipant;
    recorder.sets.emplace_back("output", fs::absolute(*options_.record).string());
    started.hosted.push_back(recorder);
  }
  supervisor_.start(mod.name, net_->command(host, processCommand(started, state_dir_), env), env);
  State& st = states_[mod.name];
  if (!st.started) {
    started_order_.push_back(mod.name);
  }
  st.started = true;
  st.beating.clear();
  st.restart_at_ns = 0;
  st.exit_expected = false;
  const pid_t pid = *supervisor_.pid(mod.name);
  say(fmt::format("started {} on {} (pid {})", mod.name, mod.host, pid));
  ModuleRecord& rec = record_.modules[mod.name];
  rec.phase = ModulePhase::kStarting;
  rec.pid = static_cast<int>(pid);
  ++rec.starts;
  rec.restarts = st.restarts;
  rec.started_ns = common::wallTimeNs();
  saveRecord();
}

void LaunchRun::onHeartbeat(const launch::ModuleBeat& beat)
{
  for (const auto& mod : m_.modules) {
    ModuleRecord& rec = record_.modules[mod.name];
    const bool hosted = std::any_of(mod.hosted.begin(), mod.hosted.end(),
                                    [&](const Module& h) { return h.kind == beat.module; });
    if ((mod.kind != beat.module && !hosted) || rec.phase != ModulePhase::kStarting || !beat.running) {
      continue;
    }
    // The process the launcher started is the module itself on this machine and in a network
    // namespace (ip netns exec execs it); over ssh the pid is the remote one, so a heartbeat
    // stamped after the start stands for it.
    const bool remote = m_.host(mod.host).kind == launch::HostKind::kSsh;
    if (beat.pid != rec.pid && !(remote && beat.stamp_ns >= rec.started_ns)) {
      continue;
    }
    // A container runs once each module it hosts does.
    State& st = states_[mod.name];
    st.beating.insert(beat.module);
    if (hosted && st.beating.size() < mod.hosted.size()) {
      continue;
    }
    rec.phase = ModulePhase::kRunning;
    say(fmt::format("{} is running (heartbeat from pid {})", mod.name, beat.pid));
    saveRecord();
  }
}

bool LaunchRun::signalModule(const std::string& name, int signal, bool exit_expected)
{
  module(name);  // throws for a name the manifest does not have
  if (!supervisor_.running(name)) {
    return false;
  }
  states_[name].exit_expected = states_[name].exit_expected || exit_expected;
  return supervisor_.signal(name, signal);
}

void LaunchRun::restartModule(const std::string& name)
{
  const Module& mod = module(name);
  if (supervisor_.running(name)) {
    states_[name].exit_expected = true;
    supervisor_.stop(name, m_.grace_s);
  }
  startModule(mod);
}

void LaunchRun::handleExit(const launch::Supervisor::Exit& e)
{
  State& st = states_[e.name];
  st.last_status = e.status;
  const std::string what = process::describeStatus(e.status);
  if (e.name == "discovery" || e.name == "record") {
    failed_ = true;
    failure_ = (e.name == "record" ? "the recorder" : "the discovery server") + std::string(" ended (") + what + ")";
    say(failure_);
    saveRecord();
    return;
  }
  const Module* it = m_.findModule(e.name);
  if (it == nullptr) {
    return;
  }
  ModuleRecord& rec = record_.modules[e.name];
  rec.last_exit = what;
  if (it->ends_run && (e.status == 0 || st.exit_expected)) {
    // What the others do depends on it (the plant is the vehicle's world): the run cannot
    // go on without it, whether it finished or a fault killed it.
    const std::string reason = e.status == 0 ? fmt::format("{} finished ({})", e.name, what)
                                             : fmt::format("{} exited ({}), as the fault meant it to: the run "
                                                           "cannot go on without it",
                                                           e.name, what);
    say(reason + ": ending the run");
    ended_by_ = EndedBy{e.name, common::steadyTimeNs(), reason};
    rec.phase = ModulePhase::kExited;
  } else if (st.restarts < it->respawn) {
    const double delay = it->backoff_s * std::pow(2.0, st.restarts);
    ++st.restarts;
    st.restart_at_ns = common::steadyTimeNs() + common::toNanoseconds(delay);
    say(fmt::format("{} exited ({}): restarting in {:.1f} s ({} of {})", e.name, what, delay, st.restarts,
                    it->respawn));
    rec.phase = ModulePhase::kRestarting;
    rec.restarts = st.restarts;
  } else if (st.exit_expected) {
    say(fmt::format("{} exited ({}), as the fault meant it to", e.name, what));
    rec.phase = ModulePhase::kExited;
  } else {
    failed_ = true;
    failure_ = fmt::format("{} failed ({}){}", e.name, what,
                           it->respawn > 0 ? fmt::format(" after {} restarts", st.restarts) : "");
    say(failure_ + ": stopping the run");
    rec.phase = ModulePhase::kFailed;
  }
  saveRecord();
}

bool LaunchRun::service(int timeout_ms)
{
  for (const auto& e : supervisor_.pump(timeout_ms)) {
    handleExit(e);
  }
  const std::int64_t now = common::steadyTimeNs();
  for (const auto& mod : m_.modules) {
    State& st = states_[mod.name];
    if (st.restart_at_ns != 0 && now >= st.restart_at_ns && !failed_ && !interrupted()) {
      startModule(mod);
    }
  }
  if (observer_) {
    observer_->update();
    for (const auto& beat : observer_->takeHeartbeats()) {
      onHeartbeat(beat);
    }
    for (std::size_t i = 0; i < observer_->vehicleCount(); ++i) {
      if (auto* mission = observer_->mission(i)) {
        for (const auto& line : mission->takeProgress()) {
          say(m_.vehicles.empty() ? line : fmt::format("vehicle {}: {}", observer_->vehicleId(i), line));
        }
      }
    }
  }
  if (options_.wall_timeout_s > 0 && now - start_ns_ > common::toNanoseconds(options_.wall_timeout_s)) {
    failed_ = true;
    failure_ = fmt::format("the run took longer than --wall-timeout {:.0f} s", options_.wall_timeout_s);
    say(failure_);
    saveRecord();
  }
  return !failed_ && !ended_by_ && !interrupted();
}

void LaunchRun::reportStall()
{
  say("no vehicle state for 30 s; what the modules last said of lockstep:");
  for (const auto& name : started_order_) {
    std::ifstream log(supervisor_.logDir() / (name + ".log"));
    std::string line;
    std::string last;
    while (std::getline(log, line)) {
      if (line.find("lockstep:") != std::string::npos) {
        last = line;
      }
    }
    say(fmt::format("  {}: {}", name, last.empty() ? "(nothing)" : last));
  }
}

std::string LaunchRun::whoWrites(const std::string& topic) const
{
  const auto contract = dds::topics::find(topic);
  if (!contract) {
    return "no module declares it";
  }
  const std::string owner(dds::toString(contract->owner));
  std::string who;
  for (const auto& mod : m_.modules) {
    if (mod.kind != owner) {
      continue;
    }
    const auto st = states_.find(mod.name);
    std::string state = "not started yet";
    if (supervisor_.running(mod.name)) {
      state = "running";
    } else if (st != states_.end() && st->second.last_status) {
      state = process::describeStatus(*st->second.last_status);
    }
    who += (who.empty() ? "" : ", ") + mod.name + " (" + state + ")";
  }
  return who.empty() ? "written by " + owner + ", which this manifest does not start"
                     : "written by " + who;
}

bool LaunchRun::waitForNeeds(const Module& mod)
{
  if (mod.needs.empty()) {
    return true;
  }
  const std::int64_t deadline = common::steadyTimeNs() + common::toNanoseconds(mod.ready_timeout_s);
  while (service(50)) {
    const auto missing = observer_->missingWriters(mod.needs);
    if (missing.empty()) {
      return true;
    }
    if (common::steadyTimeNs() >= deadline) {
      std::string list;
      for (const auto& t : missing) {
        list += (list.empty() ? "" : "; ") + t + " (" + whoWrites(t) + ")";
      }
      failed_ = true;
      failure_ = fmt::format("{} not started: after {:.1f} s no writer on {}", mod.name, mod.ready_timeout_s, list);
      say(failure_);
      saveRecord();
      return false;
    }
  }
  return false;
}

void LaunchRun::waitForGoalDelivery()
{
  // The modules that read the goal (started before the plant, whose clock starts the run)
  // take it 0.1 s of sim time after its stamp; one reaching them after that would be taken a
  // round later in one run than in another.
  const std::int64_t deadline = common::steadyTimeNs() + 5 * common::kNanosecondsPerSecond;
  while (!observer_->goalDelivered() && service(20)) {
    if (common::steadyTimeNs() >= deadline) {
      say(fmt::format("{}: not every reader acknowledged the goal within 5 s; going on",
                      dds::topics::kGoal.info.name));
      return;
    }
  }
}

void LaunchRun::stopAll()
{
  // Reverse start order; the discovery server last of all. A paused process must be resumed
  // to see its SIGTERM.
  record_.phase = RunPhase::kStopping;
  saveRecord();
  for (auto it = started_order_.rbegin(); it != started_order_.rend(); ++it) {
    supervisor_.signal(*it, SIGCONT);
    if (const auto status = supervisor_.stop(*it, m_.grace_s)) {
      say(fmt::format("stopped {} ({})", *it, process::describeStatus(*status)));
      if (const auto rec = record_.modules.find(*it); rec != record_.modules.end()) {
        rec->second.phase = ModulePhase::kStopped;
        rec->second.last_exit = process::describeStatus(*status);
        record_.stopped_order.push_back(*it);
      }
    }
  }
  supervisor_.stop("discovery", m_.grace_s);
}

std::vector<launch::ProcessCost> LaunchRun::processCosts() const
{
  std::vector<launch::ProcessCost> costs;
  for (const auto& name : started_order_) {
    // Over ssh the local process is the ssh client, whose CPU time is not the module's.
    const Module* mod = m_.findModule(name);
    const bool remote = mod != nullptr && m_.host(mod->host).kind == launch::HostKind::kSsh;
    costs.push_back({name, remote ? std::nullopt : supervisor_.cpuSeconds(name),
                     remote ? std::nullopt : supervisor_.maxResidentMiB(name),
                     remote ? std::nullopt : supervisor_.waits(name)});
  }
  if (m_.discovery == launch::Discovery::kServer && m_.host(m_.discovery_host).kind != launch::HostKind::kSsh) {
    costs.push_back({"discovery", supervisor_.cpuSeconds("discovery"), supervisor_.maxResidentMiB("discovery"),
                     supervisor_.waits("discovery")});
  }
  costs.push_back({"launch", common::processCpuSeconds(), common::processMaxResidentMiB(), common::processWaits()});
  return costs;
}

std::optional<plan::PlanningSetup> manifestPlanningSetup(const launch::Manifest& manifest)
{
  const auto modules = manifest.hostedModules();
  const auto found = std::find_if(modules.begin(), modules.end(), [](const Module* x) { return x->kind == "planning"; });
  if (found == modules.end()) {
    return std::nullopt;
  }
  const common::ParamSchema planner_schema = planning::planningSchema();
  std::vector<common::ParamOverride> overrides;
  for (const auto& [key, value] : (*found)->sets) {
    if (planner_schema.find(key) != nullptr) {
      overrides.push_back({key, value});
    }
  }
  return plan::loadPlanningSetup((*found)->config, overrides);
}

std::optional<double> LaunchRun::knownMapOptimum(const world::World& world)
{
  try {
    const auto setup = manifestPlanningSetup(m_);
    if (!setup) {
      return std::nullopt;
    }
    const plan::KnownMapPlan best = plan::planOnKnownMap(
        setup->world.withStartAndGoal(world.start(), world.goal()), setup->params, m_.mission.land);
    if (best.status != planning::PlanStatus::kOk) {
      return std::nullopt;  // no optimum where no path exists
    }
    return best.optimum_m;
  } catch (const std::exception& e) {
    say(std::string("no known-map optimum: ") + e.what());
    return std::nullopt;
  }
}

int LaunchRun::startMissions()
{
  const world::World world = world::loadWorld(m_.world);
  const common::Geofence fence = m_.geofence.value_or(common::Geofence{});
  const auto radiusOf = [](const fs::path& file) { return file.empty() ? 0.0 : vehicle::loadVehicle(file).radius; };
  std::vector<launch::MissionVehicle> vehicles;
  if (m_.vehicles.empty()) {
    const double radius = radiusOf(m_.mission.vehicle);
    if (const auto problem = launch::goalProblem(world, radius, fence)) {
      failure_ = fmt::format("{}: {}: refused", m_.world.string(), *problem);
      say(failure_);
      return kExitInvalid;
    }
    vehicles.push_back({observer_->vehicleId(0), world, radius});
  } else {
    std::vector<double> radii;
    for (const auto& v : m_.vehicles) {
      radii.push_back(radiusOf(v.vehicle));
      vehicles.push_back({v.id, launch::memberWorld(world, v), radii.back()});
    }
    if (const auto problems = launch::fleetProblems(world, m_.vehicles, radii, fence); !problems.empty()) {
      for (const auto& p : problems) {
        say(fmt::format("{}: {}", m_.file.string(), p));
      }
      failure_ = fmt::format("{}: {}: refused", m_.file.string(), problems.front());
      return kExitInvalid;
    }
  }
  for (const auto& v : vehicles) {
    const auto& s = v.world.start();
    const auto& g = v.world.goal();
    say(fmt::format("mission{}: fly from ({:.1f}, {:.1f}, {:.1f}) to the goal ({:.1f}, {:.1f}, {:.1f}) of {}",
                    m_.vehicles.empty() ? "" : fmt::format(" of vehicle {}", v.id), s.x(), s.y(), s.z(), g.x(),
                    g.y(), g.z(), m_.world.filename().string()));
  }
  observer_->startMission(m_.mission, std::move(vehicles));
  return 0;
}

launch::MissionSummary LaunchRun::missionSummary(double wall_s)
{
  std::vector<launch::MissionSummary> each;
  for (std::size_t i = 0; i < observer_->vehicleCount(); ++i) {
    launch::MissionTracker* mission = observer_->mission(i);
    launch::MissionSummary s = mission->summary(wall_s);
    s.state = m_.state;
    s.estimate = observer_->estimateScore(i).errors();
    if (!m_.vehicles.empty()) {
      s.vehicle_id = observer_->vehicleId(i);
    }
    if (ended_by_ && !s.success && s.end == launch::MissionEnd::kUnfinished) {
      s.outcome = "not finished: " + ended_by_->reason;
      s.failure = ended_by_->reason;
    }
    each.push_back(std::move(s));
  }
  launch::MissionSummary summary = m_.vehicles.empty()
                                       ? std::move(each.front())
                                       : launch::fleetSummary(std::move(each), observer_->minimumSeparation(), wall_s);
  summary.state = m_.state;
  summary.processes = processCosts();  // before the optimum's search, which the wall time leaves out
  if (const std::int64_t first = observer_->firstStateNs(); first > 0) {
    summary.startup_s = common::toSeconds(first - start_ns_);
    summary.flight_wall_s = common::toSeconds(observer_->lastStateNs() - first);
  }
  if (m_.vehicles.empty()) {
    summary.optimum_m = knownMapOptimum(world::loadWorld(m_.world));
  } else {
    const world::World world = world::loadWorld(m_.world);
    std::optional<double> total = 0.0;
    for (std::size_t i = 0; i < summary.vehicles.size(); ++i) {
      summary.vehicles[i].optimum_m = knownMapOptimum(launch::memberWorld(world, m_.vehicles[i]));
      total = total && summary.vehicles[i].optimum_m ? std::optional<double>(*total + *summary.vehicles[i].optimum_m)
                                                     : std::nullopt;
    }
    summary.optimum_m = total;
  }
  return summary;
}

int LaunchRun::execute(RunExtension* extension)
{
  say(fmt::format("{}: domain {}, {} hosts, {} modules, mode {}, logs in {}", m_.file.string(), domain_,
                  m_.hosts.size(), m_.modules.size(), m_.mode, supervisor_.logDir().string()));
  if (const auto cleaned = launch::cleanStaleSharedMemory(); cleaned.files > 0) {
    say(fmt::format("removed {} stale Fast DDS shared-memory files ({} KiB)", cleaned.files, cleaned.bytes / 1024));
  }
  try {
    net_ = std::make_unique<launch::HostNetwork>(m_, fmt::format("{:x}", getpid()));
    if (m_.firewall) {
      std::vector<int> extra;
      if (m_.discovery == launch::Discovery::kServer) {
        extra.push_back(m_.discovery_port);
      }
      net_->installFirewall(domain_, extra);
      const auto ports = launch::ddsPorts(domain_);
      say(fmt::format("firewall: UDP {}-{}{} on the netns and ssh hosts admits the manifest's hosts only", ports.first,
                      ports.last, extra.empty() ? "" : fmt::format(" and {}", extra.front())));
    }
  } catch (const std::exception& e) {
    failure_ = std::string("cannot set up the hosts: ") + e.what();
    say(failure_);
    return endedBeforeStart(kExitFailed);
  }
  for (const auto& h : m_.hosts) {
    if (h.kind == launch::HostKind::kNetns) {
      say(fmt::format("host {}: network namespace {} at {}", h.name, net_->namespaceOf(h.name), net_->address(h.name)));
    }
    record_.hosts[h.name] = {std::string(launch::toString(h.kind)), net_->address(h.name), net_->namespaceOf(h.name)};
  }
  record_.firewall = m_.firewall;
  saveRecord();
  env_ = runEnvironment(m_, domain_, *net_);
  if (options_.record && m_.mode == "lockstep") {
    env_[dds::environment::kLockstepRecorder] = "1";  // the recording starts with the run's first step
  }
  if (m_.mode == "lockstep") {
    env_[dds::environment::kLockstepObserver] = "1";  // and the summary's scores
  }
  if (m_.discovery == launch::Discovery::kServer) {
    const auto& host = m_.host(m_.discovery_host);
    const std::vector<std::string> argv{"fastdds", "discovery", "-i", "0", "-l", net_->address(host.name), "-p",
                                        std::to_string(m_.discovery_port)};
    supervisor_.start("discovery", net_->command(host, argv, {}), {});
    say(fmt::format("started a discovery server on {} at {}", host.name, env_[dds::environment::kDiscoveryServer]));
    record_.discovery_server = env_[dds::environment::kDiscoveryServer];
  }

  // The launcher's participant, set up like the modules': from the same environment, read by
  // the same parser.
  for (const auto& [key, value] : env_) {
    ::setenv(key.c_str(), value.c_str(), 1);
  }
  dds::ParticipantOptions po = dds::optionsFromEnvironment("quad_launch");
  po.observe_all = true;
  observer_ = std::make_unique<launch::Observer>(
      po, m_.vehicles.empty() ? std::vector<std::uint32_t>{} : m_.vehicleIds(),
      runtime::statePeriodNs(m_.mission.score_rate_hz));
  if (po.lockstep_observer) {
    const auto modules = m_.hostedModules();
    observer_->holdStart(static_cast<std::size_t>(
        std::count_if(modules.begin(), modules.end(), [](const launch::Module* mod) { return mod->kind == "estimation"; })));
  }

  if (m_.mission.enabled) {
    if (const int code = startMissions(); code != 0) {
      return endedBeforeStart(code);
    }
  }

  if (options_.record) {
    recorder_host_ = recorderHost(m_);
    if (recorder_host_) {
      say(fmt::format("recording every topic to {} (from container {})", *options_.record, *recorder_host_));
    } else {
      // Started first, so stopped last: it sees every module's last samples.
      const std::vector<std::string> argv{common::programPath(common::layout(), "tools/quad/quad").string(), "record",
                                          "-q", "-o", fs::absolute(*options_.record).string()};
      supervisor_.start("record", argv, env_);
      started_order_.push_back("record");
      say("recording every topic to " + *options_.record);
    }
  }
  bool all_started = true;
  for (const auto& mod : m_.modules) {
    if (!waitForNeeds(mod)) {
      all_started = false;
      break;
    }
    waitForGoalDelivery();
    startModule(mod);
  }
  if (all_started) {
    record_.phase = RunPhase::kRunning;
    saveRecord();
  }
  std::int64_t stall_reported_ns = 0;
  constexpr std::int64_t kStallNs = 30 * common::kNanosecondsPerSecond;
  // Looked at every 50 ms, or every 2 ms while the run's first round waits for the observer
  // (its plant's clock and states discovered): the start is not held a poll longer than it must.
  while (all_started && service(observer_->holdingStart() ? 2 : 50)) {
    if (observer_->missionsFinished()) {
      break;
    }
    if (extension != nullptr) {
      extension->tick(*this);
      if (extension->done()) {
        break;
      }
    }
    // A mission whose vehicle state stopped coming is stuck, whoever is at fault.
    const std::int64_t last = observer_->lastStateNs();
    if (m_.mission.enabled && last > 0 && common::steadyTimeNs() - last > kStallNs && stall_reported_ns != last) {
      stall_reported_ns = last;
      reportStall();
      if (m_.mode == "lockstep") {
        // Sim time waits for everyone: a lockstep run that stopped this long does not resume.
        failed_ = true;
        failure_ = "no vehicle state for 30 s: the lockstep run stalled";
        saveRecord();
        break;
      }
    }
  }
  if (interrupted()) {
    say(fmt::format("{}: stopping", received_signal.load() == SIGINT ? "interrupted" : "terminated"));
  }
  if (extension != nullptr && all_started) {
    extension->ending(*this);
  }
  stopAll();
  if (const auto cleaned = launch::cleanStaleSharedMemory("/dev/shm", std::chrono::seconds(1)); cleaned.files > 0) {
    say(fmt::format("removed {} Fast DDS shared-memory files left by stopped processes", cleaned.files));
  }
  net_.reset();

  // Stopped by a signal with nothing failed is a clean end; an unfinished mission is not.
  int code = failed_ ? 1 : 0;
  if (observer_->mission() != nullptr) {
    summary_ = missionSummary(common::toSeconds(common::steadyTimeNs() - start_ns_));
    const std::string json = launch::toJson(*summary_);
    std::ofstream(supervisor_.logDir() / "summary.json") << json;
    if (const auto& series = observer_->estimateScore().series(); !series.empty()) {
      std::ofstream(supervisor_.logDir() / "estimate_error.csv") << launch::toCsv(series);
      std::ofstream(supervisor_.logDir() / "estimate_error.svg")
          << launch::estimateErrorSvg(series, fmt::format("{}, world {}: the estimate against the truth (flown on the {})",
                                                          m_.file.filename().string(), m_.world.filename().string(),
                                                          m_.state));
    }
    if (options_.summary) {
      std::ofstream out(*options_.summary);
      out << json;
      if (!out) {
        say("cannot write the summary to " + *options_.summary);
        code = 1;
      }
    }
    std::printf("%s", launch::toText(*summary_).c_str());
    if (!summary_->success && code == 0 && extension == nullptr) {
      code = summary_->end == launch::MissionEnd::kNoPath ? kExitNoPath : 1;
    }
  }
  if (failed_) {
    std::printf("launch: FAILED: %s\n", failure_.c_str());
  }
  if (extension != nullptr) {
    code = extension->finish(*this, code);
  }
  record_.phase = RunPhase::kEnded;
  record_.exit_code = code;
  saveRecord();
  if (options_.record && !options_.no_report) {
    writeReport();
  }
  std::printf("launch: logs in %s\n", supervisor_.logDir().string().c_str());
  std::fflush(stdout);
  return code;
}

void LaunchRun::writeReport()
{
  const fs::path recording(*options_.record);
  if (!fs::exists(recording)) {
    return;  // the recorder never started: the run ended first
  }
  report::ReportOptions o;
  o.input = supervisor_.logDir();
  o.recording = recording;
  if (!m_.world.empty()) {
    o.world = m_.world;
  }
  // A fleet's: a report per vehicle, each in the vehicle's folder of the run's.
  std::vector<std::optional<std::uint32_t>> reported;
  for (const auto& v : m_.vehicles) {
    reported.emplace_back(v.id);
  }
  if (reported.empty()) {
    reported.emplace_back();
  }
  for (const auto& vehicle : reported) {
    o.vehicle = vehicle;
    if (vehicle) {
      o.output = supervisor_.logDir() / vehicleFolder(*vehicle);
    }
    try {
      const report::ReportResult r = report::writeReport(o);
      say(fmt::format("report: {} ({} figures; quad report{} redraws it)", r.html.string(), r.figures,
                      vehicle ? fmt::format(" --vehicle {}", *vehicle) : ""));
    } catch (const report::ReportError& e) {
      // The run's verdict stands: the report only shows it.
      say(fmt::format("no report: {}", e.what()));
    }
  }
}

std::optional<launch::Manifest> loadRunManifest(const LaunchOptions& options)
{
  launch::ManifestOverrides overrides;
  if (options.world) {
    overrides.world = *options.world;
  }
  if (options.realtime) {
    overrides.mode = "realtime";
  } else if (options.lockstep) {
    overrides.mode = "lockstep";
  }
  overrides.state = options.state;
  overrides.seed = options.seed;
  overrides.vehicle = options.vehicle;
  overrides.layout = options.layout;
  overrides.domain = options.domain;
  overrides.subnet = options.subnet;
  overrides.geofence = options.geofence;
  launch::ProgramLookup lookup{common::layout(), [](const std::string& t) -> std::optional<std::string> {
                                 const auto contract = dds::topics::find(t);
                                 return contract ? std::optional<std::string>(dds::toString(contract->owner))
                                                 : std::nullopt;
                               }};
  try {
    for (const auto& text : options.sets) {
      overrides.sets.push_back(launch::parseModuleSet(text, "--set"));
    }
    return launch::loadManifest(launch::findManifest(options.manifest, common::layout()), overrides, lookup);
  } catch (const common::ConfigError& e) {
    for (const auto& p : e.problems()) {
      std::fprintf(stderr, "%s\n", p.c_str());
    }
    return std::nullopt;
  }
}

int runManifest(const launch::Manifest& manifest, const LaunchOptions& options, RunExtension* extension)
{
  int domain = 0;
  try {
    domain = manifest.domain ? *manifest.domain : dds::optionsFromEnvironment("quad_launch").domain_id;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "launch: %s\n", e.what());
    return kExitInvalid;
  }
  const fs::path dir = options.log_dir ? fs::path(*options.log_dir) : fs::path("log") / runFolderName(manifest.name);
  LaunchOptions o = options;
  if (!o.record && !o.no_record) {
    o.record = (dir / report::kRecordingFile).string();
  }
  try {
    LaunchRun run(manifest, o, dir, domain);
    return run.execute(extension);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "launch: %s\n", e.what());
    return kExitFailed;
  }
}

}  // namespace quad::launch
