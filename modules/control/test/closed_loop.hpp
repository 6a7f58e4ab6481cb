// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The controller flying the plant core: the closed loop the control tests measure.

#include <functional>
#include <vector>

#include "quad/control/geometric_controller.hpp"
#include "quad/control/mixer.hpp"
#include "quad/plant/dynamics.hpp"

namespace quad::control::test {

vehicle::VehicleParams loadVehicle(const char* name);

/// Gains for a vehicle from Lee's normalised ones: k_x = 16 m, k_v = 5.6 m, and attitude
/// gains scaled by the inertia relative to Lee's vehicle.
GeometricGains scaledGains(const vehicle::VehicleParams& v);

struct Sample {
  double t;
  plant::RigidBodyState state;
  Reference ref;
  ControlOutput control;
  MixerOutput mixer;
};

/// Flies `seconds` with the controller at `control_hz` and the plant stepping 1 ms, starting
/// from `initial`; `reference(t)` gives the reference. Returns one sample per control tick.
std::vector<Sample> fly(const vehicle::VehicleParams& v, const GeometricGains& gains,
                        plant::RigidBodyState initial, double seconds,
                        const std::function<Reference(double)>& reference,
                        const plant::Environment& env = {}, double control_hz = 250.0);

/// As fly(), with the controller believing `model` while the plant flies `plant` (a mass off
/// its file, say).
std::vector<Sample> flyMismatched(const vehicle::VehicleParams& plant, const vehicle::VehicleParams& model,
                                  const GeometricGains& gains, plant::RigidBodyState initial, double seconds,
                                  const std::function<Reference(double)>& reference,
                                  const plant::Environment& env = {}, double control_hz = 250.0);

}  // namespace quad::control::test
