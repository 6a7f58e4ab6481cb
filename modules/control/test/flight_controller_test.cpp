// SPDX-License-Identifier: BSD-3-Clause
// The whole controller core flying the plant simulation: missions, failsafes, fuzzing.
#include "quad/control/flight_controller.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "closed_loop.hpp"
#include "quad/common/time.hpp"
#include "quad/geometry/so3.hpp"
#include "quad/plant/simulation.hpp"

namespace quad::control {
namespace {

struct Rig {
  vehicle::VehicleParams v = test::loadVehicle("x500");
  plant::Simulation sim;
  FlightController fc;
  std::vector<FlightOutput> log;
  bool feed_state = true;
  bool feed_imu = true;
  /// The operator's station sends its heartbeat every half second up to this sim time.
  double operator_until = -1.0;
  double operator_next = 0.0;
  bool tell_landed = true;  ///< false: the states do not say (an estimate); the land detector judges

  explicit Rig(FlightControllerConfig config = defaults(), plant::SimulationConfig plant = {},
               std::vector<plant::Fault> faults = {})
      : Rig(world::World(world::Bounds{Vector3(-50, -50, 0), Vector3(50, 50, 30)}, Vector3::Zero(), Vector3(10, 0, 2), {}),
            config, plant, std::move(faults))
  {
  }
  Rig(world::World world, FlightControllerConfig config, plant::SimulationConfig plant = {},
      std::vector<plant::Fault> faults = {})
      : sim(v, std::move(world), plant, std::move(faults)), fc(v, withGains(config, v))
  {
  }

  static FlightControllerConfig defaults()
  {
    FlightControllerConfig c;
    c.modes.idle_disarm_after = 1e9;
    return c;
  }
  static FlightControllerConfig withGains(FlightControllerConfig c, const vehicle::VehicleParams& v)
  {
    c.gains = test::scaledGains(v);
    return c;
  }
  double t() const { return common::toSeconds(sim.timeNs()); }

  /// Runs until `done` or `seconds` of sim time pass; the controller answers every state.
  void run(double seconds, const std::function<bool()>& done = [] { return false; })
  {
    const double end = t() + seconds;
    while (t() < end && !done()) {
      const plant::StepOutputs out = sim.step();
      if (out.imu && feed_imu) {
        fc.onImu({out.imu->sample.specific_force_B, out.imu->sample.angular_rate_B},
                 common::toSeconds(out.imu->t_ns));
      }
      if (t() < operator_until && t() >= operator_next) {
        fc.onOperatorHeartbeat(t());
        operator_next = t() + 0.5;
      }
      if (out.range) {
        fc.onRange(out.range->range.value_or(std::numeric_limits<double>::infinity()), out.range->max_range,
                   common::toSeconds(out.range->t_ns));
      }
      if (out.range_up) {
        fc.onRangeUp(out.range_up->range.value_or(std::numeric_limits<double>::infinity()), out.range_up->max_range,
                     common::toSeconds(out.range_up->t_ns));
      }
      if (out.battery) {
        const plant::BatteryReading& b = *out.battery;
        fc.onBattery({b.voltage, b.current, b.charge, b.capacity, b.cells}, common::toSeconds(b.t_ns));
      }
      if (out.state && feed_state) {
        const auto& s = out.state->state;
        fc.onState({s.p_W, s.v_W, s.q_WB, s.w_B}, common::toSeconds(out.state->t_ns),
                   {.landed = tell_landed ? std::optional<bool>(s.landed) : std::nullopt});
      }
      if (out.state) {
        log.push_back(fc.update(t()));
        sim.commands().submit(log.back().rotor_speed, log.back().armed, sim.timeNs(), sim.timeNs());
      }
    }
  }
  Mode mode() const { return fc.mode(); }
};

/// Arms, takes off and waits for the hover at the take-off altitude.
void takeOff(Rig& rig)
{
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  rig.fc.onCommand(Command::kTakeoff);
  rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
}

/// After 0.1 s on the ground, arms and asks for a take-off at the configured altitude: the
/// answer, which must be a refusal starting with `reason`; the vehicle stays idle.
void expectTakeOffRefused(Rig& rig, const std::string& reason)
{
  rig.run(0.1);
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  rig.fc.onCommand(Command::kTakeoff);
  rig.run(0.05, [&] { return !rig.log.empty() && rig.log.back().answer.has_value(); });
  ASSERT_TRUE(rig.log.back().answer.has_value());
  EXPECT_FALSE(rig.log.back().answer->accepted);
  EXPECT_TRUE(rig.log.back().answer->reason.starts_with(reason)) << rig.log.back().answer->reason;
  EXPECT_EQ(rig.mode(), Mode::kIdle);
}

TEST(FlightController, ArmTakeOffFlyTheMissionAndLand)
{
  Rig rig;
  rig.run(0.1);
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  ASSERT_EQ(rig.mode(), Mode::kIdle);
  rig.fc.onCommand(Command::kTakeoff);
  rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_NEAR(rig.sim.state().p_W.z(), 2.0, 0.1);
  const std::vector<Vector3> path = {{0, 0, 2}, {5, 0, 2}, {5, 5, 3}, {10, 5, 2}};
  rig.fc.onGoal(path.back(), 0.3);
  rig.fc.onPath(path, 1, PathKind::kOk, rig.t());
  rig.fc.onCommand(Command::kStartMission);
  // The planner re-publishes its path; here every 0.5 s.
  double next_path = rig.t() + 0.5;
  rig.run(40.0, [&] {
    if (rig.t() >= next_path) {
      rig.fc.onPath(path, 1, PathKind::kOk, rig.t());
      next_path += 0.5;
    }
    return rig.log.back().transition && rig.log.back().transition->why == "goal reached";
  });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_EQ(rig.log.back().transition->why, "goal reached");
  EXPECT_LT((rig.sim.state().p_W - path.back()).norm(), 0.3);
  rig.fc.onCommand(Command::kLand);
  rig.run(20.0, [&] { return rig.mode() == Mode::kIdle; });
  EXPECT_EQ(rig.mode(), Mode::kIdle);
  EXPECT_TRUE(rig.sim.state().landed);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

TEST(FlightController, WithoutTheGroundContactTheLandDetectorEndsTheFlightOnceTouchedDown)
{
  Rig rig;
  rig.tell_landed = false;
  rig.run(0.1);
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  ASSERT_EQ(rig.mode(), Mode::kIdle) << "on the ground at the first state: landed";
  rig.fc.onCommand(Command::kTakeoff);
  rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_FALSE(rig.fc.landed());
  rig.fc.onCommand(Command::kLand);
  double touchdown = -1.0;
  rig.run(20.0, [&] {
    if (touchdown < 0.0 && rig.sim.state().landed) {
      touchdown = rig.t();
    }
    return rig.mode() == Mode::kIdle;
  });
  ASSERT_EQ(rig.mode(), Mode::kIdle);
  ASSERT_GE(touchdown, 0.0) << "IDLE before the plant touched down";
  // Landed after the detector's hold (0.5 s), within a second of the touchdown.
  EXPECT_GE(rig.t() - touchdown, 0.5);
  EXPECT_LT(rig.t() - touchdown, 1.5);
  EXPECT_TRUE(rig.sim.state().landed);
}

TEST(FlightController, AControllerStartedInTheAirWithoutTheGroundContactTakesOver)
{
  Rig rig;
  takeOff(rig);
  ASSERT_EQ(rig.mode(), Mode::kHover);
  // A new controller (a restart) on states that do not say whether the vehicle is landed.
  rig.fc = FlightController(rig.v, Rig::withGains(Rig::defaults(), rig.v));
  rig.tell_landed = false;
  rig.run(0.1);
  EXPECT_EQ(rig.mode(), Mode::kHover);
  EXPECT_FALSE(rig.fc.landed());
  EXPECT_NEAR(rig.sim.state().p_W.z(), 2.0, 0.3);
}

TEST(FlightController, OnAPlatformTheRangefinderSaysTheVehicleStandsAndItArmsAndTakesOffFromThere)
{
  // A 2.5 m platform under the start: far above the ground plane, yet the vehicle stands.
  Rig rig(world::World(world::Bounds{Vector3(-50, -50, 0), Vector3(50, 50, 30)}, Vector3(0, 0, 2.5), Vector3(10, 0, 2),
                       {world::Obstacle::makeBox({{0, 0, 1.25}, {3, 3, 2.5}, 0.0})}),
          Rig::defaults());
  rig.tell_landed = false;
  rig.run(0.1);
  EXPECT_EQ(rig.mode(), Mode::kDisarmed) << "standing: nothing to take over";
  EXPECT_TRUE(rig.fc.landed());
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  ASSERT_EQ(rig.mode(), Mode::kIdle);
  rig.fc.onCommand(Command::kTakeoff, 2.0);  // 2 m above where it stands
  rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_NEAR(rig.sim.state().p_W.z(), 4.5, 0.1);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

// GIVEN a room fenced 1.9 m high WHEN the take-off is asked at the configured altitude (2 m)
// THEN it climbs to 0.5 m under the ceiling (1.4 m) instead of being refused; an altitude asked
// for is flown as asked or refused, never lowered; under a ceiling that leaves no room to leave
// the ground the take-off is refused, naming the ceiling.
TEST(FlightController, ATakeOffAtTheConfiguredAltitudeStopsUnderALowCeiling)
{
  FlightControllerConfig config = Rig::defaults();
  config.takeoff_altitude = 2.0;
  config.takeoff_ceiling_margin = 0.5;
  config.geofence.max = {50, 50, 1.9};
  {
    Rig rig(config);
    rig.run(0.1);
    rig.fc.onCommand(Command::kArm);
    rig.run(0.1);
    rig.fc.onCommand(Command::kTakeoff, 2.0);
    rig.run(0.1);
    EXPECT_EQ(rig.mode(), Mode::kIdle) << "2 m asked for would leave the fence";
    rig.fc.onCommand(Command::kTakeoff);
    rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
    ASSERT_EQ(rig.mode(), Mode::kHover);
    EXPECT_NEAR(rig.sim.state().p_W.z(), 1.4, 0.1);
    EXPECT_EQ(rig.sim.collisionCount(), 0U);
  }
  config.geofence.max = {50, 50, 0.7};  // 0.2 m to climb under the margin: not off the ground
  Rig rig(config);
  expectTakeOffRefused(rig, "takeoff refused: the geofence's ceiling at 0.7 m");
}

TEST(FlightController, ATakeOffAtTheConfiguredAltitudeStopsUnderTheCeilingItMeasures)
{
  // No geofence: the ceiling is a slab over the start, found by the upward rangefinder.
  FlightControllerConfig config = Rig::defaults();
  config.takeoff_altitude = 2.0;
  config.takeoff_ceiling_margin = 0.5;
  const auto room = [](double ceiling) {
    return world::World(world::Bounds{Vector3(-50, -50, 0), Vector3(50, 50, 30)}, Vector3::Zero(), Vector3(10, 0, 2),
                        {world::Obstacle::makeBox({{0, 0, ceiling + 0.1}, {10, 10, 0.2}, 0.0})});
  };
  {
    Rig rig(room(1.9), config);
    rig.run(0.1);
    takeOff(rig);
    ASSERT_EQ(rig.mode(), Mode::kHover);
    EXPECT_NEAR(rig.sim.state().p_W.z(), 1.4, 0.1);
    EXPECT_EQ(rig.sim.collisionCount(), 0U);
  }
  {
    // An altitude asked for is flown as asked, the margin's or not: never lowered.
    Rig rig(room(1.9), config);
    rig.run(0.1);
    rig.fc.onCommand(Command::kArm);
    rig.run(0.1);
    rig.fc.onCommand(Command::kTakeoff, 1.6);
    rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
    ASSERT_EQ(rig.mode(), Mode::kHover);
    EXPECT_NEAR(rig.sim.state().p_W.z(), 1.6, 0.1);
  }
  Rig rig(room(0.75), config);  // 0.25 m to climb under the margin: not off the ground
  expectTakeOffRefused(rig, "takeoff refused: the ceiling measured 0.7");
}

TEST(FlightController, EveryCommandIsAnsweredInTheTickThatAppliesItAndATakeOffClimbsAsHighAsAsked)
{
  FlightControllerConfig config = Rig::defaults();
  config.geofence.max = {50, 50, 6};  // a ceiling 6 m up
  Rig rig(config);
  rig.run(0.1);
  // The answer of the next tick: the one that applies the command given.
  const auto answered = [&] {
    const std::size_t from = rig.log.size();
    rig.run(0.05, [&] { return rig.log.size() > from; });
    EXPECT_TRUE(rig.log.back().answer.has_value());
    return rig.log.back().answer.value_or(CommandAnswer{});
  };
  // Refused, saying why, and nothing changes.
  rig.fc.onCommand(Command::kTakeoff);
  CommandAnswer a = answered();
  EXPECT_FALSE(a.accepted);
  EXPECT_EQ(a.reason, "takeoff refused in DISARMED: arm first");
  rig.fc.onCommand(Command::kArm);
  a = answered();
  EXPECT_TRUE(a.accepted);
  EXPECT_EQ(a.reason, "commanded: arm");
  // A take-off out of range: below the ground, not a number, through the ceiling.
  for (const double altitude : {-1.0, std::nan(""), 7.0}) {
    rig.fc.onCommand(Command::kTakeoff, altitude);
    a = answered();
    EXPECT_FALSE(a.accepted) << altitude;
    EXPECT_TRUE(a.reason.starts_with("takeoff refused: ")) << a.reason;
    EXPECT_EQ(rig.mode(), Mode::kIdle);
  }
  rig.fc.onCommand(Command::kTakeoff, 3.5);
  a = answered();
  EXPECT_TRUE(a.accepted);
  rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_NEAR(rig.sim.state().p_W.z(), 3.5, 0.1);
  // What already holds is taken and changes nothing.
  rig.fc.onCommand(Command::kHold);
  a = answered();
  EXPECT_TRUE(a.accepted);
  EXPECT_EQ(a.reason, "hold: nothing to change in HOVER");
  EXPECT_FALSE(rig.log.back().transition.has_value());
  // No answer without a command.
  rig.run(0.1);
  EXPECT_FALSE(rig.log.back().answer.has_value());
}

TEST(FlightController, AControllerRestartedInFlightHoldsTheVehicleWhereItTookOver)
{
  Rig rig;
  takeOff(rig);
  ASSERT_EQ(rig.mode(), Mode::kHover);
  rig.run(1.0);
  const Vector3 at = rig.sim.state().p_W;
  // A new controller (a restarted process) meets the vehicle in the air.
  rig.fc = FlightController(rig.v, Rig::withGains(Rig::defaults(), rig.v));
  rig.log.clear();
  rig.run(5.0);
  ASSERT_FALSE(rig.log.empty());
  EXPECT_TRUE(rig.log.front().armed);  // its first command already flies
  ASSERT_TRUE(rig.log.front().transition.has_value());
  EXPECT_EQ(rig.log.front().transition->to, Mode::kHover);
  EXPECT_EQ(rig.mode(), Mode::kHover);
  double lowest = at.z();
  for (const auto& out : rig.log) {
    lowest = std::min(lowest, out.reference.p_W.z());
  }
  EXPECT_GT(lowest, at.z() - 0.05) << "the reference held the altitude";
  EXPECT_LT((rig.sim.state().p_W - at).norm(), 0.1);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

TEST(FlightController, ARotorAtSeventyPercentKeepsTheAltitudeThroughTurns)
{
  // GIVEN a vehicle in hover and a zig-zag mission at 2 m/s, 2 m up
  Rig rig;
  takeOff(rig);
  const std::vector<Vector3> path = {{0, 0, 2},  {6, 0, 2},  {10, -3, 2}, {16, -3, 2},
                                     {20, 2, 2}, {26, 2, 2}, {30, -2, 2}, {40, 0, 2}};
  rig.fc.onGoal(path.back(), 0.3);
  rig.fc.onPath(path, 1, PathKind::kOk, rig.t());
  rig.fc.onCommand(Command::kStartMission);
  // WHEN rotor 2 loses 30 % of its thrust (and drag) a second in, for the rest of the flight
  plant::Fault loss;
  loss.id = 1;
  loss.kind = plant::Fault::Kind::kMotor;
  loss.rotor = 2;
  loss.magnitude = 0.7;
  loss.start_ns = rig.sim.timeNs() + 1'000'000'000;
  ASSERT_TRUE(rig.sim.injectFault(loss));
  double next_path = rig.t() + 0.5;
  double lowest = std::numeric_limits<double>::infinity();
  rig.run(60.0, [&] {
    if (rig.t() >= next_path) {
      rig.fc.onPath(path, 1, PathKind::kOk, rig.t());
      next_path += 0.5;
    }
    lowest = std::min(lowest, rig.sim.state().p_W.z());
    return rig.log.back().transition && rig.log.back().transition->why == "goal reached";
  });
  // THEN the mission completes and the vehicle never sinks more than 0.25 m: the mixer gives
  // up yaw before thrust when the weak rotor saturates in the turns (with yaw before thrust
  // it sank 0.63 m here, and to the ground at 60 %)
  EXPECT_EQ(rig.log.back().transition->why, "goal reached");
  EXPECT_GT(lowest, 1.75);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

/// Takes off to hover and starts a long mission; returns the rig in MISSION.
void intoMission(Rig& rig)
{
  takeOff(rig);
  rig.fc.onPath({{0, 0, 2}, {40, 0, 2}}, 1, PathKind::kOk, rig.t());
  rig.fc.onGoal(Vector3(40, 0, 2), 0.3);
  rig.fc.onCommand(Command::kStartMission);
  rig.run(0.5);
  ASSERT_EQ(rig.mode(), Mode::kMission);
}

TEST(FlightController, StalePathHoversWithinATickOfItsTimeoutThenLands)
{
  FlightControllerConfig config = Rig::defaults();
  config.path_timeout = 1.0;
  config.modes.path_stale_land_after = 3.0;
  Rig rig(config);
  intoMission(rig);
  const double last_path = rig.t() - 0.5;  // the path came at the start of the mission
  rig.run(5.0, [&] { return rig.mode() == Mode::kHover; });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_EQ(rig.log.back().reason, Reason::kPathStale);
  // Stale at last_path + 1.0 s: hover within 0.1 s of that (one 4 ms tick here).
  EXPECT_LE(rig.t() - (last_path + config.path_timeout), 0.1);
  const double hover_at = rig.t();
  rig.run(10.0, [&] { return rig.mode() == Mode::kLand; });
  EXPECT_EQ(rig.mode(), Mode::kLand);
  EXPECT_NEAR(rig.t() - hover_at, 3.0, 0.01);
}

TEST(FlightController, StaleStateLandsWithinATickOfItsTimeout)
{
  Rig rig;
  intoMission(rig);
  rig.feed_state = false;  // the state stops arriving, and no IMU carries it on
  rig.feed_imu = false;
  const double lost = rig.t();
  rig.run(1.0, [&] { return rig.mode() == Mode::kFailsafeLand; });
  ASSERT_EQ(rig.mode(), Mode::kFailsafeLand);
  EXPECT_LE(rig.t() - lost, 0.1 + 0.008);
  // Blind descent: below the weight, never non-finite.
  for (const double w : rig.log.back().rotor_speed) {
    EXPECT_TRUE(std::isfinite(w));
    EXPECT_LT(w, rig.v.hoverRotorSpeed());
  }
}

// GIVEN a mission flying WHEN the state stops (an estimator killed) while the IMU goes on
// THEN the controller holds on dead reckoning within a tick of the timeout; a state back
// within the hold (a restarted estimator) resumes the mission; none back lands once the
// hold is over, the vehicle held near where the state went stale.
TEST(FlightController, AStaleStateIsHeldOnDeadReckoningThenLandsUnlessItComesBack)
{
  FlightControllerConfig config = Rig::defaults();
  config.modes.auto_mission = true;  // as the shipped config: a path resumes the mission
  Rig rig(config);
  intoMission(rig);
  rig.feed_state = false;
  const double lost = rig.t();
  rig.run(1.0, [&] { return rig.mode() == Mode::kHover; });
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_EQ(rig.fc.reason(), Reason::kStateStale);
  EXPECT_LE(rig.t() - lost, 0.1 + 0.008);
  EXPECT_TRUE(rig.log.back().dead_reckoning);
  rig.run(1.0);
  EXPECT_EQ(rig.mode(), Mode::kHover);  // within the hold
  rig.fc.onPath({{0, 0, 2}, {40, 0, 2}}, 1, PathKind::kOk, rig.t());
  rig.feed_state = true;
  rig.run(0.5, [&] { return rig.mode() == Mode::kMission; });
  EXPECT_EQ(rig.mode(), Mode::kMission);

  Rig gone;
  intoMission(gone);
  gone.feed_state = false;
  const double stale_at = gone.t();
  const Vector3 p0 = gone.sim.state().p_W;
  double farthest = 0.0;
  gone.run(3.0, [&] {
    farthest = std::max(farthest, (gone.sim.state().p_W - p0).norm());
    return gone.mode() == Mode::kFailsafeLand;
  });
  ASSERT_EQ(gone.mode(), Mode::kFailsafeLand);
  EXPECT_NEAR(gone.t() - stale_at, 0.1 + config.modes.state_stale_land_after, 0.01);
  EXPECT_LT(farthest, 1.5);  // braking from 2 m/s at the tilt limit, then holding
}

TEST(FlightController, ADeadlineEventMakesItsInputStaleAtTheNextTickUntilTheNextSample)
{
  // The state: the middleware's deadline event (wall clock) comes before the sim-time timeout.
  Rig rig;
  intoMission(rig);
  rig.feed_state = false;
  rig.run(0.02);
  ASSERT_EQ(rig.mode(), Mode::kMission);  // 20 ms: well within the 0.1 s timeout
  rig.fc.onStateLate();
  rig.run(0.005);
  EXPECT_EQ(rig.mode(), Mode::kHover);  // held on dead reckoning: the IMU still comes
  EXPECT_EQ(rig.log.back().reason, Reason::kStateStale);

  // The path: HOVER at the next tick, saying so; a path again clears it.
  Rig again;
  intoMission(again);
  again.fc.onPathLate();
  again.run(0.005);
  EXPECT_EQ(again.mode(), Mode::kHover);
  EXPECT_EQ(again.log.back().reason, Reason::kPathStale);
  again.fc.onPath({{0, 0, 2}, {40, 0, 2}}, 1, PathKind::kOk, again.t());
  again.fc.onCommand(Command::kStartMission);
  again.run(0.005);
  EXPECT_EQ(again.mode(), Mode::kMission);
}

/// Flies the mission at full speed (along +x), then stops the state for `seconds` (the IMU as
/// the rig says); returns how far the vehicle went horizontally from where the state was lost,
/// and in `back_speed` the fastest it flew back (along −x).
double driftThroughAStateDropout(Rig& rig, double seconds, double* back_speed = nullptr)
{
  intoMission(rig);
  double next_path = rig.t();
  const auto republish = [&] {
    if (rig.t() >= next_path) {
      rig.fc.onPath({{0, 0, 2}, {40, 0, 2}}, 1, PathKind::kOk, rig.t());
      next_path += 0.5;
    }
  };
  rig.run(4.0, [&] { republish(); return false; });  // up to the follower's 2 m/s
  EXPECT_GT(rig.sim.state().v_W.norm(), 1.9);
  const Vector3 lost = rig.sim.state().p_W;
  rig.feed_state = false;
  double drift = 0.0;
  rig.run(seconds, [&] {
    republish();
    drift = std::max(drift, (rig.sim.state().p_W - lost).head<2>().norm());
    if (back_speed) {
      *back_speed = std::max(*back_speed, -rig.sim.state().v_W.x());
    }
    return false;
  });
  return drift;
}

TEST(FlightController, AStateDropoutIsFlownOnDeadReckoningBrakingWhereTheStateWasLost)
{
  // GIVEN a mission at 2 m/s WHEN the state stops for 1.5 s but the IMU (noisy, its biases
  // known: dead reckoning has no estimate of them) goes on
  plant::SimulationConfig plant;
  plant.imu.accel_turn_on_std = 0.0;
  plant.imu.gyro_turn_on_std = 0.0;
  FlightControllerConfig config = Rig::defaults();
  config.modes.auto_mission = true;  // as the shipped config: a path resumes the mission
  Rig rig(config, plant);
  double back_speed = 0.0;
  const double drift = driftThroughAStateDropout(rig, 1.5, &back_speed);
  // THEN the hold is flown on the IMU's estimate: the vehicle brakes (0.2 m in the 0.1 s the
  // state takes to go stale, then braking along its trajectory at up to follower.max_braking,
  // the braking ramped in at the jerk limit: about 0.9 m from 2 m/s) and holds where it stopped, not
  // flying back to a point passed (still soon: where a restarted estimator aligns); the
  // estimate stays within 5 cm of the truth
  ASSERT_EQ(rig.mode(), Mode::kHover);
  EXPECT_EQ(rig.fc.reason(), Reason::kStateStale);
  const FlightOutput& last = rig.log.back();
  EXPECT_TRUE(last.dead_reckoning);
  EXPECT_LT(drift, 1.25);
  EXPECT_LT(back_speed, 0.3);
  const Vector3 estimate = last.reference.p_W - last.position_error_W;
  EXPECT_LT((estimate - rig.sim.state().p_W).norm(), 0.05);
  EXPECT_LT((last.reference.p_W - rig.sim.state().p_W).head<2>().norm(), 0.2);
  // AND when the state comes back within the hold the mission goes on, on the state
  rig.feed_state = true;
  rig.fc.onPath({{0, 0, 2}, {40, 0, 2}}, 1, PathKind::kOk, rig.t());
  rig.run(1.0, [&] { return rig.mode() == Mode::kMission; });
  EXPECT_EQ(rig.mode(), Mode::kMission);
  EXPECT_FALSE(rig.log.back().dead_reckoning);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

TEST(FlightController, WithoutTheImuAStateDropoutIsABlindDescentOnTheMomentum)
{
  // The same dropout with no IMU (or past dead_reckoning_horizon): nothing to brake on
  Rig rig;
  rig.feed_imu = false;
  const double drift = driftThroughAStateDropout(rig, 1.5);
  EXPECT_FALSE(rig.log.back().dead_reckoning);
  EXPECT_GT(drift, 1.5);
}

TEST(FlightController, DeadReckoningEndsAtItsHorizon)
{
  FlightControllerConfig config = Rig::defaults();
  config.dead_reckoning_horizon = 0.5;
  Rig rig(config);
  intoMission(rig);
  const double lost = rig.t();
  rig.feed_state = false;
  rig.run(0.45);
  EXPECT_TRUE(rig.log.back().dead_reckoning);
  rig.run(0.1);
  EXPECT_FALSE(rig.log.back().dead_reckoning);  // blind after 0.5 s
  EXPECT_GT(rig.t() - lost, 0.5);
}

TEST(FlightController, InvalidInputsAreRejectedCountedAndTheLastGoodKept)
{
  Rig rig;
  EXPECT_FALSE(rig.fc.onState({Vector3(NAN, 0, 0), Vector3::Zero(), Quaternion::identity(), Vector3::Zero()}, 0.0, {.landed = true}));
  EXPECT_FALSE(rig.fc.onState({Vector3::Zero(), Vector3::Zero(), Quaternion{2, 0, 0, 0}, Vector3::Zero()}, 0.0, {.landed = true}));
  EXPECT_FALSE(rig.fc.onPath({{0, 0, 0}, {INFINITY, 0, 0}}, 3, PathKind::kOk, 0.0));
  EXPECT_FALSE(rig.fc.onPath({}, 4, PathKind::kOk, 0.0));
  EXPECT_FALSE(rig.fc.onGoal(Vector3(NAN, 0, 0), 0.3));
  EXPECT_FALSE(rig.fc.onImu({Vector3(0, 0, INFINITY), Vector3::Zero()}, 0.0));
  EXPECT_FALSE(rig.fc.onImu({Vector3::Zero(), Vector3(1e308, 1e308, 0)}, 1.0));
  EXPECT_EQ(rig.fc.rejectedInputs(), 7U);
  EXPECT_FALSE(rig.fc.pathVersion().has_value());
}

TEST(FlightController, FuzzedInputsNeverProduceANonFiniteCommand)
{
  Rig rig;
  intoMission(rig);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1e4, 1e4);
  const double specials[] = {NAN, INFINITY, -INFINITY, 1e308, 0.0};
  const auto value = [&] { return rng() % 5 == 0 ? specials[rng() % 5] : u(rng); };
  for (int k = 0; k < 20000; ++k) {
    const double t = rig.t() + 0.004 * static_cast<double>(k);
    switch (rng() % 5) {
      case 0:
        rig.fc.onState({Vector3(value(), value(), value()), Vector3(value(), value(), value()),
                        Quaternion{value(), value(), value(), value()}, Vector3(value(), value(), value())},
                       t, {.landed = rng() % 2 == 0, .accel_bias_B = Vector3(value(), value(), value())});
        break;
      case 1:
        rig.fc.onPath({Vector3(value(), value(), value()), Vector3(value(), value(), value())},
                      static_cast<std::uint32_t>(rng() % 5), rng() % 2 == 0 ? PathKind::kOk : PathKind::kNone, t);
        break;
      case 2:
        rig.fc.onGoal(Vector3(value(), value(), value()), value());
        break;
      case 3:
        rig.fc.onImu({Vector3(value(), value(), value()), Vector3(value(), value(), value())}, t);
        break;
      default:
        rig.fc.onCommand(static_cast<Command>(rng() % 7));
    }
    const FlightOutput out = rig.fc.update(t);
    for (const double w : out.rotor_speed) {
      ASSERT_TRUE(std::isfinite(w)) << "iteration " << k;
      ASSERT_GE(w, rig.v.rotor_speed_min);
      ASSERT_LE(w, rig.v.rotor_speed_max);
    }
  }
  EXPECT_GT(rig.fc.rejectedInputs(), 0U);
}

TEST(FlightController, TheVehicleStopsBeforeThePathLeavesKnownFreeSpace)
{
  // GIVEN a hovering vehicle and a 20 m path of which the first 6 m are known free
  Rig rig;
  takeOff(rig);
  const Vector3 start = rig.sim.state().p_W;
  const std::vector<Vector3> path = {start, start + Vector3(20, 0, 0)};
  rig.fc.onGoal(path.back(), 0.3);
  rig.fc.onPath(path, 1, PathKind::kOk, rig.t(), 6.0);
  rig.fc.onCommand(Command::kStartMission);
  // WHEN it flies for long enough to have crossed the whole path
  double furthest = 0.0;
  double next_path = rig.t() + 0.5;
  rig.run(20.0, [&] {
    if (rig.t() >= next_path) {
      rig.fc.onPath(path, 1, PathKind::kOk, rig.t(), 6.0);
      next_path += 0.5;
    }
    furthest = std::max(furthest, rig.sim.state().p_W.x() - start.x());
    return false;
  });
  // THEN it never went past the end of the known-free part (its tracking error aside), and
  // waits there in the mission
  EXPECT_LT(furthest, 6.0 + 0.15);
  EXPECT_GT(rig.sim.state().p_W.x() - start.x(), 5.8);
  EXPECT_EQ(rig.mode(), Mode::kMission);
  // AND a newer path whose known part reaches the goal takes it there
  rig.fc.onPath({rig.sim.state().p_W, path.back()}, 2, PathKind::kOk, rig.t());
  next_path = rig.t() + 0.5;
  rig.run(30.0, [&] {
    if (rig.t() >= next_path) {
      rig.fc.onPath({rig.sim.state().p_W, path.back()}, 2, PathKind::kOk, rig.t());
      next_path += 0.5;
    }
    return rig.log.back().transition && rig.log.back().transition->why == "goal reached";
  });
  EXPECT_EQ(rig.mode(), Mode::kHover);
  EXPECT_LT((rig.sim.state().p_W - path.back()).norm(), 0.3);
}

TEST(FlightController, TheCameraLooksUpOnTakeOffAlongThePathInFlightAndDownWhenLanding)
{
  Rig rig;
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  rig.fc.onCommand(Command::kTakeoff);
  rig.run(0.5);
  EXPECT_NEAR(rig.log.back().camera.pitch, geometry::kPi / 2.0, 1e-9);  // the column it climbs into
  rig.run(15.0, [&] { return rig.mode() == Mode::kHover; });
  // A path that climbs 45° to the left: the camera looks 3 m along it.
  const Vector3 p = rig.sim.state().p_W;
  rig.fc.onPath({p, p + Vector3(0, 10, 10)}, 1, PathKind::kOk, rig.t());
  rig.run(0.1);
  const CameraAim aim = rig.log.back().camera;
  EXPECT_NEAR(aim.yaw_W, geometry::kPi / 2.0, 0.05);
  EXPECT_NEAR(aim.pitch, geometry::kPi / 4.0, 0.05);
  rig.fc.onCommand(Command::kLand);
  rig.run(0.1);
  EXPECT_NEAR(rig.log.back().camera.pitch, -geometry::kPi / 2.0, 1e-9);
  EXPECT_NEAR(rig.log.back().camera.yaw_W, aim.yaw_W, 1e-9);  // the yaw is kept
}

TEST(FlightController, BatteryReadingsOutOfTheirRangesAreRejectedAndTheTimeLeftIsTheChargeOverTheCurrent)
{
  Rig rig;
  EXPECT_EQ(rig.fc.batteryTimeLeft(), std::numeric_limits<double>::infinity());  // no reading yet
  const BatteryReading good{15.0, 10.0, 0.5, 2.0, 4};
  const std::vector<std::function<void(BatteryReading&)>> breaks = {
      [](BatteryReading& b) { b.voltage = -1.0; },
      [](BatteryReading& b) { b.current = std::numeric_limits<double>::quiet_NaN(); },
      [](BatteryReading& b) { b.current = -3.0; },
      [](BatteryReading& b) { b.charge = 1.5; },
      [](BatteryReading& b) { b.capacity = 0.0; },
      [](BatteryReading& b) { b.cells = 0; }};
  for (const auto& broken : breaks) {
    BatteryReading bad = good;
    broken(bad);
    EXPECT_FALSE(rig.fc.onBattery(bad, 1.0));
  }
  EXPECT_EQ(rig.fc.rejectedInputs(), 6U);
  ASSERT_TRUE(rig.fc.onBattery(good, 1.0));
  EXPECT_FALSE(rig.fc.onBattery(good, 0.5));  // back in time
  // (0.5 − 0.15 reserve) × 2 Ah at 10 A: 252 s; at a steady current the average is that current.
  ASSERT_TRUE(rig.fc.onBattery(good, 2.0));
  EXPECT_NEAR(rig.fc.batteryTimeLeft(), 252.0, 1e-9);
  EXPECT_EQ(rig.fc.returnTime(), 0.0);  // on the ground
}

/// Out along +x at the follower's speed until `done`, with the path re-published as a
/// planner does.
void flyOut(Rig& rig, double seconds, const std::function<bool()>& done)
{
  const Vector3 p = rig.sim.state().p_W;
  const std::vector<Vector3> path = {p, p + Vector3(45, 0, 0)};
  rig.fc.onGoal(path.back(), 0.3);
  rig.fc.onPath(path, 1, PathKind::kOk, rig.t());
  rig.fc.onCommand(Command::kStartMission);
  double next_path = rig.t() + 0.5;
  rig.run(seconds, [&] {
    if (rig.t() >= next_path) {
      rig.fc.onPath(path, 1, PathKind::kOk, rig.t());
      next_path += 0.5;
    }
    return done();
  });
}

TEST(FlightController, ALowBatteryReturnsInTimeToLandAtTheTakeOffPointAboveTheCriticalCharge)
{
  // About 45 s of hovering in the pack: the 45 m out and back do not fit.
  plant::SimulationConfig plant;
  plant.battery.capacity = 0.26;
  Rig rig(Rig::defaults(), plant);
  takeOff(rig);
  const Vector3 home = rig.sim.state().p_W;
  flyOut(rig, 60.0, [&] { return rig.mode() == Mode::kReturn; });
  ASSERT_EQ(rig.mode(), Mode::kReturn);
  EXPECT_EQ(rig.log.back().reason, Reason::kBatteryLow);
  const double out = (rig.sim.state().p_W - home).norm();
  EXPECT_GT(out, 5.0);
  EXPECT_LT(out, 40.0);
  rig.run(60.0, [&] { return rig.mode() == Mode::kLand; });
  rig.run(60.0, [&] { return rig.mode() == Mode::kIdle; });
  ASSERT_EQ(rig.mode(), Mode::kIdle);
  EXPECT_EQ(rig.log.back().reason, Reason::kBatteryLow);
  EXPECT_LT((rig.sim.state().p_W.head<2>() - home.head<2>()).norm(), 0.5);
  // Landed on what the margin kept: above the critical charge, not far below the reserve.
  const double left = rig.sim.battery()->charge();
  EXPECT_GT(left, Rig::defaults().battery.critical);
  EXPECT_LT(left, Rig::defaults().battery.reserve + 0.1);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

TEST(FlightController, AFailedCellLandsWhereTheVehicleIsWithinTheCriticalHold)
{
  const double at = 8.0;  // [s] after take-off began; the vehicle hovers by then
  Rig rig(Rig::defaults(), {},
          {plant::Fault{.id = 1, .kind = plant::Fault::Kind::kCellLoss, .cells = 1,
                        .start_ns = common::toNanoseconds(at)}});
  takeOff(rig);
  rig.run(at - rig.t() + 0.01);
  ASSERT_EQ(rig.mode(), Mode::kHover);
  const Vector3 p = rig.sim.state().p_W;
  rig.run(3.0, [&] { return rig.mode() == Mode::kLand; });
  ASSERT_EQ(rig.mode(), Mode::kLand);
  EXPECT_EQ(rig.log.back().reason, Reason::kBatteryCritical);
  // The cells' voltage must stay low for critical_after (1 s), read at 10 Hz.
  EXPECT_LE(rig.t() - at, Rig::defaults().battery.critical_after + 0.2);
  rig.run(20.0, [&] { return rig.mode() == Mode::kIdle; });
  ASSERT_EQ(rig.mode(), Mode::kIdle);
  EXPECT_LT((rig.sim.state().p_W.head<2>() - p.head<2>()).norm(), 0.5);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

TEST(FlightController, AnOperatorSilentForTheLinkLossTimeReturnsTheVehicleToLandAtHome)
{
  FlightControllerConfig config = Rig::defaults();
  config.link_loss_after = 3.0;
  Rig rig(config);
  rig.operator_until = 1e9;
  takeOff(rig);
  const Vector3 home = rig.sim.state().p_W;
  const double silent_from = rig.t() + 4.0;
  rig.operator_until = silent_from;
  flyOut(rig, 30.0, [&] { return rig.mode() == Mode::kReturn; });
  ASSERT_EQ(rig.mode(), Mode::kReturn);
  EXPECT_EQ(rig.log.back().reason, Reason::kLinkLost);
  // The last heartbeat came at most half a second before the silence began.
  EXPECT_GE(rig.t(), silent_from - 0.5 + config.link_loss_after);
  EXPECT_LE(rig.t(), silent_from + config.link_loss_after + 0.01);
  rig.run(60.0, [&] { return rig.mode() == Mode::kIdle; });
  ASSERT_EQ(rig.mode(), Mode::kIdle);
  EXPECT_EQ(rig.log.back().reason, Reason::kLinkLost);
  EXPECT_LT((rig.sim.state().p_W.head<2>() - home.head<2>()).norm(), 0.5);
  EXPECT_EQ(rig.sim.collisionCount(), 0U);
}

TEST(FlightController, AGoalThePlannerCannotReachIsHeldThenLandedShortOfIt)
{
  ModeConfig modes;
  modes.idle_disarm_after = 1e9;
  modes.no_path_land_after = 3.0;
  FlightControllerConfig config = Rig::defaults();
  config.modes = modes;
  Rig rig(config);
  takeOff(rig);
  const Vector3 p = rig.sim.state().p_W;
  rig.fc.onGoal(p + Vector3(10, 0, 0), 0.3);
  double said = -1.0;
  rig.run(20.0, [&] {
    if (rig.t() >= said + 0.5) {
      rig.fc.onPath({}, 1, PathKind::kUnreachable, rig.t());
      said = rig.t();
    }
    return rig.mode() == Mode::kIdle;
  });
  EXPECT_EQ(rig.mode(), Mode::kIdle);
  EXPECT_LT((rig.sim.state().p_W.head<2>() - p.head<2>()).norm(), 0.2);
  const auto landing = std::find_if(rig.log.begin(), rig.log.end(), [](const FlightOutput& o) {
    return o.transition && o.transition->to == Mode::kLand;
  });
  ASSERT_NE(landing, rig.log.end());
  EXPECT_EQ(landing->transition->reason, Reason::kNoPath);
}

/// Hovers 10 m up, then rotor 2 keeps `efficiency` of its thrust (and drag) for 10 s, or until
/// the vehicle is on the ground. What the flight did, for the sweep below.
struct RotorLossFlight {
  double max_tilt_deg = 0.0;   ///< of the body's z axis from the vertical
  double lowest_m = 1e9;
  double max_descent = 0.0;    ///< [m/s]
  double max_rate = 0.0;       ///< [rad/s] body rate, the spin included
  double seconds = 0.0;        ///< flown after the loss
};

RotorLossFlight flyWithARotorAt(double efficiency)
{
  Rig rig;
  rig.fc.onCommand(Command::kArm);
  rig.run(0.1);
  rig.fc.onCommand(Command::kTakeoff, 10.0);
  rig.run(20.0, [&] { return rig.mode() == Mode::kHover; });
  rig.run(2.0);
  plant::Fault loss;
  loss.id = 1;
  loss.kind = plant::Fault::Kind::kMotor;
  loss.rotor = 2;
  loss.magnitude = efficiency;
  loss.start_ns = rig.sim.timeNs();
  EXPECT_TRUE(rig.sim.injectFault(loss));
  const double t0 = rig.t();
  RotorLossFlight f;
  rig.run(10.0, [&] {
    const auto& s = rig.sim.state();
    const double up = std::clamp(geometry::toMatrix(s.q_WB).col(2).z(), -1.0, 1.0);
    f.max_tilt_deg = std::max(f.max_tilt_deg, std::acos(up) * 180.0 / M_PI);
    f.lowest_m = std::min(f.lowest_m, s.p_W.z());
    f.max_descent = std::max(f.max_descent, -s.v_W.z());
    f.max_rate = std::max(f.max_rate, s.w_B.norm());
    return s.landed && rig.t() > t0 + 0.5;
  });
  f.seconds = rig.t() - t0;
  return f;
}

TEST(FlightController, ARotorDownToHalfItsThrustIsFlownByGivingUpYaw)
{
  // The sweep docs/control.md reports (Limits: a rotor lost); what must hold is asserted: down
  // to 45 % of one rotor's thrust the vehicle holds its altitude within 0.4 m for 10 s, the
  // mixer giving up yaw (it spins) before thrust and tilt. Below, it descends; without the
  // rotor it flips.
  for (const double efficiency : {0.6, 0.5, 0.45, 0.4, 0.3, 0.2, 0.0}) {
    const RotorLossFlight f = flyWithARotorAt(efficiency);
    std::printf("rotor 2 at %.2f: tilt up to %.1f deg, lowest %.2f m, descent up to %.2f m/s, body rate up to "
                "%.1f rad/s, %.2f s flown\n",
                efficiency, f.max_tilt_deg, f.lowest_m, f.max_descent, f.max_rate, f.seconds);
    if (efficiency >= 0.45) {
      EXPECT_GT(f.lowest_m, 9.6) << efficiency;
      EXPECT_LT(f.max_tilt_deg, 30.0) << efficiency;
    }
  }
}

}  // namespace
}  // namespace quad::control
