// SPDX-License-Identifier: BSD-3-Clause
// The mode machine, table-driven: every condition in every mode.
#include "quad/control/modes.hpp"

#include <gtest/gtest.h>

#include <array>
#include <functional>

namespace quad::control {
namespace {

constexpr std::array kModes = {Mode::kDisarmed, Mode::kIdle,         Mode::kTakeoff, Mode::kMission,
                               Mode::kHover,    Mode::kLand,         Mode::kFailsafeLand, Mode::kReturn};

/// Inputs of a vehicle in the air at `t` [s], with a fresh state and a fresh path.
ModeInputs flying(double t)
{
  ModeInputs in;
  in.landed = false;
  in.path_fresh = true;
  in.t = t;
  return in;
}

/// Whether `tr` is a transition to `to` for `reason`.
testing::AssertionResult goes(const std::optional<Transition>& tr, Mode to, Reason reason)
{
  if (!tr) {
    return testing::AssertionFailure() << "no transition";
  }
  if (tr->to != to || tr->reason != reason) {
    return testing::AssertionFailure() << "to " << toString(tr->to) << " for " << toString(tr->reason);
  }
  return testing::AssertionSuccess();
}

/// A machine put into `mode` through legal transitions.
ModeMachine machineIn(Mode mode, ModeConfig config = {})
{
  ModeMachine m(config);
  ModeInputs in;
  const auto step = [&](Command c, std::function<void(ModeInputs&)> tweak = {}) {
    ModeInputs i = in;
    i.command = c;
    if (tweak) {
      tweak(i);
    }
    m.update(i);
  };
  if (mode == Mode::kDisarmed) {
    return m;
  }
  step(Command::kArm);
  if (mode == Mode::kIdle) {
    return m;
  }
  in.landed = false;
  step(Command::kTakeoff);
  if (mode == Mode::kTakeoff) {
    return m;
  }
  step(Command::kNone, [](ModeInputs& i) { i.takeoff_altitude_reached = true; });
  if (mode == Mode::kHover) {
    return m;
  }
  if (mode == Mode::kMission) {
    step(Command::kStartMission, [](ModeInputs& i) { i.path_fresh = true; });
  } else if (mode == Mode::kLand) {
    step(Command::kLand);
  } else if (mode == Mode::kFailsafeLand) {
    step(Command::kNone, [](ModeInputs& i) { i.state_fresh = false; });
  } else if (mode == Mode::kReturn) {
    for (const double t : {0.0, 1e3}) {  // no path for longer than any hold
      step(Command::kNone, [t](ModeInputs& i) {
        i.no_path = true;
        i.t = t;
      });
    }
  }
  EXPECT_EQ(m.mode(), mode);
  return m;
}

struct Row {
  const char* condition;
  std::function<void(ModeInputs&)> apply;
  std::array<Mode, 8> expected;  // in the order of kModes
};

TEST(Modes, EveryConditionInEveryMode)
{
  using enum Mode;
  const Mode D = kDisarmed, I = kIdle, T = kTakeoff, M = kMission, H = kHover, L = kLand, F = kFailsafeLand,
             R = kReturn;
  const std::vector<Row> table = {
      //                                                         DISARMED IDLE TAKEOFF MISSION HOVER LAND FAILSAFE RETURN
      {"nothing", [](ModeInputs&) {}, {D, I, T, M, H, L, F, R}},
      {"arm", [](ModeInputs& i) { i.command = Command::kArm; }, {I, I, T, M, H, L, F, R}},
      {"disarm", [](ModeInputs& i) { i.command = Command::kDisarm; }, {D, D, T, M, H, L, F, R}},
      {"takeoff", [](ModeInputs& i) { i.command = Command::kTakeoff; }, {D, T, T, M, H, L, F, R}},
      {"start mission", [](ModeInputs& i) { i.command = Command::kStartMission; }, {D, I, T, M, M, L, F, R}},
      {"hold", [](ModeInputs& i) { i.command = Command::kHold; }, {D, I, H, H, H, H, F, H}},
      {"land", [](ModeInputs& i) { i.command = Command::kLand; }, {D, I, L, L, L, L, F, L}},
      {"state stale", [](ModeInputs& i) { i.state_fresh = false; }, {D, I, F, F, F, F, F, F}},
      // The IMU carries the last state on: hold, for it to come back; a landing goes on.
      {"state stale, dead reckoning", [](ModeInputs& i) { i.state_fresh = false; i.dead_reckoning = true; },
       {D, I, H, H, H, F, F, H}},
      {"path stale", [](ModeInputs& i) { i.path_fresh = false; }, {D, I, T, H, H, L, F, R}},
      {"landed", [](ModeInputs& i) { i.landed = true; }, {D, I, T, M, H, I, I, R}},
      {"altitude reached", [](ModeInputs& i) { i.takeoff_altitude_reached = true; }, {D, I, H, M, H, L, F, R}},
      {"goal reached", [](ModeInputs& i) { i.goal_reached = true; }, {D, I, T, H, H, L, F, R}},
      // A goal that ends the mission: land there (only a mission reaches it).
      {"goal reached, land there", [](ModeInputs& i) { i.goal_reached = true; i.land_at_goal = true; },
       {D, I, T, L, H, L, F, R}},
      {"no path", [](ModeInputs& i) { i.no_path = true; i.path_fresh = false; }, {D, I, T, H, H, L, F, R}},
      {"returned", [](ModeInputs& i) { i.returned = true; }, {D, I, T, M, H, L, F, L}},
      // Pushed out of the keep-in volume: hold (HOVER, reason geofence); the landings and
      // RETURN carry on.
      {"outside the geofence", [](ModeInputs& i) { i.outside_geofence = true; }, {D, I, H, H, H, L, F, R}},
      // Only the way back is left above the reserve: return (a take-off is refused); the
      // landings and RETURN carry on.
      {"battery low", [](ModeInputs& i) { i.battery_low = true; }, {D, I, R, R, R, L, F, R}},
      {"battery low, takeoff", [](ModeInputs& i) { i.battery_low = true; i.command = Command::kTakeoff; },
       {D, I, R, R, R, L, F, R}},
      // Nearly empty or a cell failed: land where the vehicle is, whatever it was doing.
      {"battery critical", [](ModeInputs& i) { i.battery_critical = true; }, {D, I, L, L, L, L, F, L}},
      {"battery critical, takeoff", [](ModeInputs& i) { i.battery_critical = true; i.command = Command::kTakeoff; },
       {D, I, L, L, L, L, F, L}},
      // Return to launch, commanded or on a lost link (the default policy); on the ground,
      // landing or returning already, nothing.
      {"return", [](ModeInputs& i) { i.command = Command::kReturn; }, {D, I, R, R, R, L, F, R}},
      {"link lost", [](ModeInputs& i) { i.link_lost = true; }, {D, I, R, R, R, L, F, R}},
      // The estimate's 1-sigma past its bounds: hold (a take-off is refused); the landings
      // and RETURN carry on.
      {"estimate uncertain", [](ModeInputs& i) { i.estimate_uncertain = true; }, {D, I, H, H, H, L, F, R}},
      {"estimate uncertain, takeoff", [](ModeInputs& i) { i.estimate_uncertain = true; i.command = Command::kTakeoff; },
       {D, I, H, H, H, L, F, R}},
      // Only a controller started in flight is disarmed in the air: it takes over.
      {"in the air", [](ModeInputs& i) { i.landed = false; }, {H, I, T, M, H, L, F, R}},
  };
  for (const Row& row : table) {
    for (std::size_t k = 0; k < kModes.size(); ++k) {
      ModeMachine m = machineIn(kModes[k]);
      ModeInputs in;
      in.landed = !airborne(kModes[k]);
      in.path_fresh = true;
      row.apply(in);
      m.update(in);
      EXPECT_EQ(m.mode(), row.expected[k])
          << row.condition << " in " << toString(kModes[k]) << ": got " << toString(m.mode());
    }
  }
}

/// What the machine did with a command: took it and changed mode (A), took it with nothing to
/// change (N), or refused it, saying why (X).
enum Answer { A, N, X };

TEST(Modes, EveryCommandInEveryModeIsTakenOrRefusedSayingWhy)
{
  const std::vector<std::pair<Command, std::array<Answer, 8>>> table = {
      //                            DISARMED IDLE TAKEOFF MISSION HOVER LAND FAILSAFE RETURN
      {Command::kArm,          {A, N, X, X, X, X, X, X}},
      {Command::kDisarm,       {N, A, X, X, X, X, X, X}},
      {Command::kTakeoff,      {X, A, X, X, X, X, X, X}},
      {Command::kStartMission, {X, X, X, N, A, X, X, X}},
      {Command::kHold,         {X, X, A, A, N, A, X, A}},
      {Command::kLand,         {X, X, A, A, A, N, X, A}},
      {Command::kReturn,       {X, X, A, A, A, X, X, N}},
  };
  for (const auto& [command, answers] : table) {
    for (std::size_t k = 0; k < kModes.size(); ++k) {
      ModeMachine m = machineIn(kModes[k]);
      ModeInputs in;
      in.landed = !airborne(kModes[k]);
      in.path_fresh = true;
      in.command = command;
      const auto tr = m.update(in);
      const std::string where = std::string(toString(command)) + " in " + std::string(toString(kModes[k]));
      switch (answers[k]) {
        case A:
          ASSERT_TRUE(tr.has_value()) << where;
          EXPECT_EQ(tr->reason, Reason::kCommanded) << where;
          EXPECT_TRUE(tr->why.starts_with("commanded: ")) << where << ": " << tr->why;
          EXPECT_TRUE(m.refused().empty()) << where << ": " << m.refused();
          break;
        case N:
          EXPECT_FALSE(tr.has_value()) << where;
          EXPECT_TRUE(m.refused().empty()) << where << ": " << m.refused();
          break;
        case X:
          EXPECT_FALSE(tr.has_value()) << where << " -> " << toString(m.mode());
          EXPECT_TRUE(m.refused().starts_with(std::string(toString(command)) + " refused in " +
                                              std::string(toString(kModes[k])) + ": "))
              << where << ": '" << m.refused() << "'";
          break;
      }
    }
  }
}

TEST(Modes, AHoldTheOperatorCommandedLastsUntilTheMissionIsCommandedAgain)
{
  ModeConfig config;
  config.auto_mission = true;
  ModeMachine m = machineIn(Mode::kMission, config);
  ModeInputs in;
  in.landed = false;
  in.path_fresh = true;
  in.command = Command::kHold;
  ASSERT_EQ(m.update(in)->to, Mode::kHover);
  // A fresh path, the goal not reached: auto_mission would start; the operator's hold stands.
  in.command = Command::kNone;
  for (int i = 0; i < 10; ++i) {
    in.t += 0.1;
    EXPECT_FALSE(m.update(in).has_value());
  }
  in.command = Command::kStartMission;
  ASSERT_EQ(m.update(in)->to, Mode::kMission);
  // A hold for another reason (the path went stale) resumes by itself.
  in.command = Command::kNone;
  in.path_fresh = false;
  ASSERT_EQ(m.update(in)->to, Mode::kHover);
  in.path_fresh = true;
  EXPECT_EQ(m.update(in)->to, Mode::kMission);
}

TEST(Modes, AControllerStartedInFlightTakesOverWhateverIsAskedOnceItHasAFreshState)
{
  ModeMachine m;
  ModeInputs in;
  in.landed = false;
  in.state_fresh = false;
  in.command = Command::kArm;
  EXPECT_FALSE(m.update(in).has_value());  // no state yet: nothing to hold
  EXPECT_EQ(m.mode(), Mode::kDisarmed);
  in.state_fresh = true;
  const auto tr = m.update(in);
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->from, Mode::kDisarmed);
  EXPECT_EQ(tr->to, Mode::kHover);
  EXPECT_EQ(tr->why, "took over in the air: holding position");
}

TEST(Modes, NothingArmsAVehicleWhoseFootingIsNotJudgedYet)
{
  ModeMachine m;
  ModeInputs in;
  in.landed = true;  // the land detector's word while it waits for the rangefinder
  in.landing_judged = false;
  in.command = Command::kArm;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.mode(), Mode::kDisarmed);
  EXPECT_EQ(m.refused(), "arm refused in DISARMED: what the vehicle stands on is not judged yet (waiting for the rangefinder)");
  in.landing_judged = true;
  const auto tr = m.update(in);
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->to, Mode::kIdle);
}

TEST(Modes, LeavingTheGeofenceHoldsThenReturnsAndLandsSayingWhy)
{
  ModeConfig config;
  config.geofence_return_after = 2.0;
  ModeMachine m = machineIn(Mode::kMission, config);
  ModeInputs in = flying(10.0);
  in.outside_geofence = true;
  auto tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kHover, Reason::kGeofence));
  // Back inside, with a path: the hold still runs its course, and no mission starts.
  in.outside_geofence = false;
  in.t = 11.0;
  in.command = Command::kStartMission;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.refused(), "start mission refused in HOVER: holding after leaving the geofence");
  in.command = Command::kNone;
  in.t = 11.9;
  EXPECT_FALSE(m.update(in).has_value());
  in.t = 12.0;
  tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kReturn, Reason::kGeofence));
  // Outside again on the way back: RETURN carries on.
  in.outside_geofence = true;
  EXPECT_FALSE(m.update(in).has_value());
  in.returned = true;
  EXPECT_EQ(m.update(in)->to, Mode::kLand);
  in.landed = true;
  tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kIdle, Reason::kGeofence));
}

TEST(Modes, AnUncertainEstimateHoldsThenLandsUnlessItComesBack)
{
  ModeConfig config;
  config.uncertain_land_after = 4.0;
  config.auto_mission = true;
  ModeMachine m = machineIn(Mode::kMission, config);
  ModeInputs in = flying(10.0);
  in.estimate_uncertain = true;
  auto tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kHover, Reason::kEstimateUncertain));
  // Holding, with a fresh path: no mission starts by itself or by command.
  in.t = 11.0;
  EXPECT_FALSE(m.update(in).has_value());
  in.command = Command::kStartMission;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.refused(), "start mission refused in HOVER: holding on an uncertain state estimate");
  in.command = Command::kNone;
  // A fix brings the estimate back within its bounds: the mission resumes.
  in.t = 13.0;
  in.estimate_uncertain = false;
  tr = m.update(in);
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->to, Mode::kMission);
  // Uncertain again, for good: the hold counts anew, and lands after 4 s of it.
  in.estimate_uncertain = true;
  in.t = 20.0;
  EXPECT_EQ(m.update(in)->to, Mode::kHover);
  in.t = 23.9;
  EXPECT_FALSE(m.update(in).has_value());
  in.t = 24.0;
  tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kLand, Reason::kEstimateUncertain));
  in.landed = true;
  tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kIdle, Reason::kEstimateUncertain));  // why the flight ended
  // On the ground, no take-off on it.
  in.command = Command::kTakeoff;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.refused(), "takeoff refused in IDLE: the state estimate is uncertain");
}

TEST(Modes, AReturnOnAnUncertainEstimateLandsAfterTheSameTime)
{
  ModeConfig config;
  config.uncertain_land_after = 4.0;
  ModeMachine m = machineIn(Mode::kReturn, config);
  ModeInputs in;
  in.landed = false;
  in.t = 2000.0;
  in.estimate_uncertain = true;
  EXPECT_FALSE(m.update(in).has_value());  // the return carries on
  in.t = 2003.9;
  EXPECT_FALSE(m.update(in).has_value());
  in.t = 2004.0;
  const auto tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kLand, Reason::kEstimateUncertain));
}

TEST(Modes, ALowBatteryReturnsAndACriticalOneLandsWhereItIsSayingWhy)
{
  ModeMachine m = machineIn(Mode::kMission);
  ModeInputs in = flying(20.0);
  in.battery_low = true;
  auto tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kReturn, Reason::kBatteryLow));
  EXPECT_EQ(tr->why, "battery low: returning to land at the take-off point");
  // On the way back the operator cannot send it off again, nor park it.
  for (const Command c : {Command::kStartMission, Command::kHold}) {
    in.command = c;
    EXPECT_FALSE(m.update(in).has_value());
    EXPECT_EQ(m.mode(), Mode::kReturn);
  }
  EXPECT_EQ(m.refused(), "hold refused in RETURN: returning on a low battery");
  in.command = Command::kNone;
  // The pack fails on the way: land where it is.
  in.battery_critical = true;
  tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kLand, Reason::kBatteryCritical));
  EXPECT_EQ(tr->why, "battery critical: landing where it is");
  in.landed = true;
  tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kIdle, Reason::kBatteryCritical));
  // On the ground, no take-off on that pack.
  in.command = Command::kTakeoff;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.refused(), "takeoff refused in IDLE: battery critical");
}

TEST(Modes, ALostLinkReturnsOrLandsOrDoesNothingByPolicy)
{
  for (const auto& [policy, expected] : {std::pair{LinkLossAction::kReturn, Mode::kReturn},
                                         std::pair{LinkLossAction::kLand, Mode::kLand},
                                         std::pair{LinkLossAction::kNone, Mode::kMission}}) {
    ModeConfig config;
    config.link_loss = policy;
    ModeMachine m = machineIn(Mode::kMission, config);
    ModeInputs in;
    in.landed = false;
    in.path_fresh = true;
    in.link_lost = true;
    const auto tr = m.update(in);
    EXPECT_EQ(m.mode(), expected);
    if (expected != Mode::kMission) {
      ASSERT_TRUE(tr.has_value());
      EXPECT_EQ(tr->reason, Reason::kLinkLost);
    }
    // The link back: what the failsafe began goes on, until the operator commands again.
    in.link_lost = false;
    EXPECT_FALSE(m.update(in).has_value());
    EXPECT_EQ(m.mode(), expected);
  }
  // A return commanded while landing is refused, saying why.
  ModeMachine m = machineIn(Mode::kLand);
  ModeInputs in;
  in.landed = false;
  in.command = Command::kReturn;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.refused(), "return refused in LAND: landing already");
}

TEST(Modes, TransitionsCarryTheirReason)
{
  ModeMachine m = machineIn(Mode::kMission);
  ModeInputs in;
  in.landed = false;
  in.path_fresh = false;
  const auto tr = m.update(in);
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->from, Mode::kMission);
  EXPECT_EQ(tr->to, Mode::kHover);
  EXPECT_EQ(tr->reason, Reason::kPathStale);
  in.state_fresh = false;
  EXPECT_EQ(m.update(in)->reason, Reason::kStateStale);
}

TEST(Modes, AStaleStateIsHeldOnDeadReckoningUntilItComesBackOrTheHoldEnds)
{
  ModeConfig config;
  config.state_stale_land_after = 1.5;
  config.auto_mission = true;
  ModeMachine m = machineIn(Mode::kMission, config);
  ModeInputs in = flying(10.0);
  in.state_fresh = false;
  in.dead_reckoning = true;
  auto tr = m.update(in);
  ASSERT_TRUE(goes(tr, Mode::kHover, Reason::kStateStale));
  in.t = 11.0;
  in.command = Command::kStartMission;
  EXPECT_FALSE(m.update(in).has_value());
  EXPECT_EQ(m.refused(), "start mission refused in HOVER: holding without a vehicle state");
  in.command = Command::kNone;
  // Back: the mission resumes.
  in.state_fresh = true;
  in.dead_reckoning = false;
  EXPECT_EQ(m.update(in)->to, Mode::kMission);
  // Stale again, the hold counts anew; the reckoning's end lands at once.
  in.t = 20.0;
  in.state_fresh = false;
  in.dead_reckoning = true;
  EXPECT_EQ(m.update(in)->to, Mode::kHover);
  in.t = 21.0;
  in.dead_reckoning = false;
  tr = m.update(in);
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->to, Mode::kFailsafeLand);
  // And the hold's end lands too.
  ModeMachine again = machineIn(Mode::kMission, config);
  in.t = 30.0;
  in.dead_reckoning = true;
  EXPECT_EQ(again.update(in)->to, Mode::kHover);
  in.t = 31.49;
  EXPECT_FALSE(again.update(in).has_value());
  in.t = 31.5;
  tr = again.update(in);
  ASSERT_TRUE(tr.has_value());
  EXPECT_EQ(tr->to, Mode::kFailsafeLand);
  EXPECT_EQ(tr->why, "vehicle state stale too long: landing");
}

TEST(Modes, StalePathInHoverLandsAfterItsTimeout)
{
  ModeConfig config;
  config.path_stale_land_after = 5.0;
  ModeMachine m = machineIn(Mode::kMission, config);
  ModeInputs in;
  in.landed = false;
  in.path_fresh = false;
  in.t = 10.0;
  m.update(in);
  ASSERT_EQ(m.mode(), Mode::kHover);
  in.t = 14.9;
  m.update(in);
  EXPECT_EQ(m.mode(), Mode::kHover);
  in.t = 15.0;
  const auto tr = m.update(in);
  EXPECT_EQ(m.mode(), Mode::kLand);
  EXPECT_EQ(tr->reason, Reason::kPathStale);
}

TEST(Modes, NoPathHoldsThenLandsUnlessAPathComesBack)
{
  // GIVEN a mission, and a planner that says the goal cannot be reached
  ModeConfig config;
  config.no_path_land_after = 5.0;
  config.auto_mission = true;
  ModeMachine m = machineIn(Mode::kMission, config);
  ModeInputs in;
  in.landed = false;
  in.no_path = true;
  in.t = 10.0;
  // WHEN it says so: the vehicle holds, for the stated reason
  auto tr = m.update(in);
  ASSERT_EQ(m.mode(), Mode::kHover);
  EXPECT_EQ(tr->reason, Reason::kNoPath);
  // THEN a path that comes back within the hold resumes the mission
  in.t = 12.0;
  in.no_path = false;
  in.path_fresh = true;
  m.update(in);
  EXPECT_EQ(m.mode(), Mode::kMission);
  // and one that does not lands it after the hold, counted from when it was last said
  in.no_path = true;
  in.path_fresh = false;
  in.t = 20.0;
  m.update(in);
  ASSERT_EQ(m.mode(), Mode::kHover);
  in.t = 24.9;
  m.update(in);
  EXPECT_EQ(m.mode(), Mode::kHover);
  in.t = 25.0;
  tr = m.update(in);
  EXPECT_EQ(m.mode(), Mode::kReturn);
  EXPECT_EQ(tr->reason, Reason::kNoPath);
  // back above the take-off point, it lands there, and says why
  in.t = 40.0;
  in.returned = true;
  tr = m.update(in);
  EXPECT_EQ(m.mode(), Mode::kLand);
  EXPECT_EQ(tr->reason, Reason::kNoPath);
}

TEST(Modes, NoPathRightAfterTakeOffLandsToo)
{
  ModeConfig config;
  config.no_path_land_after = 2.0;
  ModeMachine m = machineIn(Mode::kHover, config);
  ModeInputs in;
  in.landed = false;
  in.no_path = true;
  in.t = 3.0;
  m.update(in);
  EXPECT_EQ(m.mode(), Mode::kHover);
  in.t = 5.0;
  EXPECT_EQ(m.update(in)->reason, Reason::kNoPath);
  EXPECT_EQ(m.mode(), Mode::kReturn);
}

TEST(Modes, IdleDisarmsAfterItsTimeoutAndAutoMissionStartsWithAPath)
{
  ModeConfig config;
  config.idle_disarm_after = 10.0;
  config.auto_mission = true;
  ModeMachine idle = machineIn(Mode::kIdle, config);
  ModeInputs in;
  in.t = 10.0;
  idle.update(in);
  EXPECT_EQ(idle.mode(), Mode::kDisarmed);

  ModeMachine hover = machineIn(Mode::kHover, config);
  ModeInputs air;
  air.landed = false;
  air.path_fresh = true;
  hover.update(air);
  EXPECT_EQ(hover.mode(), Mode::kMission);
}

TEST(Modes, RefusedCommandsSayWhy)
{
  ModeMachine flying = machineIn(Mode::kHover);
  ModeInputs in;
  in.landed = false;
  in.command = Command::kDisarm;
  EXPECT_FALSE(flying.update(in).has_value());
  EXPECT_EQ(flying.refused(), "disarm refused in HOVER: the vehicle is in the air");
  in.command = Command::kStartMission;
  in.path_fresh = false;
  flying.update(in);
  EXPECT_EQ(flying.refused(), "start mission refused in HOVER: no fresh path");
  ModeMachine ground;
  ModeInputs g;
  g.command = Command::kTakeoff;
  ground.update(g);
  EXPECT_EQ(ground.refused(), "takeoff refused in DISARMED: arm first");
}

}  // namespace
}  // namespace quad::control
