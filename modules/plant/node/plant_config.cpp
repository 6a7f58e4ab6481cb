#include "plant_config.hpp"

#include <sstream>

#include "quad/common/time.hpp"

namespace quad::plant {

common::ParamSchema plantSchema()
{
  common::ParamSchema s;
  s.addString("sim.mode", "realtime", {"realtime", "lockstep"}, "pace to the wall clock, or lockstep")
      .addDouble("sim.real_time_factor", 1.0, 0.01, 100.0, "", "sim seconds per wall second (realtime)")
      .addDouble("sim.step", 0.001, 1e-5, 0.01, "s", "RK4 integration step")
      .addInt("sim.seed", 1, 0, 4294967295.0, "", "seed of every random draw in the plant")
      .addDouble("sim.duration", 0.0, 0.0, 1e7, "s", "stop after this much sim time; 0 = never")
      .addString("lockstep.participants", "", {}, "comma-separated names the clock waits for")
      .addBool("lockstep.wait_for_command", true, "wait for the controller's command of each round")
      .addDouble("lockstep.period", 0.004, 1e-4, 1.0, "s", "sim time between lockstep rounds")
      .addDouble("lockstep.timeout", 5.0, 0.01, 3600.0, "s", "wall time before a stalled round is reported")
      .addString("vehicle", "vehicles/x500.yaml", {}, "vehicle file")
      .addString("world", "worlds/demo.yaml", {}, "world file")
      .addString("faults.schedule", "", {}, "fault schedule file; empty: none")
      .addDouble("commands.timeout", 0.1, 0.001, 10.0, "s", "rotor commands older than this are late")
      .addDouble("state.rate", 250.0, 1.0, 2000.0, "Hz", "vehicle state and clock rate")
      .addDouble("imu.rate", 250.0, 1.0, 2000.0, "Hz", "IMU rate")
      .addDouble("imu.accel_noise", 0.02, 0.0, 10.0, "m/s^2", "accelerometer white noise std dev")
      .addDouble("imu.gyro_noise", 0.002, 0.0, 10.0, "rad/s", "gyroscope white noise std dev")
      .addVector("imu.accel_bias", std::vector<double>{0, 0, 0}, 3, -10.0, 10.0, "m/s^2", "accelerometer bias")
      .addVector("imu.gyro_bias", std::vector<double>{0, 0, 0}, 3, -1.0, 1.0, "rad/s", "gyroscope bias")
      .addInt("depth.width", 64, 1, 1024, "px", "depth image width")
      .addInt("depth.height", 48, 1, 1024, "px", "depth image height")
      .addDouble("depth.fov", 1.5707963, 0.1, 3.0, "rad", "horizontal field of view")
      .addDouble("depth.max_range", 20.0, 0.1, 200.0, "m", "beyond this a ray is a miss")
      .addDouble("depth.noise", 0.01, 0.0, 10.0, "m", "range noise std dev")
      .addDouble("depth.rate", 10.0, 0.1, 100.0, "Hz", "depth frame rate")
      .addVector("depth.position", std::vector<double>{0.1, 0.0, 0.0}, 3, -5.0, 5.0, "m", "mount point, body frame")
      .addDouble("depth.tilt_down", 0.0, -1.5, 1.5, "rad", "optical axis pitched below body x (fixed mount)")
      .addBool("gimbal.enabled", false, "the depth camera hangs on a world-stabilised pan-tilt gimbal the controller aims")
      .addDouble("gimbal.slew_rate", 3.0, 0.01, 100.0, "rad/s", "per axis")
      .addDouble("gimbal.min_pitch", -1.5707963267948966, -1.5707963267948966, 1.5707963267948966, "rad",
                 "lowest elevation of the optical axis")
      .addDouble("gimbal.max_pitch", 1.5707963267948966, -1.5707963267948966, 1.5707963267948966, "rad",
                 "highest elevation of the optical axis");
  return s;
}

namespace {
Vector3 vec(const common::Params& p, const char* key)
{
  const auto& v = p.getVector(key);
  return {v[0], v[1], v[2]};
}
}  // namespace

PlantNodeConfig plantConfigFrom(const common::Params& p)
{
  PlantNodeConfig c;
  const std::string& origin = p.origin();
  c.mode = p.getString("sim.mode") == "lockstep" ? PlantNodeConfig::Mode::kLockstep
                                                 : PlantNodeConfig::Mode::kRealTime;
  c.real_time_factor = p.getDouble("sim.real_time_factor");
  c.duration_s = p.getDouble("sim.duration");
  std::stringstream names(p.getString("lockstep.participants"));
  for (std::string name; std::getline(names, name, ',');) {
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (!name.empty()) {
      c.lockstep_participants.push_back(name);
    }
  }
  c.lockstep_wait_for_command = p.getBool("lockstep.wait_for_command");
  c.lockstep_timeout_s = p.getDouble("lockstep.timeout");
  c.vehicle_file = common::configPath(p, "vehicle", QUAD_CONFIG_DIR);
  c.world_file = common::configPath(p, "world", QUAD_CONFIG_DIR);
  c.fault_schedule_file = common::configPath(p, "faults.schedule", QUAD_CONFIG_DIR);

  SimulationConfig& s = c.simulation;
  s.step_ns = common::toNanoseconds(p.getDouble("sim.step"));
  s.seed = static_cast<std::uint64_t>(p.getInt("sim.seed"));
  s.command_timeout_ns = common::toNanoseconds(p.getDouble("commands.timeout"));
  s.state_rate_hz = p.getDouble("state.rate");
  s.imu.rate_hz = p.getDouble("imu.rate");
  s.imu.accel_noise_std = p.getDouble("imu.accel_noise");
  s.imu.gyro_noise_std = p.getDouble("imu.gyro_noise");
  s.imu.accel_bias = vec(p, "imu.accel_bias");
  s.imu.gyro_bias = vec(p, "imu.gyro_bias");
  s.depth.width = static_cast<int>(p.getInt("depth.width"));
  s.depth.height = static_cast<int>(p.getInt("depth.height"));
  s.depth.horizontal_fov = p.getDouble("depth.fov");
  s.depth.max_range = p.getDouble("depth.max_range");
  s.depth.noise_std = p.getDouble("depth.noise");
  s.depth.rate_hz = p.getDouble("depth.rate");
  s.depth.position_B = vec(p, "depth.position");
  s.depth.tilt_down = p.getDouble("depth.tilt_down");
  s.gimbal.enabled = p.getBool("gimbal.enabled");
  s.gimbal.slew_rate = p.getDouble("gimbal.slew_rate");
  s.gimbal.min_pitch = p.getDouble("gimbal.min_pitch");
  s.gimbal.max_pitch = p.getDouble("gimbal.max_pitch");

  std::vector<std::string> problems;
  c.lockstep_period_ns = common::toNanoseconds(p.getDouble("lockstep.period"));
  if (c.lockstep_period_ns % s.step_ns != 0) {
    problems.push_back(common::configProblem(origin, "lockstep.period", p.getDouble("lockstep.period"),
                                             "must be a whole number of sim.step (" +
                                                 common::formatValue(p.getDouble("sim.step")) + ")"));
  }
  if (s.gimbal.min_pitch > s.gimbal.max_pitch) {
    problems.push_back(common::configProblem(origin, "gimbal.min_pitch", s.gimbal.min_pitch,
                                             "above gimbal.max_pitch (" + common::formatValue(s.gimbal.max_pitch) + ")"));
  }
  if (s.depth.width * s.depth.height > 65536) {
    problems.push_back(common::configProblem(origin, "depth.width", std::int64_t{s.depth.width},
                                             "width x height = " + std::to_string(s.depth.width * s.depth.height) +
                                                 " exceeds the 65536 points a PointCloud carries"));
  }
  if (!problems.empty()) {
    throw common::ConfigError(problems);
  }
  return c;
}

}  // namespace quad::plant
