// SPDX-License-Identifier: BSD-3-Clause
#include "closed_loop.hpp"

#include <cmath>
#include <string>

namespace quad::control::test {

vehicle::VehicleParams loadVehicle(const char* name)
{
  return vehicle::loadVehicle(std::string(QUAD_CONFIG_DIR) + "/vehicles/" + name + ".yaml");
}

GeometricGains scaledGains(const vehicle::VehicleParams& v)
{
  GeometricGains g;
  g.kx = 16.0 * v.mass;
  g.kv = 5.6 * v.mass;
  const double inertia_ratio = v.inertia.mean() / Vector3(0.0820, 0.0845, 0.1377).mean();
  g.kR = 8.81 * inertia_ratio;
  g.kOmega = 2.54 * inertia_ratio;
  return g;
}

std::vector<Sample> fly(const vehicle::VehicleParams& v, const GeometricGains& gains,
                        plant::RigidBodyState s, double seconds,
                        const std::function<Reference(double)>& reference, const plant::Environment& env,
                        double control_hz)
{
  return flyMismatched(v, v, gains, s, seconds, reference, env, control_hz);
}

std::vector<Sample> flyMismatched(const vehicle::VehicleParams& plant, const vehicle::VehicleParams& model,
                                  const GeometricGains& gains, plant::RigidBodyState s, double seconds,
                                  const std::function<Reference(double)>& reference, const plant::Environment& env,
                                  double control_hz)
{
  const plant::QuadrotorDynamics dynamics(plant);
  GeometricController controller(model.mass, model.inertia, gains);
  const Mixer mixer(model);
  const int steps_per_tick = static_cast<int>(std::lround(1000.0 / control_hz));
  const double dt = steps_per_tick * 1e-3;
  std::vector<Sample> out;
  const int ticks = static_cast<int>(std::lround(seconds * control_hz));
  for (int k = 0; k < ticks; ++k) {
    const double t = k * dt;
    const Reference ref = reference(t);
    const ControlOutput c = controller.update({s.p_W, s.v_W, s.q_WB, s.w_B}, ref, dt);
    const MixerOutput m = mixer.mix(c.thrust, c.torque_B);
    out.push_back({t, s, ref, c, m});
    for (int i = 0; i < steps_per_tick; ++i) {
      dynamics.step(s, m.rotor_speed, env, 1e-3);
    }
  }
  return out;
}

}  // namespace quad::control::test
