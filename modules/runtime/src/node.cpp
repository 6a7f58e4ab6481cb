// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/node.hpp"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>
#include <ctime>
#include <unistd.h>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "quad/common/logging.hpp"
#include "quad/common/time.hpp"
#include "quad/common/yaml_input.hpp"
#include "quad/dds/message_types.hpp"
#include "quad/dds/topics.hpp"
#include "quad/wire/validating_transport.hpp"
#include "fault_layer_control.hpp"

namespace quad::runtime {

namespace {
constexpr std::int64_t kHeartbeatPeriodNs = 500'000'000;  // 2 Hz, the contract's rate
constexpr std::int64_t kIdleWakeNs = 100'000'000;         // re-check stop at least this often

sigset_t stopSignals()
{
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

std::string hostName()
{
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return name;
}
}  // namespace

SignalWatcher::SignalWatcher()
{
  const sigset_t set = stopSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  thread_ = std::thread([this] { watch(); });
}

SignalWatcher::~SignalWatcher()
{
  quit_ = true;
  thread_.join();
}

void SignalWatcher::onSignal(std::function<void(int)> callback)
{
  std::lock_guard lock(mutex_);
  callback_ = std::move(callback);
}

void SignalWatcher::watch()
{
  const sigset_t set = stopSignals();
  const timespec poll{0, 100'000'000};
  while (!quit_) {
    const int signal = sigtimedwait(&set, nullptr, &poll);
    if (signal > 0) {
      received_ = signal;
      std::lock_guard lock(mutex_);
      if (callback_) {
        callback_(signal);
      }
    }
  }
}

Node::Node(std::string module_name, dds::ParticipantOptions options)
    : Node(std::move(module_name), dds::Participant(std::move(options)))
{
}

Node::Node(std::string module_name, dds::Participant participant)
    : module_name_(std::move(module_name)),
      participant_(std::move(participant)),
      heartbeat_(participant_, dds::topics::kHeartbeat)
{
  lockstep_ = participant_.options().lockstep;
  waker_.setRunner([this] { return wakeOnReceipt(); });
  participant_.events().setNotifier([this] { waker_.notify(); });
  if (participant_.datagramFaults() != nullptr) {
    fault_layer_ = std::make_unique<FaultLayerControl>(participant_, module_name_, &waker_);
  }
}

Node::~Node()
{
  participant_.events().setNotifier({});
}

void Node::countLoss(const dds::EndpointEvent& event)
{
  if (event.kind != dds::EventKind::kSampleLost || event.count <= 0) {
    return;
  }
  const auto contract = dds::topics::find(event.topic);
  if (contract && participant_.promisesEverySample(contract->qos_profile)) {
    counters_.samples_lost += static_cast<std::uint64_t>(event.count);
  }
}

void Node::countRejectedPayloads()
{
  // Of the types this node reads: in a container, each node its own. The process's count,
  // read without a lock, says whether there is anything new to look at.
  const std::uint64_t in_process = dds::rejectedPayloadCount();
  std::uint64_t refused = rejected_payloads_;
  if (in_process != process_rejected_payloads_) {
    process_rejected_payloads_ = in_process;
    refused = 0;
    for (const auto& type : participant_.readerTypes()) {
      refused += dds::rejectedPayloadCount(type);
    }
  }
  if (refused > rejected_payloads_) {
    counters_.errors += refused - rejected_payloads_;
    spdlog::warn("{}: {} received payload(s) refused; the process's last: {}", module_name_, refused - rejected_payloads_,
                 dds::rejectedPayloads().last);
    rejected_payloads_ = refused;
  }
  // The validating transport logs each itself (at most once a second); the process's node
  // that made the participant counts them.
  const std::uint64_t malformed = wire::malformedDatagramCount();
  if (participant_.reportsProcessInputs() && malformed > malformed_datagrams_) {
    counters_.errors += malformed - malformed_datagrams_;
    malformed_datagrams_ = malformed;
  }
}

bool Node::isDatagramFaultId(std::uint32_t id) const
{
  return fault_layer_ && fault_layer_->knows(id);
}

void Node::stop()
{
  stop_ = true;
  waker_.notify();
}

msg::Heartbeat processHeartbeat(const std::string& module_name, msg::ModuleState state, std::int64_t stamp_ns)
{
  msg::Heartbeat hb;
  hb.header().stamp_ns(stamp_ns);
  hb.module_name(module_name);
  hb.host(hostName());
  hb.pid(static_cast<std::int32_t>(getpid()));
  hb.state(state);
  return hb;
}

void Node::publishHeartbeat(msg::ModuleState state)
{
  msg::Heartbeat hb = processHeartbeat(module_name_, state, common::wallTimeNs());
  hb.samples_in(counters_.samples_in.load());
  hb.samples_out(counters_.samples_out.load());
  hb.errors(counters_.errors.load());
  hb.samples_lost(counters_.samples_lost.load());
  heartbeat_.write(hb);
}

void Node::onEvent(const dds::EndpointEvent& event)
{
  if (event.kind == dds::EventKind::kDeadlineMissed) {
    if (lockstep_) {
      return;
    }
    const std::int64_t now = common::steadyTimeNs();
    if (now - last_deadline_log_ns_ < common::kNanosecondsPerSecond) {
      return;
    }
    last_deadline_log_ns_ = now;
  }
  const bool problem = event.kind == dds::EventKind::kIncompatibleQos ||
                       event.kind == dds::EventKind::kTypeMismatch ||
                       event.kind == dds::EventKind::kWriteFailed ||
                       event.kind == dds::EventKind::kLivelinessLost ||
                       event.kind == dds::EventKind::kForeignSample ||
                       event.kind == dds::EventKind::kDeadlineMissed;
  if (problem) {
    spdlog::warn("{}: {}: {}", event.topic, toString(event.kind), event.detail);
  } else {
    spdlog::debug("{}: {}: {}", event.topic, toString(event.kind), event.detail);
  }
}

void Node::followSimClock(std::int32_t depth)
{
  sim_clock_ = std::make_unique<SimClockFollower>(participant_, &waker_, std::vector<std::uint32_t>{}, depth);
}

void Node::takeSimClock()
{
  if (sim_clock_ && sim_clock_->update()) {
    setLockstep(sim_clock_->lockstep());
  }
}

bool Node::overran(std::int64_t due_ns, std::string_view what)
{
  takeSimClock();
  if (!lockstep_ || !sim_clock_ || sim_clock_->ns() < due_ns) {
    return false;
  }
  spdlog::debug("{}: {} is {:.3f} s past its due time", module_name_, what, common::toSeconds(sim_clock_->ns() - due_ns));
  return true;
}

namespace {
/// The nodes whose work this thread is doing (their locks held), innermost last: a sample one
/// of them writes reaches a reader of another node in the process on this thread, which may
/// do that node's work there and then, but a notification of a node already at work here
/// must not take its lock again.
thread_local std::vector<const Node*> t_working;

class Working {
public:
  explicit Working(const Node* node) { t_working.push_back(node); }
  ~Working() { t_working.pop_back(); }
  Working(const Working&) = delete;
  Working& operator=(const Working&) = delete;

  static bool here(const Node* node) { return std::find(t_working.begin(), t_working.end(), node) != t_working.end(); }
};
}  // namespace

void Node::handleEvents()
{
  takeSimClock();  // events are judged against the clock as it is now
  for (const auto& event : participant_.events().drain()) {
    countLoss(event);
    onEvent(event);
  }
  countRejectedPayloads();
}

void Node::handleWake()
{
  handleEvents();
  if (fault_layer_) {
    fault_layer_->take();
  }
  takeSimClock();
  onWake();
}

bool Node::wakeOnReceipt()
{
  if (!wake_on_receipt_ || !running_.load() || Working::here(this)) {
    return false;
  }
  std::unique_lock lock(work_mutex_, std::try_to_lock);
  if (!lock.owns_lock() || !running_.load() || stop_.load()) {
    return false;  // the node's thread is at work (and will look), or it is stopping
  }
  const Working working(this);
  handleWake();
  return true;
}

void Node::run()
{
  std::unique_lock lock(work_mutex_);
  const Working working(this);
  onStart();
  publishHeartbeat(msg::MODULE_RUNNING);
  running_ = true;
  std::int64_t next_heartbeat = common::steadyTimeNs() + kHeartbeatPeriodNs;
  std::int64_t next_tick = common::steadyTimeNs() + tick_period_ns_;
  while (!stop_) {
    std::int64_t deadline = std::min(next_heartbeat, common::steadyTimeNs() + kIdleWakeNs);
    if (tick_period_ns_ > 0) {
      deadline = std::min(deadline, next_tick);
    }
    lock.unlock();
    const bool woken = waker_.waitUntil(deadline);
    lock.lock();
    if (stop_) {
      break;
    }
    if (woken) {
      handleWake();
    } else {
      handleEvents();
    }
    const std::int64_t now = common::steadyTimeNs();
    if (tick_period_ns_ > 0 && now >= next_tick) {
      takeSimClock();
      onTick(now);
      // Keep the phase; after an overrun, skip the missed ticks rather than bursting.
      next_tick += tick_period_ns_;
      if (next_tick <= now) {
        next_tick = now + tick_period_ns_;
      }
    }
    if (now >= next_heartbeat) {
      publishHeartbeat(msg::MODULE_RUNNING);
      next_heartbeat = now + kHeartbeatPeriodNs;
    }
  }
  running_ = false;
  publishHeartbeat(msg::MODULE_STOPPING);
  if (fault_layer_) {
    fault_layer_->logActive();
  }
  onStop();
}

}  // namespace quad::runtime
