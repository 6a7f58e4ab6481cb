// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The skeleton every quad node shares (as Fast DDS's example applications share theirs):
/// the constructor creates every entity and fails loudly, the destructor releases them,
/// run() loops on a Waker with a tick period until stop() — from a signal or another thread.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include <quad/msg/Heartbeat.h>

#include "quad/common/params.hpp"
#include "quad/dds/liveliness.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/waker.hpp"
#include "quad/runtime/due_queue.hpp"
#include "quad/runtime/sim_clock.hpp"

namespace quad::runtime {

class FaultLayerControl;  // fault_layer_control.hpp: the node's side of its datagram fault layer

/// Turns SIGINT and SIGTERM into a callback on an ordinary thread. Construct it first in
/// main(), before any other thread exists, so that every thread inherits the blocked mask.
class SignalWatcher {
public:
  SignalWatcher();
  ~SignalWatcher();
  SignalWatcher(const SignalWatcher&) = delete;
  SignalWatcher& operator=(const SignalWatcher&) = delete;

  /// Called once per signal received; replaces any earlier callback.
  void onSignal(std::function<void(int)> callback);
  /// The last signal received, 0 if none.
  int received() const { return received_.load(); }

private:
  void watch();
  std::atomic<bool> quit_{false};
  std::atomic<int> received_{0};
  std::mutex mutex_;
  std::function<void(int)> callback_;
  std::thread thread_;
};

/// Counters a node reports in its heartbeat.
struct NodeCounters {
  std::atomic<std::uint64_t> samples_in{0};
  std::atomic<std::uint64_t> samples_out{0};
  std::atomic<std::uint64_t> errors{0};
  std::atomic<std::uint64_t> samples_lost{0};  ///< on topics that promise every sample
};

/// A heartbeat of this process: `module_name`, this host's name and this process's id, in
/// `state`, stamped `stamp_ns`; the counters are the caller's to fill.
msg::Heartbeat processHeartbeat(const std::string& module_name, msg::ModuleState state, std::int64_t stamp_ns);

class Node {
public:
  /// `module_name` names the node in heartbeats and logs ("plant", "control"); `participant`
  /// is its handle on the process's participant, its own or one it shares with the other
  /// nodes of a container.
  Node(std::string module_name, dds::Participant participant);
  /// A node on a participant of its own.
  Node(std::string module_name, dds::ParticipantOptions options);
  virtual ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  /// Runs until stop(). Drains endpoint events, calls onWake() when data may have arrived and
  /// onTick() at the tick period, and publishes a heartbeat at 2 Hz.
  void run();
  /// Thread-safe; run() returns soon after.
  void stop();
  bool stopping() const { return stop_.load(); }
  /// After run() returned: stops what the node keeps running besides (its heartbeat's
  /// liveliness), so that its process may remove the participant under it and end without
  /// destroying it.
  void quiesce() { heartbeat_alive_.stop(); }

  dds::Participant& participant() { return participant_; }
  const std::string& moduleName() const { return module_name_; }

  /// A datagram fault of this node's fault layer has (had) this id: a FAULT_CLEAR with it is
  /// the layer's, not the module's own.
  bool isDatagramFaultId(std::uint32_t id) const;

protected:
  /// The Waker to give every Subscriber of this node.
  dds::Waker* waker() { return &waker_; }
  NodeCounters& counters() { return counters_; }
  /// 0 (the default) for no ticks.
  void setTickPeriod(std::int64_t period_ns) { tick_period_ns_ = period_ns; }
  /// Arriving samples are handled on the middleware's thread that received them, when the
  /// node's own thread is not busy: onWake() runs there and then (under the node's lock, as
  /// everything run() calls does), instead of that thread waking this one for it. For a
  /// node on the lockstep clock's critical path whose onWake() is short (the estimator, the
  /// controller): each sample then costs one thread woken, not two. Call from the
  /// constructor.
  void setWakeOnReceipt(bool on) { wake_on_receipt_ = on; }
  /// In lockstep, sim time waits for the slowest module: wall-clock deadlines say nothing,
  /// and onEvent's default stops reporting them. From the start as the environment says
  /// (ParticipantOptions::lockstep), then as the sim clock says.
  void setLockstep(bool lockstep) { lockstep_ = lockstep; }
  bool lockstep() const { return lockstep_; }
  /// Follows the plant's clock: run() takes its samples before every onWake() and onTick(),
  /// and lockstep() follows the newest. Call once, from the constructor. `depth`: as the
  /// SimClockFollower's.
  void followSimClock(std::int32_t depth = 0);
  /// The clock followed (followSimClock() first).
  const SimClockFollower& simClock() const { return *sim_clock_; }
  /// Takes the clock samples that arrived: run() does before every onWake() and onTick(); a
  /// node whose work takes long calls it to know where the clock got meanwhile.
  void takeSimClock();
  /// Takes every unread sample of `reader`, each counted as an input: in lockstep held in
  /// `due` until the first time handled after its stamp (dueAfter: a state stamped t is
  /// answered with what was stamped before t), otherwise handed to `apply` at once.
  template <typename T, typename Apply>
  void takeDueAfterStamp(dds::Subscriber<T>& reader, DueQueue<T>& due, Apply&& apply)
  {
    while (auto sample = reader.take()) {
      counters_.samples_in++;
      if (lockstep_) {
        due.hold(dueAfter(sample->header().stamp_ns()), std::move(*sample));
      } else {
        apply(*sample);
      }
    }
  }
  /// For an output due at `due_ns` about to go out: takes the clock's samples and, in
  /// lockstep, says whether the clock reached that time first (it waits there for the output:
  /// an overrun, which the caller counts), logging how far past it is at debug level as `what`.
  bool overran(std::int64_t due_ns, std::string_view what);

  virtual void onStart() {}
  virtual void onWake() {}
  virtual void onTick(std::int64_t /*steady_ns*/) {}
  /// Default: logs the event (deadline misses at most once a second; none in lockstep).
  virtual void onEvent(const dds::EndpointEvent& event);
  virtual void onStop() {}

private:
  /// The events that came (onEvent), judged against the clock as it is now, and the
  /// payloads refused. The node's lock held.
  void handleEvents();
  /// What a notification of the waker asks for: the events, the fault layer's commands, the
  /// clock and onWake(). The node's lock held.
  void handleWake();
  /// The waker's runner: handleWake() on the notifying thread, when wake-on-receipt is on,
  /// the node runs and its lock is free; false otherwise (the loop is woken).
  bool wakeOnReceipt();
  void publishHeartbeat(msg::ModuleState state);
  /// Adds a reader's lost samples to the heartbeat's count, on topics that promise every one.
  void countLoss(const dds::EndpointEvent& event);
  /// Payloads of the types its readers take refused for breaking their IDL (message_types.hpp),
  /// and, in the node that made the participant, datagrams the validating transport dropped,
  /// count as rejected inputs.
  void countRejectedPayloads();

  std::string module_name_;
  dds::Participant participant_;
  dds::Waker waker_;
  NodeCounters counters_;
  dds::Publisher<msg::Heartbeat> heartbeat_;
  // With a fault layer only (ParticipantOptions::fault_layer).
  std::unique_ptr<FaultLayerControl> fault_layer_;
  std::unique_ptr<SimClockFollower> sim_clock_;  // with followSimClock() only
  std::atomic<bool> stop_{false};
  bool wake_on_receipt_ = false;
  std::atomic<bool> running_{false};  // between onStart() and onStop(): onWake() may run
  std::mutex work_mutex_;             // held while anything of the node runs
  dds::LivelinessKeeper heartbeat_alive_{heartbeat_};  // a node busy in a long computation stays alive
  std::int64_t tick_period_ns_ = 0;
  bool lockstep_ = false;
  std::int64_t last_deadline_log_ns_ = 0;
  std::uint64_t rejected_payloads_ = 0;          // of its readers' types
  std::uint64_t process_rejected_payloads_ = 0;  // the process's count when it last looked
  std::uint64_t malformed_datagrams_ = 0;
};

}  // namespace quad::runtime
