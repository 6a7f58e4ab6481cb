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

common::ParamSchema vehicleSchema()
{
  common::ParamSchema s;
  s.addDouble("mass", std::nullopt, 0.01, 1000.0, "kg", "vehicle mass")
      .addVector("inertia", std::nullopt, 3, 1e-6, 1000.0, "kg m^2",
                 "principal moments of inertia about body x, y, z")
      .addDouble("arm_length", std::nullopt, 0.01, 10.0, "m", "centre to rotor axis")
      .addDouble("rotor.thrust_coefficient", std::nullopt, 1e-12, 1.0, "N s^2/rad^2",
                 "k_f: thrust = k_f w^2")
      .addDouble("rotor.torque_coefficient", std::nullopt, 0.0, 1.0, "N m s^2/rad^2",
                 "k_m: reaction torque = k_m w^2")
      .addDouble("rotor.speed_min", 0.0, 0.0, 1e5, "rad/s", "lowest rotor speed")
      .addDouble("rotor.speed_max", std::nullopt, 1.0, 1e5, "rad/s", "highest rotor speed")
      .addDouble("motor.time_constant_up", 0.02, 1e-4, 10.0, "s", "first-order lag, speeding up")
      .addDouble("motor.time_constant_down", 0.04, 1e-4, 10.0, "s",
                 "first-order lag, slowing down")
      .addVector("drag.linear", std::vector<double>{0.0, 0.0, 0.0}, 3, 0.0, 1e3, "N s/m",
                 "linear drag per body axis")
      .addVector("drag.quadratic", std::vector<double>{0.0, 0.0, 0.0}, 3, 0.0, 1e3, "N s^2/m^2",
                 "quadratic drag per body axis")
      .addDouble("radius", std::nullopt, 0.01, 10.0, "m", "bounding sphere radius");
  return s;
}

VehicleParams vehicleFromParams(const common::Params& p)
{
  const auto vec = [&p](const char* key) {
    const auto& v = p.getVector(key);
    return Eigen::Vector3d(v[0], v[1], v[2]);
  };
  VehicleParams v;
  v.mass = p.getDouble("mass");
  v.inertia = vec("inertia");
  v.arm_length = p.getDouble("arm_length");
  v.thrust_coefficient = p.getDouble("rotor.thrust_coefficient");
  v.torque_coefficient = p.getDouble("rotor.torque_coefficient");
  v.rotor_speed_min = p.getDouble("rotor.speed_min");
  v.rotor_speed_max = p.getDouble("rotor.speed_max");
  v.motor_time_constant_up = p.getDouble("motor.time_constant_up");
  v.motor_time_constant_down = p.getDouble("motor.time_constant_down");
  v.drag_linear = vec("drag.linear");
  v.drag_quadratic = vec("drag.quadratic");
  v.radius = p.getDouble("radius");

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
