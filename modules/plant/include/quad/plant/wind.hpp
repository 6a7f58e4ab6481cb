// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The air the vehicle flies in: a steady wind plus Dryden turbulence, MIL-F-8785C's
/// low-altitude form. The turbulence is three independent gust velocities, shaped from
/// white noise by the spec's filters: along the mean wind (u, first order), across it (v)
/// and vertical (w, second order each), with intensities and scale lengths set by the wind
/// at 20 ft (W20) and the vehicle's altitude. As the spec does, the filters see the
/// turbulence as a frozen field the vehicle moves through at its airspeed; a hovering
/// multirotor in calm air has none, so the airspeed is floored at kMinAirspeed.

#include <cstdint>
#include <random>

#include "quad/geometry/quaternion.hpp"

namespace quad::plant {

using geometry::Vector3;

struct WindConfig {
  Vector3 steady_W = Vector3::Zero();  ///< [m/s] the mean wind, world frame
  double turbulence_w20 = 0.0;         ///< [m/s] wind speed at 20 ft that sets the turbulence; 0: none
};

/// MIL-F-8785C low-altitude intensities [m/s] and scale lengths [m] along, across and
/// vertical, at `altitude` [m] (clamped to the spec's 10–1000 ft) for wind `w20` [m/s] at 20 ft.
struct DrydenScales {
  Vector3 sigma = Vector3::Zero();   ///< σ_u, σ_v, σ_w
  Vector3 length = Vector3::Ones();  ///< L_u, L_v, L_w
};
DrydenScales lowAltitudeScales(double altitude, double w20);

inline constexpr double kMinAirspeed = 1.0;  ///< [m/s] the filters' airspeed floor

/// The three shaping filters, stepped in time.
class DrydenTurbulence {
public:
  explicit DrydenTurbulence(std::uint64_t seed);
  /// Advances `dt` [s] at `airspeed` [m/s] (at least kMinAirspeed is used); returns the gust
  /// velocities u, v, w [m/s]. `dt` must be well below the scale lengths over the airspeed
  /// (the second-order filters are stepped by Euler–Maruyama).
  Vector3 step(const DrydenScales& scales, double airspeed, double dt);

private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  double u_ = 0.0;           // the first-order filter's output (unit intensity)
  double v_[2] = {0.0, 0.0};  // the second-order filters' states: z, ż
  double w_[2] = {0.0, 0.0};
};

/// Steady wind plus turbulence, in the world frame: u along the steady wind's horizontal
/// direction (world x when it has none), v across it horizontally, w up.
class Wind {
public:
  Wind(WindConfig config, std::uint64_t seed);
  /// Advances `dt` with the vehicle at `p_W` moving at `v_W`; returns the air velocity there.
  Vector3 step(const Vector3& p_W, const Vector3& v_W, double dt);
  const Vector3& current() const { return current_; }
  const WindConfig& config() const { return config_; }

private:
  WindConfig config_;
  Vector3 along_;   // the gusts' axes: the steady wind's horizontal direction,
  Vector3 across_;  // and z × it
  DrydenTurbulence turbulence_;
  Vector3 current_;
};

}  // namespace quad::plant
