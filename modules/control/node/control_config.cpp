#include "control_config.hpp"

#include "quad/dds/topics.hpp"

namespace quad::control {

common::ParamSchema controlSchema()
{
  common::ParamSchema s;
  s.addString("vehicle", "vehicles/x500.yaml", {}, "vehicle file (the plant's)")
      .addDouble("gains.position", 32.0, 0.01, 1e4, "N/m", "k_x")
      .addDouble("gains.velocity", 11.2, 0.01, 1e4, "N s/m", "k_v")
      .addDouble("gains.attitude", 2.33, 1e-3, 1e3, "N m/rad", "k_R")
      .addDouble("gains.rate", 0.673, 1e-4, 1e3, "N m s/rad", "k_Omega")
      .addDouble("gains.yaw_weight", 0.4, 0.01, 1.0, "", "yaw's share of the attitude error")
      .addString("gains.attitude_error", "quaternion", {"quaternion", "lee2010"},
                 "2 sin(theta/2) about the error axis, or Lee 2010's sin(theta) (slow from upside down)")
      .addDouble("limits.max_tilt", 0.6, 0.05, 1.5, "rad", "desired thrust vector from vertical")
      .addVector("limits.max_rate", std::vector<double>{6.0, 6.0, 2.0}, 3, 0.1, 50.0, "rad/s", "body rate limits")
      .addDouble("limits.max_acceleration", 8.0, 0.1, 50.0, "m/s^2", "horizontal feedback acceleration")
      .addDouble("follower.max_speed", 2.0, 0.05, 30.0, "m/s", "along the path")
      .addDouble("follower.max_acceleration", 2.0, 0.05, 30.0, "m/s^2", "along the path")
      .addDouble("follower.max_jerk", 6.0, 0.1, 500.0, "m/s^3", "along the path")
      .addDouble("follower.max_lateral_acceleration", 2.0, 0.05, 30.0, "m/s^2", "in curves")
      .addDouble("follower.max_yaw_rate", 1.0, 0.01, 10.0, "rad/s", "heading change")
      .addDouble("follower.corner_deviation", 0.1, 0.0, 5.0, "m", "rounded corners stay this close to the path")
      .addDouble("follower.max_braking", 4.0, 0.05, 30.0, "m/s^2",
                 "hardest braking, only when a path joined while moving turns back after its lead-in")
      .addDouble("takeoff_altitude", 2.0, 0.2, 100.0, "m", "above the take-off point")
      .addDouble("land_speed", 0.5, 0.05, 5.0, "m/s", "descent in LAND")
      .addDouble("timeouts.state", dds::topics::kSimState.info.stale_after_s, 0.005, 10.0, "s",
                 "vehicle state older than this is stale (default: the quad/sim/state contract's)")
      .addDouble("timeouts.path", dds::topics::kPath.info.stale_after_s, 0.05, 600.0, "s",
                 "path not republished for this long is stale (default: the quad/planning/path contract's)")
      .addDouble("goal_tolerance", 0.3, 0.01, 10.0, "m", "when the goal gives none")
      .addDouble("failsafe_thrust", 0.85, 0.3, 1.0, "", "fraction of the weight in a blind descent")
      .addDouble("dead_reckoning_horizon", 2.0, 0.0, 30.0, "s",
                 "how long the IMU may carry the last state on while it is stale (0: never)")
      .addDouble("modes.path_stale_land_after", 5.0, 0.0, 3600.0, "s", "hover without a path, then land")
      .addDouble("modes.no_path_land_after", 5.0, 0.0, 3600.0, "s",
                 "hover while the planner says the goal cannot be reached, then land")
      .addDouble("camera.look_ahead", 3.0, 0.1, 100.0, "m", "the camera gimbal looks at the path this far ahead")
      .addDouble("modes.idle_disarm_after", 30.0, 0.1, 1e6, "s", "armed on the ground, then disarm")
      .addBool("modes.auto_mission", false, "start the mission as soon as a path is available")
      .addBool("autostart", false, "arm and take off once the vehicle state is fresh")
      .addDouble("status.rate", 20.0, 0.1, 1000.0, "Hz", "control status publication");
  return s;
}

ControlNodeConfig controlConfigFrom(const common::Params& p)
{
  ControlNodeConfig c;
  c.vehicle_file = common::configPath(p, "vehicle", QUAD_CONFIG_DIR);
  FlightControllerConfig& f = c.flight;
  f.gains.kx = p.getDouble("gains.position");
  f.gains.kv = p.getDouble("gains.velocity");
  f.gains.kR = p.getDouble("gains.attitude");
  f.gains.kOmega = p.getDouble("gains.rate");
  f.gains.yaw_weight = p.getDouble("gains.yaw_weight");
  f.gains.attitude_error = p.getString("gains.attitude_error") == "lee2010" ? AttitudeError::kLee2010
                                                                              : AttitudeError::kQuaternion;
  f.gains.max_tilt = p.getDouble("limits.max_tilt");
  const auto& rate = p.getVector("limits.max_rate");
  f.gains.max_rate = Vector3(rate[0], rate[1], rate[2]);
  f.gains.max_acceleration = p.getDouble("limits.max_acceleration");
  f.follower.max_speed = p.getDouble("follower.max_speed");
  f.follower.max_acceleration = p.getDouble("follower.max_acceleration");
  f.follower.max_jerk = p.getDouble("follower.max_jerk");
  f.follower.max_lateral_acceleration = p.getDouble("follower.max_lateral_acceleration");
  f.follower.max_yaw_rate = p.getDouble("follower.max_yaw_rate");
  f.follower.corner_deviation = p.getDouble("follower.corner_deviation");
  f.follower.max_braking = p.getDouble("follower.max_braking");
  f.takeoff_altitude = p.getDouble("takeoff_altitude");
  f.land_speed = p.getDouble("land_speed");
  f.state_timeout = p.getDouble("timeouts.state");
  f.path_timeout = p.getDouble("timeouts.path");
  f.goal_tolerance = p.getDouble("goal_tolerance");
  f.failsafe_thrust = p.getDouble("failsafe_thrust");
  f.dead_reckoning_horizon = p.getDouble("dead_reckoning_horizon");
  f.modes.path_stale_land_after = p.getDouble("modes.path_stale_land_after");
  f.modes.idle_disarm_after = p.getDouble("modes.idle_disarm_after");
  f.modes.no_path_land_after = p.getDouble("modes.no_path_land_after");
  f.camera_look_ahead = p.getDouble("camera.look_ahead");
  f.modes.auto_mission = p.getBool("modes.auto_mission");
  c.autostart = p.getBool("autostart");
  c.status_rate = p.getDouble("status.rate");
  return c;
}

}  // namespace quad::control
