// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/operator_station.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/launch/observer.hpp"
#include "quad/runtime/sim_clock.hpp"

namespace quad::launch {

namespace topics = dds::topics;

namespace {
constexpr auto kPoll = std::chrono::milliseconds(10);

msg::CommandKind toMessage(OperatorCommand c)
{
  switch (c) {
    case OperatorCommand::kArm:
      return msg::COMMAND_ARM;
    case OperatorCommand::kDisarm:
      return msg::COMMAND_DISARM;
    case OperatorCommand::kTakeoff:
      return msg::COMMAND_TAKEOFF;
    case OperatorCommand::kStartMission:
      return msg::COMMAND_START_MISSION;
    case OperatorCommand::kHold:
      return msg::COMMAND_HOLD;
    case OperatorCommand::kLand:
      return msg::COMMAND_LAND;
    case OperatorCommand::kReturn:
      return msg::COMMAND_RETURN;
  }
  return msg::COMMAND_HOLD;
}

/// Waits until `ready` or the deadline; true when ready.
template <class Ready>
bool waitUntil(std::int64_t deadline_ns, Ready ready)
{
  while (!ready()) {
    if (common::steadyTimeNs() >= deadline_ns) {
      return false;
    }
    std::this_thread::sleep_for(kPoll);
  }
  return true;
}

/// A command id that another operator (the launcher counts from 1) is unlikely to have used.
std::uint32_t freshCommandId()
{
  std::random_device random;
  std::uniform_int_distribution<std::uint32_t> id(1u << 16, 0xffffffffu);
  return id(random);
}
/// Whether one participant both writes what `answers` reads and reads what `requests` writes:
/// the module that will answer has its own reader of the request matched (other modules may
/// read the same topic, and a request written before the answerer's reader matched is lost
/// to it).
bool answererReads(const dds::ReaderEndpoint& answers, const dds::WriterEndpoint& requests)
{
  const auto answering = answers.matchedWriterParticipants();
  const auto reading = requests.matchedReaderParticipants();
  return std::any_of(answering.begin(), answering.end(), [&](const dds::ParticipantPrefix& p) {
    return std::find(reading.begin(), reading.end(), p) != reading.end();
  });
}

}  // namespace

struct OperatorStation::Endpoints {
  explicit Endpoints(dds::Participant& p)
      : command(p, topics::kVehicleCommand), acks(p, topics::kCommandAck), status(p, topics::kControlStatus), clock(p)
  {
  }
  dds::Publisher<msg::VehicleCommand> command;
  dds::Subscriber<msg::CommandAck> acks;
  dds::Subscriber<msg::ControlStatus> status;
  runtime::SimClockFollower clock;
  std::string mode;  // of the newest status taken
};

/// Only a goal's verbs need these: a latched goal writer of its own, and what tells the goal
/// ids used so far (the latched goal and path).
struct OperatorStation::GoalEndpoints {
  explicit GoalEndpoints(dds::Participant& p)
      : goal(p, topics::kGoal), goals(p, topics::kGoal), acks(p, topics::kGoalAck), paths(p, topics::kPath)
  {
  }
  dds::Publisher<msg::Goal> goal;
  dds::Subscriber<msg::Goal> goals;
  dds::Subscriber<msg::GoalAck> acks;
  dds::Subscriber<msg::Path> paths;
};

OperatorStation::OperatorStation(dds::ParticipantOptions options, double timeout_s)
    : participant_(std::move(options)),
      timeout_s_(timeout_s),
      start_ns_(common::steadyTimeNs()),
      endpoints_(std::make_unique<Endpoints>(participant_))
{
}

OperatorStation::~OperatorStation() = default;

std::int64_t OperatorStation::deadlineNs() const { return start_ns_ + common::toNanoseconds(timeout_s_); }

std::int64_t OperatorStation::stampNs()
{
  // Sim time while a simulation runs (the stamps of everything else in the run), else wall time.
  endpoints_->clock.update();
  return endpoints_->clock.seen() ? endpoints_->clock.ns() : common::wallTimeNs();
}

std::string OperatorStation::mode()
{
  waitUntil(deadlineNs(), [&] {
    for (const auto& s : endpoints_->status.takeAll()) {
      endpoints_->mode = controlModeName(static_cast<int>(s.mode()));
    }
    return !endpoints_->mode.empty();
  });
  return endpoints_->mode;
}

OperatorAnswer OperatorStation::command(OperatorCommand command, double takeoff_altitude)
{
  Endpoints& e = *endpoints_;
  // The controller is there when the participant that answers commands reads them.
  if (!waitUntil(deadlineNs(), [&] { return answererReads(e.acks, e.command); })) {
    return {OperatorAnswer::Outcome::kNoAnswer,
            fmt::format("no controller found (no writer of {}) within {} s", topics::kCommandAck.info.name, timeout_s_),
            ""};
  }
  std::this_thread::sleep_for(dds::kReaderMatchSettle);
  msg::VehicleCommand c;
  c.header().stamp_ns(stampNs());
  c.command_id(freshCommandId());
  c.kind(toMessage(command));
  c.altitude(takeoff_altitude);
  if (!e.command.write(c)) {
    return {OperatorAnswer::Outcome::kNoAnswer, fmt::format("{}: the middleware refused the command", topics::kVehicleCommand.info.name), ""};
  }
  OperatorAnswer answer{OperatorAnswer::Outcome::kNoAnswer,
                        fmt::format("no answer from the controller on {} within {} s", topics::kCommandAck.info.name,
                                    timeout_s_),
                        ""};
  waitUntil(deadlineNs(), [&] {
    for (const auto& ack : e.acks.takeAll()) {
      if (ack.command_id() == c.command_id() && ack.kind() == c.kind()) {
        answer = {ack.accepted() ? OperatorAnswer::Outcome::kTaken : OperatorAnswer::Outcome::kRefused,
                  ack.reason().to_string(), controlModeName(static_cast<int>(ack.mode()))};
        return true;
      }
    }
    return false;
  });
  return answer;
}

OperatorAnswer OperatorStation::setGoal(const Eigen::Vector3d& p_W, double tolerance)
{
  if (!p_W.allFinite()) {
    std::ostringstream p;
    p << "goal position (" << p_W.x() << ", " << p_W.y() << ", " << p_W.z() << ") is not finite";
    throw std::invalid_argument(p.str());
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw std::invalid_argument(fmt::format("goal tolerance {} m: must be a positive distance", tolerance));
  }
  goal_ = std::make_unique<GoalEndpoints>(participant_);
  GoalEndpoints& g = *goal_;
  if (!waitUntil(deadlineNs(), [&] { return answererReads(g.acks, g.goal); })) {
    return {OperatorAnswer::Outcome::kNoAnswer,
            fmt::format("no planner found (no writer of {}) within {} s", topics::kGoalAck.info.name, timeout_s_), ""};
  }
  std::this_thread::sleep_for(dds::kReaderMatchSettle);
  // The next goal id: past the latched goal (the launcher's) and the latched path's (the goal
  // the planner flies to, which may be an earlier command's).
  std::uint32_t last_id = 0;
  for (const auto& goal : g.goals.takeAll()) {
    last_id = std::max(last_id, goal.goal_id());
  }
  for (const auto& path : g.paths.takeAll()) {
    last_id = std::max(last_id, path.goal_id());
  }
  msg::Goal goal;
  goal.header().stamp_ns(stampNs());
  goal.goal_id(last_id + 1);
  goal.p_W(dds::toMessage(p_W));
  goal.yaw(std::nan(""));
  goal.tolerance(tolerance);
  g.goal.write(goal);

  OperatorAnswer answer{OperatorAnswer::Outcome::kNoAnswer,
                        fmt::format("no answer from the planner on {} within {} s", topics::kGoalAck.info.name,
                                    timeout_s_),
                        ""};
  const bool acked = waitUntil(deadlineNs(), [&] {
    for (const auto& ack : g.acks.takeAll()) {
      if (ack.goal_id() == goal.goal_id()) {
        answer = {ack.accepted() ? OperatorAnswer::Outcome::kTaken : OperatorAnswer::Outcome::kRefused,
                  ack.reason().to_string(), ""};
        return true;
      }
    }
    return false;
  });
  if (!acked || answer.outcome == OperatorAnswer::Outcome::kRefused) {
    return answer;
  }
  // Taken: the first path to it that settles whether one exists answers. A passing status
  // (no consistent search values yet, the budget ran out, the map's writer lost) waits for
  // the next.
  const std::string taken = answer.text;
  answer.text = fmt::format("{}; no path to it within {} s", taken, timeout_s_);
  waitUntil(deadlineNs(), [&] {
    for (const auto& path : g.paths.takeAll()) {
      if (path.goal_id() != goal.goal_id()) {
        continue;
      }
      if (path.status() == msg::PLAN_OK) {
        answer.text = fmt::format("{}; path of {:.1f} m", taken, path.cost());
        return true;
      }
      if (const std::string why = noPathReason(path.status()); !why.empty()) {
        answer = {OperatorAnswer::Outcome::kRefused,
                  fmt::format("goal {} at ({}, {}, {}): {}", goal.goal_id(), p_W.x(), p_W.y(), p_W.z(), why), ""};
        return true;
      }
    }
    return false;
  });
  return answer;
}

}  // namespace quad::launch
