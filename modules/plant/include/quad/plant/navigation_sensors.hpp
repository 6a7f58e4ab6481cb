// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The navigation aids an estimator fuses with the IMU: an absolute position sensor (a GNSS
/// receiver or a motion-capture system: white noise, a latency, outages), a barometric
/// altimeter (an offset that starts at the pressure of the day and drifts, and noise) and a
/// magnetometer (Earth's field in the body frame, and noise). And rangefinders: a downward one,
/// by which the controller knows the vehicle stands on something, and an upward one, by which
/// it knows how high a room's ceiling is. Randomness comes from a
/// generator the caller owns, so a run is reproducible for a seed.

#include <optional>
#include <random>

#include "quad/geometry/cspace.hpp"
#include "quad/world/world.hpp"

namespace quad::plant {

using geometry::Vector3;

struct PositionSensorConfig {
  bool enabled = true;
  double rate_hz = 10.0;             ///< [Hz]
  double noise_std = 0.02;           ///< [m] white, per axis
  double latency = 0.05;             ///< [s] from the measurement to its delivery
  double outages_per_minute = 0.0;   ///< random outages (a Poisson process); 0: none
  double outage_duration = 2.0;      ///< [s] mean length of one (exponential)
};

/// One position sample, the body origin in the world.
struct PositionFix {
  Vector3 p_W;         ///< [m]
  double std_dev = 0;  ///< [m] 1σ per axis, as the sensor declares it
};

/// Position samples with outages: within one, samples fall due and none is measured.
class PositionSensor {
public:
  explicit PositionSensor(PositionSensorConfig config) : config_(config) {}
  const PositionSensorConfig& config() const { return config_; }

  /// The sample due now, `period_s` after the previous one; nothing while in an outage.
  std::optional<PositionFix> measure(const Vector3& p_W, std::mt19937_64& rng, double extra_noise_std = 0.0);
  bool inOutage() const { return outage_left_s_ > 0.0; }

private:
  PositionSensorConfig config_;
  double outage_left_s_ = 0.0;
};

struct BarometerConfig {
  bool enabled = true;
  double rate_hz = 25.0;     ///< [Hz]
  double noise_std = 0.1;    ///< [m] white
  double offset_std = 0.5;   ///< [m] the offset at turn-on (the pressure of the day)
  double drift_walk = 0.005; ///< [m/√s] the offset's random walk (the weather)
};

/// Pressure altitude: the height above the world's z = 0, plus an offset that drifts.
class Barometer {
public:
  /// Draws the turn-on offset.
  Barometer(BarometerConfig config, std::mt19937_64& rng);
  const BarometerConfig& config() const { return config_; }
  /// [m] The altitude read at height `z_W`, `dt_s` after the previous reading.
  double measure(double z_W, double dt_s, std::mt19937_64& rng, double extra_noise_std = 0.0);
  /// [m] The offset now (for tests and scoring).
  double offset() const { return offset_; }

private:
  BarometerConfig config_;
  double offset_ = 0.0;
};

struct MagnetometerConfig {
  bool enabled = true;
  double rate_hz = 50.0;                  ///< [Hz]
  Vector3 field_W{0.0, 21.0, -43.0};      ///< [µT] Earth's field in the world (ENU: north is +y; mid-latitudes point down)
  double noise_std = 0.3;                 ///< [µT] white, per axis
};

/// [µT] The field the magnetometer reads on a body at `q_WB`, with `disturbance_W` (a
/// nearby magnet, a power line) added to Earth's.
Vector3 measureMagnetometer(const MagnetometerConfig& config, const geometry::Quaternion& q_WB,
                            const Vector3& disturbance_W, std::mt19937_64& rng, double extra_noise_std = 0.0);

struct RangefinderConfig {
  bool enabled = true;
  double rate_hz = 20.0;    ///< [Hz] (it also reads once at turn-on, at the first step)
  double max_range = 10.0;  ///< [m] beyond it: nothing in range
  double noise_std = 0.01;  ///< [m] white
};

/// [m] A rangefinder at the body's origin looking along the body's unit axis `axis_B`
/// (kDownward, kUpward): how far along it the first surface lies (the ground, a ceiling, an
/// obstacle, a scan), with white noise, never below 0; none when nothing is within
/// `max_range`. A vehicle standing on a surface reads about 0 downward. Both look from
/// kRangefinderLift over the origin (the body's top), so the downward one sees a surface the
/// origin touches and the upward one does not see the surface the body stands on.
std::optional<double> measureRange(const RangefinderConfig& config, const world::World& world, const Vector3& p_W,
                                   const geometry::Quaternion& q_WB, const Vector3& axis_B, std::mt19937_64& rng,
                                   double extra_noise_std = 0.0);
inline const Vector3 kDownward{0.0, 0.0, -1.0};  ///< the body's -z axis
inline const Vector3 kUpward{0.0, 0.0, 1.0};     ///< the body's +z axis
inline constexpr double kRangefinderLift = 0.05;  ///< [m]

}  // namespace quad::plant
