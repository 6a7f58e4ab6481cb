// SPDX-License-Identifier: BSD-3-Clause
#include "quad/vehicle/vehicle.hpp"

#include <cmath>
#include <string>

namespace quad::vehicle {

std::array<Eigen::Vector3d, kRotorCount> VehicleParams::rotorPositions() const
{
  const double a = arm_length / std::sqrt(2.0);
  return {Eigen::Vector3d(a, a, 0), Eigen::Vector3d(-a, a, 0), Eigen::Vector3d(-a, -a, 0),
          Eigen::Vector3d(a, -a, 0)};
}

Eigen::Matrix4d VehicleParams::allocation() const
{
  Eigen::Matrix4d A;
  const auto positions = rotorPositions();
  for (int i = 0; i < kRotorCount; ++i) {
    const Eigen::Vector3d& r = positions[static_cast<std::size_t>(i)];
    // Torque of thrust at r: r × (0, 0, T) = (r_y T, −r_x T, 0); reaction about z: −spin k_m ω².
    A(0, i) = thrust_coefficient;
    A(1, i) = r.y() * thrust_coefficient;
    A(2, i) = -r.x() * thrust_coefficient;
    A(3, i) = -kSpin[static_cast<std::size_t>(i)] * torque_coefficient;
  }
  return A;
}

double VehicleParams::hoverRotorSpeed(double gravity) const
{
  return std::sqrt(mass * gravity / (kRotorCount * thrust_coefficient));
}

const common::ParamTable<VehicleParams>& vehicleTable()
{
  using common::Need;
  using V = VehicleParams;
  static const common::ParamTable<V> table = [] {
    common::ParamTable<V> t;
    t.number("mass", [](V& v) -> double& { return v.mass; }, {0.01, 1000.0}, "kg", "vehicle mass", Need::kRequired)
        .vector("inertia", [](V& v) -> Eigen::Vector3d& { return v.inertia; }, {1e-6, 1000.0}, "kg m^2",
                "principal moments of inertia about body x, y, z", Need::kRequired)
        .number("arm_length", [](V& v) -> double& { return v.arm_length; }, {0.01, 10.0}, "m",
                "centre to rotor axis", Need::kRequired)
        .number("rotor.thrust_coefficient", [](V& v) -> double& { return v.thrust_coefficient; }, {1e-12, 1.0},
                "N s^2/rad^2", "k_f: thrust = k_f w^2", Need::kRequired)
        .number("rotor.torque_coefficient", [](V& v) -> double& { return v.torque_coefficient; }, {0.0, 1.0},
                "N m s^2/rad^2", "k_m: reaction torque = k_m w^2", Need::kRequired)
        .number("rotor.speed_min", [](V& v) -> double& { return v.rotor_speed_min; }, {0.0, 1e5}, "rad/s",
                "lowest rotor speed")
        .number("rotor.speed_max", [](V& v) -> double& { return v.rotor_speed_max; }, {1.0, 1e5}, "rad/s",
                "highest rotor speed", Need::kRequired)
        .number("motor.time_constant_up", [](V& v) -> double& { return v.motor_time_constant_up; }, {1e-4, 10.0},
                "s", "first-order lag, speeding up")
        .number("motor.time_constant_down", [](V& v) -> double& { return v.motor_time_constant_down; },
                {1e-4, 10.0}, "s", "first-order lag, slowing down")
        .vector("drag.linear", [](V& v) -> Eigen::Vector3d& { return v.drag_linear; }, {0.0, 1e3}, "N s/m",
                "linear drag per body axis")
        .vector("drag.quadratic", [](V& v) -> Eigen::Vector3d& { return v.drag_quadratic; }, {0.0, 1e3},
                "N s^2/m^2", "quadratic drag per body axis")
        .number("radius", [](V& v) -> double& { return v.radius; }, {0.01, 10.0}, "m", "bounding sphere radius",
                Need::kRequired);
    return t;
  }();
  return table;
}

common::ParamSchema vehicleSchema() { return vehicleTable().schema(); }

VehicleParams vehicleFromParams(const common::Params& p)
{
  const VehicleParams v = vehicleTable().read(p);

  std::vector<std::string> problems;
  const std::string& origin = p.origin();
  if (v.rotor_speed_min >= v.rotor_speed_max) {
    problems.push_back(common::configProblem(origin, "rotor.speed_min", v.rotor_speed_min,
                                             "must be below rotor.speed_max (" +
                                                 common::formatValue(v.rotor_speed_max) + ")"));
  }
  const double max_thrust = kRotorCount * v.thrust_coefficient * v.rotor_speed_max * v.rotor_speed_max;
  if (max_thrust <= v.mass * 9.81) {
    problems.push_back(common::configProblem(origin, "rotor.speed_max", v.rotor_speed_max,
                                             "full thrust " + common::formatValue(max_thrust) +
                                                 " N cannot lift the weight " +
                                                 common::formatValue(v.mass * 9.81) + " N"));
  }
  const Eigen::Vector3d& J = v.inertia;
  if (J.x() + J.y() < J.z() || J.y() + J.z() < J.x() || J.x() + J.z() < J.y()) {
    problems.push_back(common::configProblem(origin, "inertia", std::vector<double>{J.x(), J.y(), J.z()},
                                             "violates the triangle inequality of principal moments"));
  }
  if (!problems.empty()) {
    throw common::ConfigError(problems);
  }
  return v;
}

VehicleParams loadVehicle(const std::filesystem::path& file)
{
  return vehicleFromParams(common::loadParams(file, vehicleSchema()));
}

}  // namespace quad::vehicle
