// SPDX-License-Identifier: BSD-3-Clause
// Cost of one control tick: the SE(3) controller and mixer, and the whole FlightController
// (modes, follower, controller, mixer) in a mission.
#include <benchmark/benchmark.h>

#include "quad/control/flight_controller.hpp"

namespace {

using namespace quad::control;

quad::vehicle::VehicleParams x500()
{
  quad::vehicle::VehicleParams v;
  v.mass = 2.0;
  v.inertia = {0.0217, 0.0217, 0.040};
  v.arm_length = 0.25;
  v.thrust_coefficient = 8.54858e-6;
  v.torque_coefficient = 1.3677e-7;
  return v;
}

/// Argument 0: the quaternion attitude error (the default); 1: Lee 2010's sin θ form.
void BM_GeometricControllerAndMixer(benchmark::State& state)
{
  const auto v = x500();
  GeometricGains gains;
  gains.attitude_error = state.range(0) == 0 ? AttitudeError::kQuaternion : AttitudeError::kLee2010;
  GeometricController controller(v.mass, v.inertia, gains);
  const Mixer mixer(v);
  VehicleState s;
  s.p_W = {0.1, -0.2, 1.9};
  s.q_WB = quad::geometry::fromAxisAngle(Vector3(1, 2, 3), 0.1);
  s.w_B = {0.1, 0.0, -0.1};
  Reference r;
  r.p_W = {1, 0, 2};
  r.v_W = {1, 0, 0};
  for (auto _ : state) {
    const ControlOutput out = controller.update(s, r, 0.004);
    benchmark::DoNotOptimize(mixer.mix(out.thrust, out.torque_B));
  }
}

void BM_FlightControllerTickInMission(benchmark::State& state)
{
  const auto v = x500();
  FlightControllerConfig config;
  FlightController fc(v, config);
  double t = 0.0;
  VehicleState s;
  fc.onState(s, t, {.landed = true});
  fc.onCommand(Command::kArm);
  fc.update(t);
  fc.onCommand(Command::kTakeoff);
  for (int k = 0; k < 2000 && fc.mode() != Mode::kHover; ++k) {  // the state follows the reference
    t += 0.004;
    fc.onState(s, t, {.landed = false});
    s.p_W = fc.update(t).reference.p_W;
  }
  fc.onPath({{0, 0, 2}, {100, 0, 2}, {100, 50, 2}}, 1, PathKind::kOk, t);
  fc.onCommand(Command::kStartMission);
  for (auto _ : state) {
    t += 0.004;
    fc.onState(s, t, {.landed = false});
    fc.onPath({{0, 0, 2}, {100, 0, 2}, {100, 50, 2}}, 1, PathKind::kOk, t);
    const FlightOutput out = fc.update(t);
    s.p_W = out.reference.p_W;
    benchmark::DoNotOptimize(out);
  }
  state.counters["mission"] = fc.mode() == Mode::kMission ? 1 : 0;
}

BENCHMARK(BM_GeometricControllerAndMixer)->ArgName("lee2010")->Arg(0)->Arg(1);
BENCHMARK(BM_FlightControllerTickInMission);

}  // namespace

BENCHMARK_MAIN();
