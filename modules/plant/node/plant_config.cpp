// SPDX-License-Identifier: BSD-3-Clause
#include "plant_config.hpp"

#include "quad/common/layout.hpp"
#include "quad/common/time.hpp"

namespace quad::plant {

namespace {

/// One rangefinder's keys under `prefix`, filling the simulation's `which`.
void declareRangefinder(common::ParamTable<PlantNodeConfig>& t, const std::string& prefix,
                        RangefinderConfig SimulationConfig::*which, const std::string& what)
{
  using C = PlantNodeConfig;
  const auto of = [which](C& c) -> RangefinderConfig& { return c.simulation.*which; };
  t.flag(prefix + ".enabled", [of](C& c) -> bool& { return of(c).enabled; }, "publish the " + what)
      .number(prefix + ".rate", [of](C& c) -> double& { return of(c).rate_hz; }, {0.1, 1000.0}, "Hz",
              "rangefinder rate (it also reads once at the first step)")
      .number(prefix + ".max", [of](C& c) -> double& { return of(c).max_range; }, {0.1, 1000.0}, "m",
              "the farthest surface it measures")
      .number(prefix + ".noise", [of](C& c) -> double& { return of(c).noise_std; }, {0.0, 10.0}, "m",
              "white noise std dev");
}

}  // namespace

const common::ParamTable<PlantNodeConfig>& plantTable()
{
  using C = PlantNodeConfig;
  using Mode = PlantNodeConfig::Mode;
  static const common::ParamTable<C> table = [] {
    common::ParamTable<C> t;
    t.choice("sim.mode", [](C& c) -> Mode& { return c.mode; }, {{"realtime", Mode::kRealTime}, {"lockstep", Mode::kLockstep}},
             "pace to the wall clock, or lockstep")
        .number("sim.real_time_factor", [](C& c) -> double& { return c.real_time_factor; }, {0.01, 100.0}, "",
                "sim seconds per wall second (realtime)")
        .seconds("sim.step", [](C& c) -> std::int64_t& { return c.simulation.step_ns; }, {1e-5, 0.01},
                 "RK4 integration step")
        .number("sim.seed", [](C& c) -> std::uint64_t& { return c.simulation.seed; }, {0, 4294967295.0}, "",
                "seed of every random draw in the plant")
        .number("sim.duration", [](C& c) -> double& { return c.duration_s; }, {0.0, 1e7}, "s",
                "stop after this much sim time; 0 = never")
        .flag("sim.crash_on_impact", [](C& c) -> bool& { return c.simulation.crash_on_impact; },
              "an impact with a solid stops the vehicle there and ends the run; false: count it and fly on")
        .list("lockstep.participants", [](C& c) -> std::vector<std::string>& { return c.lockstep_participants; },
              "comma-separated names the clock waits for")
        .flag("lockstep.wait_for_command", [](C& c) -> bool& { return c.lockstep_wait_for_command; },
              "wait for the controller's command of each round")
        .seconds("lockstep.period", [](C& c) -> std::int64_t& { return c.lockstep_period_ns; }, {1e-4, 1.0},
                 "sim time between lockstep rounds");
    runtime::declareStateSource(
        t, [](C& c) -> runtime::StateSource& { return c.state_source; },
        "; in lockstep a round waits for the command answering it (the estimate follows each IMU sample)");
    t.number("lockstep.timeout", [](C& c) -> double& { return c.lockstep_timeout_s; }, {0.01, 3600.0}, "s",
                "wall time before a stalled round is reported")
        .path("vehicle", [](C& c) -> std::filesystem::path& { return c.vehicle_file; }, "vehicle file")
        .path("world", [](C& c) -> std::filesystem::path& { return c.world_file; }, "world file")
        .path("faults.schedule", [](C& c) -> std::filesystem::path& { return c.fault_schedule_file; },
              "fault schedule file; empty: none")
        .path("fleet", [](C& c) -> std::filesystem::path& { return c.fleet_file; },
              "fleet file: the vehicles simulated, each with its id and start; empty: one vehicle, this "
              "participant's, at the world's start")
        .seconds("commands.timeout", [](C& c) -> std::int64_t& { return c.simulation.command_timeout_ns; },
                 {0.001, 10.0}, "rotor commands older than this are late")
        .seconds("commands.failsafe_after",
                 [](C& c) -> std::int64_t& { return c.simulation.command_failsafe_ns; }, {0.001, 10.0},
                 "a held rotor command older than this is flown balanced (no torque)")
        .number("state.rate", [](C& c) -> double& { return c.simulation.state_rate_hz; }, {1.0, 2000.0}, "Hz",
                "vehicle state and clock rate")
        .number("imu.rate", [](C& c) -> double& { return c.simulation.imu.rate_hz; }, {1.0, 2000.0}, "Hz", "IMU rate")
        .number("imu.accel_noise", [](C& c) -> double& { return c.simulation.imu.accel_noise_std; }, {0.0, 10.0},
                "m/s^2", "accelerometer white noise std dev")
        .number("imu.gyro_noise", [](C& c) -> double& { return c.simulation.imu.gyro_noise_std; }, {0.0, 10.0},
                "rad/s", "gyroscope white noise std dev")
        .vector("wind.steady", [](C& c) -> Vector3& { return c.simulation.wind.steady_W; }, {-50.0, 50.0}, "m/s",
                "steady wind, world frame")
        .number("wind.turbulence_w20", [](C& c) -> double& { return c.simulation.wind.turbulence_w20; },
                {0.0, 40.0}, "m/s", "Dryden turbulence (MIL-F-8785C) for this wind at 20 ft; 0: none")
        .vector("imu.accel_bias", [](C& c) -> Vector3& { return c.simulation.imu.accel_bias; }, {-10.0, 10.0},
                "m/s^2", "accelerometer bias")
        .vector("imu.gyro_bias", [](C& c) -> Vector3& { return c.simulation.imu.gyro_bias; }, {-1.0, 1.0}, "rad/s",
                "gyroscope bias")
        .number("imu.accel_turn_on", [](C& c) -> double& { return c.simulation.imu.accel_turn_on_std; }, {0.0, 10.0},
                "m/s^2", "std dev of the accelerometer bias drawn at each start, per axis")
        .number("imu.gyro_turn_on", [](C& c) -> double& { return c.simulation.imu.gyro_turn_on_std; }, {0.0, 1.0},
                "rad/s", "std dev of the gyroscope bias drawn at each start, per axis")
        .number("imu.accel_bias_walk", [](C& c) -> double& { return c.simulation.imu.accel_bias_walk; }, {0.0, 1.0},
                "m/s^2/sqrt(s)", "accelerometer bias random walk")
        .number("imu.gyro_bias_walk", [](C& c) -> double& { return c.simulation.imu.gyro_bias_walk; }, {0.0, 0.1},
                "rad/s/sqrt(s)", "gyroscope bias random walk")
        .flag("position.enabled", [](C& c) -> bool& { return c.simulation.position.enabled; },
              "publish absolute position fixes (GNSS or motion capture)")
        .number("position.rate", [](C& c) -> double& { return c.simulation.position.rate_hz; }, {0.1, 1000.0}, "Hz",
                "position fix rate")
        .number("position.noise", [](C& c) -> double& { return c.simulation.position.noise_std; }, {0.0001, 100.0}, "m",
                "white noise std dev per axis")
        .number("position.latency", [](C& c) -> double& { return c.simulation.position.latency; }, {0.0, 5.0}, "s",
                "from a fix's measurement to its delivery")
        .number("position.outages_per_minute", [](C& c) -> double& { return c.simulation.position.outages_per_minute; },
                {0.0, 600.0}, "1/min", "random outages (a Poisson process); 0: none")
        .number("position.outage_duration", [](C& c) -> double& { return c.simulation.position.outage_duration; },
                {0.01, 3600.0}, "s", "mean length of an outage")
        .flag("baro.enabled", [](C& c) -> bool& { return c.simulation.baro.enabled; }, "publish barometric altitude")
        .number("baro.rate", [](C& c) -> double& { return c.simulation.baro.rate_hz; }, {0.1, 1000.0}, "Hz",
                "barometer rate")
        .number("baro.noise", [](C& c) -> double& { return c.simulation.baro.noise_std; }, {0.0001, 100.0}, "m",
                "white noise std dev")
        .number("baro.offset", [](C& c) -> double& { return c.simulation.baro.offset_std; }, {0.0, 1000.0}, "m",
                "std dev of the offset drawn at each start (the pressure of the day)")
        .number("baro.drift", [](C& c) -> double& { return c.simulation.baro.drift_walk; }, {0.0, 10.0}, "m/sqrt(s)",
                "random walk of the offset")
        .flag("mag.enabled", [](C& c) -> bool& { return c.simulation.mag.enabled; }, "publish the magnetometer")
        .number("mag.rate", [](C& c) -> double& { return c.simulation.mag.rate_hz; }, {0.1, 1000.0}, "Hz",
                "magnetometer rate")
        .vector("mag.field", [](C& c) -> Vector3& { return c.simulation.mag.field_W; }, {-100.0, 100.0}, "uT",
                "Earth's field in the world frame (ENU)")
        .number("mag.noise", [](C& c) -> double& { return c.simulation.mag.noise_std; }, {0.0001, 100.0}, "uT",
                "white noise std dev per axis");
    declareRangefinder(t, "range", &SimulationConfig::range,
                       "downward rangefinder (the controller knows from it what the vehicle stands on)");
    declareRangefinder(t, "range_up", &SimulationConfig::range_up,
                       "upward rangefinder (the controller knows from it how high the ceiling over it is)");
    t.number("depth.width", [](C& c) -> int& { return c.simulation.depth.width; }, {1, 1024}, "px",
                "depth image width")
        .number("depth.height", [](C& c) -> int& { return c.simulation.depth.height; }, {1, 1024}, "px",
                "depth image height")
        .number("depth.fov", [](C& c) -> double& { return c.simulation.depth.horizontal_fov; }, {0.1, 3.0}, "rad",
                "horizontal field of view")
        .number("depth.max_range", [](C& c) -> double& { return c.simulation.depth.max_range; }, {0.1, 200.0}, "m",
                "beyond this a ray is a miss")
        .number("depth.noise", [](C& c) -> double& { return c.simulation.depth.noise_std; }, {0.0, 10.0}, "m",
                "range noise std dev")
        .number("depth.rate", [](C& c) -> double& { return c.simulation.depth.rate_hz; }, {0.1, 100.0}, "Hz",
                "depth frame rate")
        .vector("depth.position", [](C& c) -> Vector3& { return c.simulation.depth.position_B; }, {-5.0, 5.0}, "m",
                "mount point, body frame")
        .number("depth.tilt_down", [](C& c) -> double& { return c.simulation.depth.tilt_down; }, {-1.5, 1.5}, "rad",
                "optical axis pitched below body x (fixed mount)")
        .flag("battery.enabled", [](C& c) -> bool& { return c.simulation.battery.enabled; },
              "fly on a battery that drains and sags; off: an ideal supply")
        .number("battery.cells", [](C& c) -> int& { return c.simulation.battery.cells; }, {1, 16}, "",
                "lithium-polymer cells in series")
        .number("battery.capacity", [](C& c) -> double& { return c.simulation.battery.capacity; }, {0.001, 1000.0},
                "Ah", "the pack's capacity")
        .number("battery.initial_charge", [](C& c) -> double& { return c.simulation.battery.initial_charge; },
                {0.0, 1.0}, "", "fraction of the capacity at the start")
        .number("battery.resistance", [](C& c) -> double& { return c.simulation.battery.resistance; }, {0.0, 10.0},
                "ohm", "the pack's internal resistance (voltage sag under load)")
        .number("battery.rated_cell_voltage", [](C& c) -> double& { return c.simulation.battery.rated_cell_voltage; },
                {2.5, 4.2}, "V", "a cell's voltage below which the rotors' top speed falls with it")
        .number("battery.motor_efficiency", [](C& c) -> double& { return c.simulation.battery.motor_efficiency; },
                {0.05, 1.0}, "", "rotor shaft power over electric power")
        .number("battery.avionics_power", [](C& c) -> double& { return c.simulation.battery.avionics_power; },
                {0.0, 1000.0}, "W", "drawn besides the rotors")
        .number("battery.rate", [](C& c) -> double& { return c.simulation.battery_rate_hz; }, {0.1, 1000.0}, "Hz",
                "battery readings")
        .flag("gimbal.enabled", [](C& c) -> bool& { return c.simulation.gimbal.enabled; },
              "the depth camera hangs on a world-stabilised pan-tilt gimbal the controller aims")
        .number("gimbal.slew_rate", [](C& c) -> double& { return c.simulation.gimbal.slew_rate; }, {0.01, 100.0},
                "rad/s", "per axis")
        .number("gimbal.min_pitch", [](C& c) -> double& { return c.simulation.gimbal.min_pitch; },
                {-1.5707963267948966, 1.5707963267948966}, "rad", "lowest elevation of the optical axis")
        .number("gimbal.max_pitch", [](C& c) -> double& { return c.simulation.gimbal.max_pitch; },
                {-1.5707963267948966, 1.5707963267948966}, "rad", "highest elevation of the optical axis");
    return t;
  }();
  return table;
}

common::ParamSchema plantSchema() { return plantTable().schema(); }

PlantNodeConfig plantConfigFrom(const common::Params& p)
{
  const PlantNodeConfig c = plantTable().read(p, common::configDir());
  const SimulationConfig& s = c.simulation;
  const std::string& origin = p.origin();

  std::vector<std::string> problems;
  if (c.lockstep_period_ns % s.step_ns != 0) {
    problems.push_back(common::configProblem(origin, "lockstep.period", common::toSeconds(c.lockstep_period_ns),
                                             "must be a whole number of sim.step (" +
                                                 common::formatValue(common::toSeconds(s.step_ns)) + ")"));
  }
  if (s.gimbal.min_pitch > s.gimbal.max_pitch) {
    problems.push_back(common::configProblem(origin, "gimbal.min_pitch", s.gimbal.min_pitch,
                                             "above gimbal.max_pitch (" + common::formatValue(s.gimbal.max_pitch) + ")"));
  }
  if (s.mag.enabled && s.mag.field_W.head<2>().norm() < 1.0) {
    problems.push_back(common::configProblem(origin, "mag.field", s.mag.field_W.head<2>().norm(),
                                             "horizontal part in uT: below 1 uT the field gives no heading"));
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
