// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>

#include "quad/common/params.hpp"
#include "quad/geometry/quaternion.hpp"
#include "quad/geometry/so3.hpp"
#include "test_vehicle.hpp"

namespace quad::plant {
namespace {

using world::Bounds;
using world::Obstacle;
using world::World;

vehicle::VehicleParams vehicle() { return test::dragFreeVehicle(); }

World corridor()
{
  return World(Bounds{Vector3(-10, -10, 0), Vector3(60, 10, 20)}, Vector3(0, 0, 0), Vector3(50, 0, 2),
               {Obstacle::makeBox({Vector3(6, 0, 5), Vector3(2, 4, 10), 0.0}),
                Obstacle::makeCylinder({20, 5, 0.5, 8})});
}

RotorArray hoverCommand(const Simulation& sim)
{
  const double w = sim.dynamics().params().hoverRotorSpeed(9.81);
  return {w, w, w, w};
}

/// In the corridor without gravity, 5 m up at 2 m/s along x towards the box's face x = 5.
Simulation headingIntoTheBox(SimulationConfig config)
{
  config.gravity_W.setZero();
  Simulation sim(vehicle(), corridor(), config);
  RigidBodyState s;
  s.p_W = {0, 0, 5};
  s.v_W = {2, 0, 0};
  sim.setState(s);
  return sim;
}

TEST(Simulation, CollisionIsDetectedAtTheRightTime)
{
  Simulation sim = headingIntoTheBox({});
  // The sphere (r = 0.35) meets the box face x = 5 at t = (5 − 0.35) / 2 = 2.325 s.
  std::optional<SimEventRecord> hit;
  for (int k = 0; k < 4000 && !hit; ++k) {
    for (const auto& e : sim.step().events) {
      if (e.kind == SimEventRecord::Kind::kCollision) {
        hit = e;
      }
    }
  }
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->subject_id, 0);
  EXPECT_GE(hit->t_ns, 2'325'000'000);
  EXPECT_LE(hit->t_ns, 2'326'000'000);
  EXPECT_EQ(sim.collisionCount(), 1U);
  // Staying in contact is one collision, not one per step.
  for (int k = 0; k < 100; ++k) {
    sim.step();
  }
  EXPECT_EQ(sim.collisionCount(), 1U);
}

TEST(Simulation, AVehicleFlownIntoAWallStopsThereCrashed)
{
  // GIVEN the vehicle at 2 m/s towards the box's face x = 5, no gravity
  Simulation sim = headingIntoTheBox({});
  std::vector<SimEventRecord> crashes;
  for (int k = 0; k < 4000; ++k) {
    for (const auto& e : sim.step().events) {
      if (e.kind == SimEventRecord::Kind::kCrash) {
        crashes.push_back(e);
      }
    }
  }
  // THEN it crashed once, at the impact (t = 2.325 s, x = 4.65), at 2 m/s, into the box, and
  // stayed there at rest with its rotors stopped
  ASSERT_EQ(crashes.size(), 1U);
  ASSERT_TRUE(sim.crash().has_value());
  EXPECT_EQ(sim.crash()->solid, 0);
  EXPECT_NEAR(sim.crash()->speed, 2.0, 1e-9);
  EXPECT_NEAR(static_cast<double>(sim.crash()->t_ns) * 1e-9, 2.325, 1e-3);
  EXPECT_EQ(crashes[0].detail, "crashed into obstacle 0 at 2.00 m/s");
  EXPECT_NEAR(sim.state().p_W.x(), 4.65, 0.003);
  EXPECT_TRUE(sim.state().v_W.isZero());
  EXPECT_EQ(sim.collisionCount(), 1U);

  // WITHOUT crashes the vehicle flies on through it
  SimulationConfig flying_on;
  flying_on.crash_on_impact = false;
  Simulation ghost = headingIntoTheBox(flying_on);
  for (int k = 0; k < 4000; ++k) {
    ghost.step();
  }
  EXPECT_FALSE(ghost.crash().has_value());
  EXPECT_GT(ghost.state().p_W.x(), 7.0);
  EXPECT_EQ(ghost.collisionCount(), 1U);
}

TEST(Simulation, AVehicleDroppedOntoABoxComesToRestOnItsTop)
{
  // GIVEN a 1 m high box under a vehicle let go 3 m up with its rotors stopped
  const World w(Bounds{Vector3(-10, -10, 0), Vector3(10, 10, 10)}, Vector3(0, 0, 3), Vector3(5, 0, 2),
                {Obstacle::makeBox({Vector3(0, 0, 0.5), Vector3(2, 2, 1), 0.0})});
  Simulation sim(vehicle(), w, {});
  ASSERT_FALSE(sim.state().landed);
  std::size_t touchdowns = 0;
  for (int k = 0; k < 1000; ++k) {  // 4 s
    for (const auto& e : sim.step().events) {
      touchdowns += e.kind == SimEventRecord::Kind::kGroundContact ? 1U : 0U;
    }
  }
  // THEN it falls √(2·2/g) = 0.64 s and rests on the box's top, not on the ground, with no
  // collision: what it stands on is contact
  EXPECT_TRUE(sim.state().landed);
  EXPECT_DOUBLE_EQ(sim.state().p_W.z(), 1.0);
  EXPECT_TRUE(sim.state().v_W.isZero());
  EXPECT_EQ(touchdowns, 1U);
  EXPECT_EQ(sim.collisionCount(), 0U);
}

TEST(Simulation, ATiltedTouchdownIsFeltByTheImuAsTheStopAndTheTurnItIs)
{
  // GIVEN a vehicle let go 0.5 m up, pitched 34 degrees, rotors stopped (it lands as a vehicle
  // braking hard in a descent does), and an IMU without noise or bias
  const World w(Bounds{Vector3(-10, -10, 0), Vector3(10, 10, 10)}, Vector3(0, 0, 0.5), Vector3(5, 0, 2), {});
  SimulationConfig config;
  config.imu.accel_noise_std = config.imu.gyro_noise_std = 0.0;
  config.imu.accel_turn_on_std = config.imu.gyro_turn_on_std = 0.0;
  config.imu.accel_bias_walk = config.imu.gyro_bias_walk = 0.0;
  Simulation sim(vehicle(), w, config);
  RigidBodyState s;
  s.p_W = {0, 0, 0.5};
  s.q_WB = geometry::fromAxisAngle(Vector3::UnitY(), 34.0 * M_PI / 180.0);
  sim.setState(s);
  // WHEN the IMU's samples are integrated from the true state, as an estimator does: the force
  // turned into the world by the attitude the sample began with, then the rate's turn
  geometry::Matrix3 R = geometry::toMatrix(s.q_WB);
  Vector3 v = Vector3::Zero();
  bool touched_down = false;
  double fastest = 0.0;
  for (int k = 0; k < 1000; ++k) {  // 1 s: it falls 0.32 s
    const StepOutputs out = sim.step();
    if (out.imu) {
      const double dt = 1.0 / config.imu.rate_hz;
      v += (R * out.imu->sample.specific_force_B + config.gravity_W) * dt;
      R = R * geometry::expSO3(out.imu->sample.angular_rate_B * dt);
    }
    touched_down = touched_down || sim.state().landed;
    fastest = std::max(fastest, sim.state().v_W.norm());
  }
  // THEN the plant stopped and levelled it on touchdown, and the integrated samples stopped and
  // turned with it. Read at an instant, the rate would miss the turn and keep the 34 degrees;
  // the stop felt along the level axes, but turned by the tilted ones, would leave 1.8 m/s.
  ASSERT_TRUE(touched_down);
  EXPECT_GT(fastest, 3.0);
  const geometry::Matrix3 truth = geometry::toMatrix(sim.state().q_WB);
  EXPECT_NEAR(truth(2, 2), 1.0, 1e-12) << "level on the ground";
  EXPECT_LT(geometry::logSO3(R.transpose() * truth).norm(), 1e-9);
  EXPECT_TRUE(sim.state().v_W.isZero());
  EXPECT_LT(v.norm(), 1e-9);
}

TEST(Simulation, SameSeedSameCommandsGiveBitIdenticalRuns)
{
  const auto run = [](std::uint64_t seed) {
    SimulationConfig config;
    config.seed = seed;
    Simulation sim(vehicle(), corridor(), config);
    std::vector<double> trace;
    for (int k = 0; k < 3000; ++k) {
      const double w = sim.dynamics().params().hoverRotorSpeed(9.81) * (1.05 + 0.02 * std::sin(k * 0.01));
      sim.commands().submit({w, w * 1.001, w, w * 0.999}, true, sim.timeNs(), sim.timeNs());
      const StepOutputs out = sim.step();
      if (out.imu) {
        trace.push_back(out.imu->sample.specific_force_B.x());
      }
      if (out.depth) {
        for (const auto& p : out.depth->scan.points_S) {
          trace.push_back(p.x());
        }
      }
    }
    trace.push_back(sim.state().p_W.x());
    trace.push_back(sim.state().q_WB.w);
    return trace;
  };
  const auto a = run(42);
  const auto b = run(42);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double)));  // bit for bit
  EXPECT_NE(run(43), a);
}

TEST(Simulation, BadMotorCommandsAreRejectedCountedAndNeverIntegrated)
{
  Simulation sim(vehicle(), corridor(), {});
  const RotorArray good = hoverCommand(sim);
  EXPECT_EQ(sim.commands().submit(good, true, 0, 0), CommandGuard::Verdict::kAccepted);
  EXPECT_EQ(sim.commands().submit({NAN, 1, 1, 1}, true, 0, 0), CommandGuard::Verdict::kRejectedInvalid);
  EXPECT_EQ(sim.commands().submit({INFINITY, 1, 1, 1}, true, 0, 0), CommandGuard::Verdict::kRejectedInvalid);
  EXPECT_EQ(sim.commands().command(0), good);  // the last good command is held
  EXPECT_EQ(sim.commands().submit({-5, 1e6, 1, 1}, true, 1, 1), CommandGuard::Verdict::kClamped);
  const RotorArray clamped = sim.commands().command(1);
  EXPECT_EQ(clamped[0], 0.0);
  EXPECT_EQ(clamped[1], sim.dynamics().params().rotor_speed_max);
  // Late (older than the 100 ms timeout) and out-of-order commands are ignored.
  EXPECT_EQ(sim.commands().submit(good, true, 0, 200'000'000), CommandGuard::Verdict::kRejectedLate);
  EXPECT_EQ(sim.commands().submit(good, true, 0, 50'000'000), CommandGuard::Verdict::kRejectedOld);
  const auto& c = sim.commands().counters();
  EXPECT_EQ(c.accepted, 1U);
  EXPECT_EQ(c.rejected_invalid, 2U);
  EXPECT_EQ(c.clamped, 1U);
  EXPECT_EQ(c.rejected_late, 1U);
  EXPECT_EQ(c.rejected_old, 1U);
  // Missing commands: the held one is used, and each stale step counted.
  for (int k = 0; k < 300; ++k) {
    sim.step();
    ASSERT_TRUE(sim.state().p_W.allFinite());
  }
  EXPECT_GT(sim.commands().counters().stale_steps, 150U);
  // Disarmed: rotors spin down whatever the speeds say.
  sim.commands().submit(good, false, sim.timeNs(), sim.timeNs());
  EXPECT_EQ(sim.commands().command(sim.timeNs()), RotorArray{});
}

// A command with a torque in it, held open loop after its controller fell silent: whole, it
// spins the vehicle up without end; past the failsafe age the rotors run balanced at the
// same total thrust, and the spin stops growing once the motors have settled.
TEST(Simulation, AHeldCommandPastTheFailsafeAgeIsFlownBalancedWithItsThrust)
{
  struct Outcome {
    double spin;  // [rad/s] angular rate after 0.4 s
    RotorArray flown;
    std::uint64_t failsafe_steps;
  };
  const auto hold = [](std::int64_t failsafe_ns) {
    SimulationConfig config;
    config.command_failsafe_ns = failsafe_ns;
    Simulation sim(vehicle(), corridor(), config);
    const RotorArray hover = hoverCommand(sim);
    const double d = 0.05 * hover[0];
    const RotorArray torqued{hover[0] + d, hover[1] + d, hover[2] - d, hover[3] - d};
    RigidBodyState s;
    s.p_W = {0, -5, 5};
    s.rotor_speed = torqued;
    sim.setState(s);
    EXPECT_EQ(sim.commands().submit(torqued, true, 0, 0), CommandGuard::Verdict::kAccepted);
    for (int k = 0; k < 400; ++k) {
      sim.step();
    }
    Outcome out{sim.state().w_B.norm(), sim.commands().command(sim.timeNs()), 0};
    out.failsafe_steps = sim.commands().counters().failsafe_steps;
    double held_sq = 0.0;
    double flown_sq = 0.0;
    for (std::size_t i = 0; i < torqued.size(); ++i) {
      held_sq += torqued[i] * torqued[i];
      flown_sq += out.flown[i] * out.flown[i];
    }
    EXPECT_NEAR(flown_sq, held_sq, 1e-9 * held_sq);  // the total thrust is kept
    return out;
  };
  const Outcome whole = hold(10'000'000'000);  // past the run: the held command flown whole
  const Outcome failsafe = hold(20'000'000);
  EXPECT_NE(whole.flown[0], whole.flown[2]);
  EXPECT_EQ(whole.failsafe_steps, 0U);
  EXPECT_EQ(failsafe.failsafe_steps, 380U);  // steps at 21..400 ms
  for (const double w : failsafe.flown) {
    EXPECT_EQ(w, failsafe.flown[0]);
  }
  // Torque for 20 ms and the motors' settling, against torque for the whole 400 ms.
  EXPECT_GT(whole.spin, 1.0);
  EXPECT_LT(failsafe.spin, 0.2 * whole.spin);
}

TEST(Simulation, StartOnTheGroundIsLandedAndTakeoffIsAnEvent)
{
  Simulation sim(vehicle(), corridor(), {});
  EXPECT_TRUE(sim.state().landed);
  const double w = sim.dynamics().params().hoverRotorSpeed(9.81) * 1.2;
  bool took_off = false;
  for (int k = 0; k < 1000; ++k) {
    sim.commands().submit({w, w, w, w}, true, sim.timeNs(), sim.timeNs());
    for (const auto& e : sim.step().events) {
      took_off = took_off || e.kind == SimEventRecord::Kind::kTakeoff;
    }
  }
  EXPECT_TRUE(took_off);
  EXPECT_GT(sim.state().p_W.z(), 0.5);
}

TEST(Simulation, SensorsComeAtTheirRates)
{
  SimulationConfig config;
  config.state_rate_hz = 250;
  config.imu.rate_hz = 500;
  config.depth.rate_hz = 10;
  Simulation sim(vehicle(), corridor(), config);
  int states = 0, imus = 0, depths = 0;
  for (int k = 0; k < 1000; ++k) {
    const StepOutputs out = sim.step();
    states += out.state ? 1 : 0;
    imus += out.imu ? 1 : 0;
    depths += out.depth ? 1 : 0;
  }
  EXPECT_EQ(states, 250);
  EXPECT_EQ(imus, 500);
  EXPECT_EQ(depths, 10);
}

// GIVEN a vehicle climbing at 1 m/s WHEN the navigation aids fall due THEN each comes at its
// rate, and a position fix is delivered its latency after it was measured, telling where the
// vehicle was then (within its noise); a dropout fault stops the fixes and nothing else.
TEST(Simulation, NavigationAidsComeAtTheirRatesAndAFixArrivesItsLatencyLate)
{
  SimulationConfig config;
  config.position.latency = 0.05;
  Simulation sim(vehicle(), corridor(), config);
  RigidBodyState s;
  s.p_W = {0, 0, 5};
  s.v_W = {0, 0, 1};
  sim.setState(s);
  Fault dropout;
  dropout.id = 3;
  dropout.kind = Fault::Kind::kSensorDropout;
  dropout.sensor = Sensor::kPosition;
  dropout.start_ns = 1'000'000'000;
  dropout.duration_ns = 500'000'000;
  ASSERT_TRUE(sim.injectFault(dropout));
  std::map<std::int64_t, double> z_at;  // sim time → true height
  int fixes = 0, baros = 0, mags = 0;
  for (int k = 0; k < 2000; ++k) {
    sim.commands().submit(hoverCommand(sim), true, sim.timeNs(), sim.timeNs());
    const StepOutputs out = sim.step();
    z_at[sim.timeNs()] = sim.state().p_W.z();
    if (out.position) {
      ++fixes;
      EXPECT_EQ(sim.timeNs() - out.position->t_ns, 50'000'000);
      EXPECT_NEAR(out.position->fix.p_W.z(), z_at.at(out.position->t_ns), 0.1);
      EXPECT_FALSE(out.position->t_ns > 1'000'000'000 && out.position->t_ns < 1'500'000'000);
    }
    baros += out.baro ? 1 : 0;
    mags += out.mag ? 1 : 0;
  }
  EXPECT_EQ(fixes, 20 - 1 - 5);  // the last one still in flight; 5 dropped
  EXPECT_EQ(baros, 50);
  EXPECT_EQ(mags, 100);
}

TEST(Simulation, TheRangefinderReadsAtTheFirstStepBeforeTheFirstStateThenAtItsRate)
{
  SimulationConfig config;
  config.range.noise_std = 0.0;
  Simulation sim(vehicle(), corridor(), config);  // standing on the ground at the start
  std::optional<std::int64_t> first_range, first_state;
  int ranges = 0;
  for (int k = 0; k < 1000; ++k) {  // 1 s
    const StepOutputs out = sim.step();
    if (out.range) {
      ++ranges;
      first_range = first_range.value_or(out.range->t_ns);
      ASSERT_TRUE(out.range->range.has_value());
      EXPECT_NEAR(*out.range->range, 0.0, 1e-9);
      EXPECT_EQ(out.range->max_range, config.range.max_range);
    }
    if (out.state) {
      first_state = first_state.value_or(out.state->t_ns);
    }
  }
  ASSERT_TRUE(first_range && first_state);
  EXPECT_EQ(*first_range, config.step_ns);
  EXPECT_LT(*first_range, *first_state);
  EXPECT_EQ(ranges, 1 + 20);  // at turn-on, then 20 Hz
  // Switched off: none.
  config.range.enabled = false;
  Simulation off(vehicle(), corridor(), config);
  for (int k = 0; k < 200; ++k) {
    ASSERT_FALSE(off.step().range.has_value());
  }
}

// GIVEN a vehicle at rest WHEN sensor_offset faults are active THEN each sensor reads its
// offset on top (a position jump, a barometer step, a magnetic disturbance, an accelerometer
// bias step), within its noise, and reads true again once the fault clears.
TEST(Simulation, SensorOffsetFaultsShiftEachSensorsReadingsWhileActive)
{
  SimulationConfig config;
  config.position.latency = 0.0;
  config.imu.accel_turn_on_std = 0.0;
  config.baro.offset_std = 0.0;
  config.baro.drift_walk = 0.0;
  Simulation sim(vehicle(), corridor(), config);
  const auto offset = [&](std::uint32_t id, Sensor s, const Vector3& v) {
    Fault f;
    f.id = id;
    f.kind = Fault::Kind::kSensorOffset;
    f.sensor = s;
    f.offset = v;
    f.start_ns = 500'000'000;
    f.duration_ns = 500'000'000;
    ASSERT_TRUE(sim.injectFault(f));
  };
  offset(1, Sensor::kPosition, {3.0, -1.0, 0.0});
  offset(2, Sensor::kBaro, {0.0, 0.0, 2.0});
  offset(3, Sensor::kMag, {10.0, 0.0, 0.0});
  offset(4, Sensor::kImu, {0.5, 0.0, 0.0});
  Vector3 p_during = Vector3::Zero(), p_after = Vector3::Zero(), m_during = Vector3::Zero(), f_during = Vector3::Zero();
  double baro_during = 0.0, baro_after = 0.0;
  int n_p = 0, n_pa = 0, n_b = 0, n_ba = 0, n_m = 0, n_f = 0;
  for (int k = 0; k < 1500; ++k) {
    const StepOutputs out = sim.step();
    const bool during = sim.timeNs() > 500'000'000 && sim.timeNs() < 1'000'000'000;
    const bool after = sim.timeNs() > 1'000'000'000;
    if (out.position && (during || after)) {
      (during ? p_during : p_after) += out.position->fix.p_W;
      ++(during ? n_p : n_pa);
    }
    if (out.baro && (during || after)) {
      (during ? baro_during : baro_after) += out.baro->altitude;
      ++(during ? n_b : n_ba);
    }
    if (out.mag && during) {
      m_during += out.mag->field_B;
      ++n_m;
    }
    if (out.imu && during) {
      f_during += out.imu->sample.specific_force_B;
      ++n_f;
    }
  }
  const Vector3 start = corridor().start();
  EXPECT_LT((p_during / n_p - (start + Vector3(3.0, -1.0, 0.0))).norm(), 0.03);
  EXPECT_LT((p_after / n_pa - start).norm(), 0.03);
  EXPECT_NEAR(baro_during / n_b, start.z() + 2.0, 0.05);
  EXPECT_NEAR(baro_after / n_ba, start.z(), 0.05);
  EXPECT_LT((m_during / n_m - (config.mag.field_W + Vector3(10.0, 0.0, 0.0))).norm(), 0.2);  // level, facing x
  EXPECT_NEAR(f_during.x() / n_f, 0.5, 0.01);
}

TEST(Simulation, FaultsTakeEffectAreAcknowledgedAndClear)
{
  Simulation sim(vehicle(), corridor(), {});
  RigidBodyState s;
  s.p_W = {0, 0, 10};
  sim.setState(s);
  Fault motor;
  motor.id = 7;
  motor.kind = Fault::Kind::kMotor;
  motor.rotor = 0;
  motor.magnitude = 0.0;
  motor.start_ns = 100'000'000;
  motor.duration_ns = 200'000'000;
  ASSERT_TRUE(sim.injectFault(motor));
  EXPECT_FALSE(sim.injectFault(motor));  // one id, once
  Fault dropout;
  dropout.id = 8;
  dropout.kind = Fault::Kind::kSensorDropout;
  dropout.sensor = Sensor::kState;
  dropout.start_ns = 0;
  dropout.duration_ns = 50'000'000;
  ASSERT_TRUE(sim.injectFault(dropout));
  std::vector<SimEventRecord> events;
  int states_during_dropout = 0;
  for (int k = 0; k < 400; ++k) {
    sim.commands().submit(hoverCommand(sim), true, sim.timeNs(), sim.timeNs());
    const StepOutputs out = sim.step();
    events.insert(events.end(), out.events.begin(), out.events.end());
    if (sim.timeNs() < 50'000'000 && out.state) {
      ++states_during_dropout;
    }
  }
  EXPECT_EQ(states_during_dropout, 0);
  ASSERT_GE(events.size(), 4U);
  const auto find = [&](SimEventRecord::Kind kind, std::int64_t id) {
    return std::find_if(events.begin(), events.end(),
                        [&](const SimEventRecord& e) { return e.kind == kind && e.subject_id == id; });
  };
  const auto applied = find(SimEventRecord::Kind::kFaultApplied, 7);
  ASSERT_NE(applied, events.end());
  EXPECT_EQ(applied->t_ns, 100'000'000);
  EXPECT_EQ(applied->detail, "fault 7 motor: rotor 0 at 0 efficiency");
  const auto cleared = find(SimEventRecord::Kind::kFaultCleared, 7);
  ASSERT_NE(cleared, events.end());
  EXPECT_EQ(cleared->t_ns, 300'000'000);
  // With rotor 0 (front-left) dead at hover speed, the vehicle rolls left and sinks.
  EXPECT_LT(sim.state().p_W.z(), 10.0);
}

TEST(FaultSchedule, FileIsValidatedAndParsed)
{
  const auto faults = parseFaultSchedule(R"(
- {id: 1, kind: motor, rotor: 2, efficiency: 0.5, at: 10.0, duration: 5.0}
- {id: 2, kind: sensor_dropout, sensor: depth, at: 3}
- {id: 3, kind: wind_gust, wind: [4, 0, 0], at: 1, duration: 2}
- {id: 4, kind: sensor_noise, sensor: imu, std_dev: 0.5, at: 0}
- {id: 5, kind: push, force: [0, -20, 0], at: 6, duration: 0.5}
- {id: 6, kind: cell_loss, cells: 2, at: 7}
)",
                                         "faults.yaml");
  ASSERT_EQ(faults.size(), 6U);
  EXPECT_EQ(faults[5].kind, Fault::Kind::kCellLoss);
  EXPECT_EQ(faults[5].cells, 2);
  EXPECT_EQ(faults[4].kind, Fault::Kind::kPush);
  EXPECT_EQ(faults[4].force_W, Vector3(0, -20, 0));
  EXPECT_EQ(faults[0].rotor, 2);
  EXPECT_EQ(faults[0].start_ns, 10'000'000'000);
  EXPECT_EQ(faults[1].sensor, Sensor::kDepth);
  EXPECT_EQ(faults[2].wind_W, Vector3(4, 0, 0));
  try {
    parseFaultSchedule("- {id: 1, kind: motor, rotor: 5, efficiency: 0.5, at: 1}\n"
                       "- {id: 2, kind: sensor_stuck, sensor: lidar, at: 1}\n"
                       "- {id: 3, kind: meteor, at: 1}\n"
                       "- {id: 4, at: 1}\n"
                       "- {id: 5, kind: cell_loss, cells: 0, at: 1}",
                       "faults.yaml");
    FAIL();
  } catch (const common::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 5U) << e.what();
    EXPECT_EQ(e.problems()[4], "faults.yaml:[4].cells: 0: out of range [1, 16]");
    EXPECT_EQ(e.problems()[3], "faults.yaml:[3].kind: (missing): expected motor, sensor_dropout, "
                               "sensor_stuck, sensor_noise, sensor_offset, wind_gust, push or cell_loss");
    EXPECT_EQ(e.problems()[0], "faults.yaml:[0].rotor: 5: out of range [0, 3]");
    EXPECT_EQ(e.problems()[1],
              "faults.yaml:[1].sensor: lidar: expected depth, imu, state, position, baro, mag, range or range_up");
    EXPECT_EQ(e.problems()[2], "faults.yaml:[2].kind: meteor: expected motor, sensor_dropout, "
                               "sensor_stuck, sensor_noise, sensor_offset, wind_gust, push or cell_loss");
  }
}

}  // namespace
}  // namespace quad::plant
