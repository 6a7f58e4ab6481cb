// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The vehicle the plant's tests fly: 2 kg, a 0.35 m sphere, no drag, so that motions have
/// closed forms.

#include "quad/vehicle/vehicle.hpp"

namespace quad::plant::test {

inline vehicle::VehicleParams dragFreeVehicle()
{
  vehicle::VehicleParams v;
  v.mass = 2.0;
  v.radius = 0.35;
  v.drag_linear.setZero();
  v.drag_quadratic.setZero();
  return v;
}

}  // namespace quad::plant::test
