// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The plant: the vehicle in its world, stepped in sim time. Each step integrates the rotor
/// command the CommandGuard holds (as far as the battery's voltage lets the rotors follow it),
/// draws the rotors' power from the battery, applies due faults, detects contacts, and emits
/// the sensor samples that fall due. Everything random draws from one generator seeded by the config, so
/// the same seed and the same commands give bit-identical runs.

#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "quad/plant/battery.hpp"
#include "quad/plant/command_guard.hpp"
#include "quad/plant/dynamics.hpp"
#include "quad/plant/faults.hpp"
#include "quad/plant/gimbal.hpp"
#include "quad/plant/navigation_sensors.hpp"
#include "quad/plant/sensors.hpp"
#include "quad/plant/wind.hpp"
#include "quad/world/world.hpp"

namespace quad::plant {

using geometry::Vector3;

struct SimulationConfig {
  std::int64_t step_ns = 1'000'000;            ///< integration step (1 ms)
  std::uint64_t seed = 1;
  std::int64_t command_timeout_ns = 100'000'000;
  std::int64_t command_failsafe_ns = 20'000'000;  ///< a held command older than this is flown balanced
  double state_rate_hz = 250.0;
  DepthCameraConfig depth;
  GimbalConfig gimbal;  ///< enabled: the depth camera hangs on it (at depth.position_B), not on its fixed mount
  ImuConfig imu;
  PositionSensorConfig position;
  BarometerConfig baro;
  MagnetometerConfig mag;
  RangefinderConfig range;     ///< looks down: what the vehicle stands on, how high it flies
  RangefinderConfig range_up;  ///< looks up: how high the ceiling over it is
  WindConfig wind;  ///< steady wind and turbulence (gusts come as faults, on top)
  BatteryConfig battery;
  double battery_rate_hz = 10.0;  ///< battery readings (the pack's monitor)
  Vector3 gravity_W{0.0, 0.0, -9.81};
  /// An impact with a solid (an obstacle or a scan, not the bounds) stops the vehicle where it
  /// is: it has crashed and holds still. False: the collision is counted and it flies on.
  bool crash_on_impact = true;
};

struct SimEventRecord {
  enum class Kind { kCollision, kGroundContact, kTakeoff, kFaultApplied, kFaultCleared, kCrash };
  Kind kind;
  std::int64_t t_ns = 0;
  Vector3 p_W = Vector3::Zero();
  std::int64_t subject_id = -1;  ///< obstacle index (world::World::kBounds for the bounds) or fault id
  std::string detail;
  std::int64_t other_vehicle = -1;  ///< the vehicle touched, for a collision between two vehicles (Fleet)
};

struct StateSample {
  std::int64_t t_ns = 0;
  RigidBodyState state;
  Vector3 a_W = Vector3::Zero();
};

struct ImuReading {
  std::int64_t t_ns = 0;
  ImuSample sample;
};

/// A position fix, stamped when it was measured (it is delivered `latency` later).
struct PositionReading {
  std::int64_t t_ns = 0;
  PositionFix fix;
};

struct BaroReading {
  std::int64_t t_ns = 0;
  double altitude = 0.0;  ///< [m]
  double std_dev = 0.0;   ///< [m] the white noise's, as the sensor declares it
};

struct MagReading {
  std::int64_t t_ns = 0;
  Vector3 field_B;        ///< [µT]
  double std_dev = 0.0;   ///< [µT] per axis, as the sensor declares it
};

/// A rangefinder's reading (measureRange).
struct RangeReading {
  std::int64_t t_ns = 0;
  std::optional<double> range;  ///< [m] from the body's origin along its axis; none: nothing within max_range
  double max_range = 0.0;       ///< [m]
  double std_dev = 0.0;         ///< [m] the white noise's, as the sensor declares it
};

struct DepthReading {
  std::int64_t t_ns = 0;
  DepthScan scan;
  /// The sensor's pose on the body at capture: its mount, turned by the gimbal (what the
  /// gimbal's encoders report); where the body is, the state says.
  geometry::Pose3 sensor_B;
};

/// What the pack's monitor reads.
struct BatteryReading {
  std::int64_t t_ns = 0;
  double voltage = 0.0;   ///< [V] at the terminals
  double current = 0.0;   ///< [A] drawn
  double charge = 0.0;    ///< fraction of the capacity left
  double capacity = 0.0;  ///< [Ah]
  int cells = 0;          ///< in series, as built (a failed cell still counts)
};

struct StepOutputs {
  bool state_due = false;  ///< a state sample was due this step (whether or not a fault dropped it)
  std::optional<StateSample> state;
  std::optional<ImuReading> imu;
  std::optional<PositionReading> position;  ///< delivered now, measured at its stamp
  std::optional<BaroReading> baro;
  std::optional<MagReading> mag;
  std::optional<RangeReading> range;     ///< downward
  std::optional<RangeReading> range_up;  ///< upward
  std::optional<DepthReading> depth;
  std::optional<BatteryReading> battery;
  std::vector<SimEventRecord> events;
};

class Simulation {
public:
  /// Starts at the world's start, level, at rest (landed when the start is on the ground).
  Simulation(vehicle::VehicleParams vehicle, world::World world, SimulationConfig config,
             std::vector<Fault> schedule = {});

  std::int64_t timeNs() const { return t_ns_; }
  const RigidBodyState& state() const { return state_; }
  const world::World& world() const { return world_; }
  const QuadrotorDynamics& dynamics() const { return dynamics_; }
  const SimulationConfig& config() const { return config_; }
  CommandGuard& commands() { return guard_; }
  const CommandGuard& commands() const { return guard_; }
  /// The battery, unless the config asks for an ideal supply.
  const std::optional<Battery>& battery() const { return battery_; }

  /// Schedules a fault (it takes effect at the next step at or after its start). Returns
  /// false when its id is already scheduled or active.
  bool injectFault(Fault fault);
  /// Ends an active or pending fault now; false when the id is unknown.
  bool clearFault(std::uint32_t id);

  /// Aims the camera gimbal (world yaw [rad], elevation [rad]); false when the plant has no
  /// gimbal or the angles are not finite.
  bool aimGimbal(double yaw_W, double pitch);
  /// The gimbal, when the camera hangs on one.
  const std::optional<Gimbal>& gimbal() const { return gimbal_; }
  /// Where the depth camera is now, in the world.
  geometry::Pose3 cameraPose() const;

  /// The IMU's biases now (for tests and scoring).
  const ImuBias& imuBias() const { return imu_bias_; }
  /// The barometer's offset now (for tests and scoring).
  double baroOffset() const { return baro_.offset(); }

  /// Places the vehicle (scenarios and tests: start in the air, moving).
  void setState(const RigidBodyState& state);

  /// The other vehicles in the world, each its bounding sphere, as the next step's depth
  /// camera sees them (a Fleet sets them before every step; contacts between vehicles are the
  /// Fleet's to detect).
  void setOthers(std::span<const world::Sphere> others) { others_.assign(others.begin(), others.end()); }

  /// Advances one step.
  StepOutputs step();
  /// [m/s] the air's velocity at the vehicle, in the world (steady, turbulence, gusts).
  Vector3 windAtVehicle() const { return environment().wind_W; }

  std::uint64_t collisionCount() const { return collisions_; }

  /// An impact that stopped the vehicle (SimulationConfig::crash_on_impact).
  struct Crash {
    std::int64_t t_ns = 0;
    double speed = 0.0;  ///< [m/s] at impact
    int solid = -1;      ///< what it hit (world::World::describe)
  };
  const std::optional<Crash>& crash() const { return crash_; }

private:
  struct Active {
    Fault fault;
    bool applied = false;
  };
  /// A rangefinder's state: it reads at turn-on (the first step), then on its grid.
  struct Rangefinder {
    RangefinderConfig SimulationConfig::*config;  ///< which of config_'s
    Sensor sensor;                                ///< what its faults name
    Vector3 axis_B;                               ///< kDownward or kUpward
    std::mt19937_64 rng;                          ///< its own: it left every other draw as it was
    std::int64_t next_ns = 0;                     ///< 0: it reads at the first step
    std::optional<RangeReading> last;
  };
  /// The rangefinder's sample if one is due this step.
  std::optional<RangeReading> measureRangefinder(Rangefinder& r);
  void applyFaults(StepOutputs& out);
  /// The navigation aids' samples due this step.
  void measureNavigation(StepOutputs& out);
  Environment environment() const;
  bool sensorFault(Sensor s, Fault::Kind k) const;
  /// `zero` plus `field` of every applied fault of kind `k` on sensor `s`.
  template <typename T>
  T sumOfFaults(Sensor s, Fault::Kind k, T Fault::*field, T zero) const;
  /// The extra noise active sensor_noise faults add to a sensor's readings.
  double sensorNoise(Sensor s) const;
  /// The offsets active sensor_offset faults add to a sensor's readings.
  Vector3 sensorOffset(Sensor s) const;
  static bool due(std::int64_t t_ns, std::int64_t& next_ns, double rate_hz);

  QuadrotorDynamics dynamics_;
  world::World world_;
  SimulationConfig config_;
  DepthCamera camera_;
  std::optional<Gimbal> gimbal_;
  ImuIntegrals imu_integrals_;  ///< what the IMU felt since its last sample
  CommandGuard guard_;
  std::mt19937_64 rng_;
  Wind wind_;  // its own generator: turbulence on or off leaves the sensors' draws as they were
  // The IMU's bias walks and the navigation aids draw from their own too: they left the depth
  // camera's and the IMU noise's draws as they were when they came.
  std::mt19937_64 nav_rng_;
  ImuBias imu_bias_;
  PositionSensor position_;
  Barometer baro_;
  std::optional<Battery> battery_;
  RigidBodyState state_;
  std::int64_t t_ns_ = 0;
  std::vector<Active> faults_;
  std::vector<int> contacts_;
  std::vector<world::Sphere> others_;
  std::uint64_t collisions_ = 0;
  std::optional<Crash> crash_;
  double surface_z_ = 0.0;  // [m] what the vehicle stands on or would land on, where it is now
  std::int64_t next_state_ns_ = 0;
  std::int64_t next_imu_ns_ = 0;
  std::int64_t next_depth_ns_ = 0;
  std::int64_t next_battery_ns_ = 0;
  std::int64_t next_position_ns_ = 0;
  std::int64_t next_baro_ns_ = 0;
  std::int64_t next_mag_ns_ = 0;
  std::deque<PositionReading> positions_in_flight_;  // measured, not yet delivered
  std::optional<PositionReading> last_position_;
  std::optional<BaroReading> last_baro_;
  std::optional<MagReading> last_mag_;
  Rangefinder range_down_;
  Rangefinder range_up_;
  std::optional<StateSample> last_state_;
  std::optional<ImuReading> last_imu_;
  std::optional<DepthReading> last_depth_;
};

}  // namespace quad::plant
