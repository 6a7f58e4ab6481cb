// SPDX-License-Identifier: BSD-3-Clause
#include "control_config.hpp"

#include "quad/common/layout.hpp"
#include "quad/dds/topics.hpp"

namespace quad::control {

FlightControllerConfig nodeFlightDefaults()
{
  FlightControllerConfig f;
  f.gains.kx = 32.0;
  f.gains.kv = 11.2;
  f.gains.kR = 2.33;
  f.gains.kOmega = 0.673;
  f.gains.ki = 16.0;
  f.modes.idle_disarm_after = 30.0;
  f.state_timeout = dds::topics::kEstimatedState.info.stale_after_s;  // the truth's is the same
  f.path_timeout = dds::topics::kPath.info.stale_after_s;
  return f;
}

const common::ParamTable<ControlNodeConfig>& controlTable()
{
  using C = ControlNodeConfig;
  static const common::ParamTable<C> table = [] {
    common::ParamTable<C> t;
    t.path("vehicle", [](C& c) -> std::filesystem::path& { return c.vehicle_file; }, "vehicle file (the plant's)");
    runtime::declareStateSource(t, [](C& c) -> runtime::StateSource& { return c.state_source; });
    t.number("gains.position", [](C& c) -> double& { return c.flight.gains.kx; }, {0.01, 1e4}, "N/m", "k_x")
        .number("gains.velocity", [](C& c) -> double& { return c.flight.gains.kv; }, {0.01, 1e4}, "N s/m", "k_v")
        .number("gains.integral", [](C& c) -> double& { return c.flight.gains.ki; }, {0.0, 1e4}, "N/(m s)",
                "k_i, on the position error's integral; 0: none")
        .number("gains.integral_limit", [](C& c) -> double& { return c.flight.gains.integral_limit; }, {0.0, 1e3},
                "N", "the most force the integral adds on each axis")
        .number("gains.attitude", [](C& c) -> double& { return c.flight.gains.kR; }, {1e-3, 1e3}, "N m/rad", "k_R")
        .number("gains.rate", [](C& c) -> double& { return c.flight.gains.kOmega; }, {1e-4, 1e3}, "N m s/rad",
                "k_Omega")
        .number("gains.yaw_weight", [](C& c) -> double& { return c.flight.gains.yaw_weight; }, {0.01, 1.0}, "",
                "yaw's share of the attitude error")
        .choice("gains.attitude_error", [](C& c) -> AttitudeError& { return c.flight.gains.attitude_error; },
                {{"quaternion", AttitudeError::kQuaternion}, {"lee2010", AttitudeError::kLee2010}},
                "2 sin(theta/2) about the error axis, or Lee 2010's sin(theta) (slow from upside down)")
        .number("limits.max_tilt", [](C& c) -> double& { return c.flight.gains.max_tilt; }, {0.05, 1.5}, "rad",
                "desired thrust vector from vertical")
        .vector("limits.max_rate", [](C& c) -> Vector3& { return c.flight.gains.max_rate; }, {0.1, 50.0}, "rad/s",
                "body rate limits")
        .number("limits.max_acceleration", [](C& c) -> double& { return c.flight.gains.max_acceleration; },
                {0.1, 50.0}, "m/s^2", "horizontal feedback acceleration")
        .number("follower.max_speed", [](C& c) -> double& { return c.flight.follower.max_speed; }, {0.05, 30.0},
                "m/s", "of the trajectory")
        .number("follower.max_acceleration", [](C& c) -> double& { return c.flight.follower.max_acceleration; },
                {0.05, 30.0}, "m/s^2", "of the trajectory (its feed-forward)")
        .number("follower.max_jerk", [](C& c) -> double& { return c.flight.follower.max_jerk; }, {0.1, 500.0},
                "m/s^3", "of the trajectory")
        .number("follower.max_yaw_rate", [](C& c) -> double& { return c.flight.follower.max_yaw_rate; },
                {0.01, 10.0}, "rad/s", "heading change")
        .number("follower.corner_deviation", [](C& c) -> double& { return c.flight.follower.corner_deviation; },
                {0.01, 5.0}, "m", "rounded corners pass at most this far from the path's corners")
        .number("follower.corridor", [](C& c) -> double& { return c.flight.follower.corridor; }, {0.01, 5.0}, "m",
                "the trajectory keeps this close to the path (or to the trajectory it replaces)")
        .number("follower.max_braking", [](C& c) -> double& { return c.flight.follower.max_braking; }, {0.05, 30.0},
                "m/s^2", "the hardest braking when the controller must stop (a hold while moving)")
        .number("follower.thrust_share", [](C& c) -> double& { return c.flight.follower.thrust_share; }, {0.1, 1.0},
                "", "of the vehicle's top thrust a trajectory may ask for (the rest is the feedback's)")
        .number("follower.tilt_share", [](C& c) -> double& { return c.flight.follower.tilt_share; }, {0.1, 1.0}, "",
                "of limits.max_tilt a trajectory may ask for (the rest is the feedback's)")
        .number("takeoff_altitude", [](C& c) -> double& { return c.flight.takeoff_altitude; }, {0.2, 100.0}, "m",
                "above the take-off point")
        .number("takeoff_ceiling_margin", [](C& c) -> double& { return c.flight.takeoff_ceiling_margin; },
                {0.0, 100.0}, "m",
                "a take-off at takeoff_altitude stops this far under the geofence's ceiling when it would reach it")
        .number("land_speed", [](C& c) -> double& { return c.flight.land_speed; }, {0.05, 5.0}, "m/s",
                "descent in LAND")
        .number("timeouts.state", [](C& c) -> double& { return c.flight.state_timeout; }, {0.005, 10.0}, "s",
                "vehicle state older than this is stale (default: the state topic's contract's)")
        .number("land_detector.max_vertical_speed",
                [](C& c) -> double& { return c.flight.land_detector.max_vertical_speed; }, {0.01, 5.0}, "m/s",
                "on an estimate, a landing has touched down once it sinks slower than this ...")
        .number("land_detector.max_thrust", [](C& c) -> double& { return c.flight.land_detector.max_thrust; },
                {0.1, 1.0}, "", "... on less than this fraction of the weight ...")
        .number("land_detector.hold_time", [](C& c) -> double& { return c.flight.land_detector.hold_time; },
                {0.0, 10.0}, "s", "... for this long")
        .number("land_detector.ground_clearance",
                [](C& c) -> double& { return c.flight.land_detector.ground_clearance; }, {0.0, 10.0}, "m",
                "on an estimate, a controller started still with the rangefinder reading less than this (without a "
                "reading within range_wait: below this height above z = 0) takes the vehicle for standing")
        .number("land_detector.range_wait", [](C& c) -> double& { return c.flight.land_detector.range_wait; },
                {0.0, 10.0}, "s", "how long after the first state the first judgment waits for a rangefinder reading")
        .number("land_detector.rest_accel_tolerance",
                [](C& c) -> double& { return c.flight.land_detector.rest_accel_tolerance; }, {0.01, 5.0}, "m/s^2",
                "without any state, a landing has touched down once the accelerometer reads gravity within this ...")
        .number("land_detector.rest_rate", [](C& c) -> double& { return c.flight.land_detector.rest_rate; },
                {0.01, 5.0}, "rad/s", "... and the gyroscope less than this, on less than max_thrust, for hold_time")
        .number("timeouts.path", [](C& c) -> double& { return c.flight.path_timeout; }, {0.05, 600.0}, "s",
                "path not republished for this long is stale (default: the quad/planning/path contract's)")
        .number("goal_tolerance", [](C& c) -> double& { return c.flight.goal_tolerance; }, {0.01, 10.0}, "m",
                "when the goal gives none")
        .number("failsafe_thrust", [](C& c) -> double& { return c.flight.failsafe_thrust; }, {0.3, 1.0}, "",
                "fraction of the weight in a blind descent")
        .number("dead_reckoning_horizon", [](C& c) -> double& { return c.flight.dead_reckoning_horizon; },
                {0.0, 30.0}, "s", "how long the IMU may carry the last state on while it is stale (0: never)")
        .number("modes.path_stale_land_after", [](C& c) -> double& { return c.flight.modes.path_stale_land_after; },
                {0.0, 3600.0}, "s", "hover without a path, then land")
        .number("modes.state_stale_land_after",
                [](C& c) -> double& { return c.flight.modes.state_stale_land_after; }, {0.0, 30.0}, "s",
                "hold on dead reckoning without a vehicle state (for it to come back), then land")
        .number("modes.no_path_land_after", [](C& c) -> double& { return c.flight.modes.no_path_land_after; },
                {0.0, 3600.0}, "s", "hover while the planner says the goal cannot be reached, then land")
        .number("modes.geofence_return_after",
                [](C& c) -> double& { return c.flight.modes.geofence_return_after; }, {0.0, 3600.0}, "s",
                "hold after the vehicle left the geofence, then return to the take-off point and land")
        .number("modes.uncertain_land_after",
                [](C& c) -> double& { return c.flight.modes.uncertain_land_after; }, {0.0, 3600.0}, "s",
                "hold (or return) on a state estimate whose 1-sigma is past the estimator's bounds, then land")
        .include(common::geofenceTable(), [](C& c) -> common::Geofence& { return c.flight.geofence; })
        .number("battery.reserve", [](C& c) -> double& { return c.flight.battery.reserve; }, {0.0, 0.9}, "",
                "fraction of the capacity to land with: the vehicle returns when only the way back is left above it")
        .number("battery.critical", [](C& c) -> double& { return c.flight.battery.critical; }, {0.0, 0.9}, "",
                "at or below this fraction of the capacity left, land where the vehicle is")
        .number("battery.critical_cell_voltage",
                [](C& c) -> double& { return c.flight.battery.critical_cell_voltage; }, {0.0, 4.2}, "V",
                "a cell's share of the pack's voltage under load below which (for battery.critical_after) to land")
        .number("battery.critical_after", [](C& c) -> double& { return c.flight.battery.critical_after; },
                {0.0, 60.0}, "s", "how long the cells' voltage stays low before it counts")
        .number("battery.return_margin", [](C& c) -> double& { return c.flight.battery.return_margin; },
                {1.0, 10.0}, "", "the way back is taken to last this many times its estimate ...")
        .number("battery.return_overhead", [](C& c) -> double& { return c.flight.battery.return_overhead; },
                {0.0, 600.0}, "s", "... and this much longer (braking, turning, touching down)")
        .number("battery.current_window", [](C& c) -> double& { return c.flight.battery.current_window; },
                {0.1, 600.0}, "s", "the current drawn is averaged over about this long")
        .number("camera.look_ahead", [](C& c) -> double& { return c.flight.camera_look_ahead; }, {0.1, 100.0}, "m",
                "the camera gimbal looks at the path this far ahead")
        .number("modes.idle_disarm_after", [](C& c) -> double& { return c.flight.modes.idle_disarm_after; },
                {0.1, 1e6}, "s", "armed on the ground, then disarm")
        .number("operator.link_loss_after", [](C& c) -> double& { return c.flight.link_loss_after; }, {0.0, 3600.0},
                "s", "the operator's station, once heard, silent this long: the link is lost; 0: never")
        .choice("operator.link_loss_action", [](C& c) -> LinkLossAction& { return c.flight.modes.link_loss; },
                {{"return", LinkLossAction::kReturn}, {"land", LinkLossAction::kLand}, {"none", LinkLossAction::kNone}},
                "what a lost link does in flight: return to land at the take-off point, land where it is, or nothing")
        .flag("modes.auto_mission", [](C& c) -> bool& { return c.flight.modes.auto_mission; },
              "start the mission as soon as a path is available")
        .flag("autostart", [](C& c) -> bool& { return c.autostart; }, "arm and take off once the vehicle state is fresh")
        .number("status.rate", [](C& c) -> double& { return c.status_rate; }, {0.1, 1000.0}, "Hz",
                "control status publication");
    return t;
  }();
  return table;
}

common::ParamSchema controlSchema() { return controlTable().schema(); }

ControlNodeConfig controlConfigFrom(const common::Params& p)
{
  ControlNodeConfig c = controlTable().read(p, common::configDir());
  common::checkGeofence(c.flight.geofence, p.origin());
  const BatteryPolicy& battery = c.flight.battery;
  if (battery.critical > battery.reserve) {
    throw common::ConfigError({common::configProblem(p.origin(), "battery.critical", battery.critical,
                                                     "above battery.reserve (" + common::formatValue(battery.reserve) +
                                                         "): the vehicle would land before it returned")});
  }
  return c;
}

}  // namespace quad::control
