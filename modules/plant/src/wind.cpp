// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/wind.hpp"

#include <algorithm>
#include <cmath>

namespace quad::plant {

namespace {
constexpr double kFoot = 0.3048;  // [m]
constexpr double kPi = 3.14159265358979323846;
}  // namespace

DrydenScales lowAltitudeScales(double altitude, double w20)
{
  // MIL-F-8785C, low altitude (below 1000 ft), in feet: L_w = h, L_u = L_v = h / (0.177 +
  // 0.000823 h)^1.2, σ_w = 0.1 W20, σ_u = σ_v = σ_w / (0.177 + 0.000823 h)^0.4.
  const double h = std::clamp(altitude / kFoot, 10.0, 1000.0);
  const double k = 0.177 + 0.000823 * h;
  DrydenScales s;
  const double sigma_w = 0.1 * w20;
  const double sigma_uv = sigma_w / std::pow(k, 0.4);
  s.sigma = Vector3(sigma_uv, sigma_uv, sigma_w);
  const double length_uv = h / std::pow(k, 1.2) * kFoot;
  s.length = Vector3(length_uv, length_uv, h * kFoot);
  return s;
}

DrydenTurbulence::DrydenTurbulence(std::uint64_t seed) : rng_(seed) {}

Vector3 DrydenTurbulence::step(const DrydenScales& scales, double airspeed, double dt)
{
  const double V = std::max(airspeed, kMinAirspeed);
  // Along: H_u(s) = σ_u √(2L_u/(πV)) / (1 + (L_u/V) s), stepped exactly as the AR(1)
  // process with the same variance σ_u² and correlation exp(−V τ / L_u).
  const double a = std::exp(-V * dt / scales.length.x());
  u_ = a * u_ + std::sqrt(1.0 - a * a) * normal_(rng_);
  // Across and vertical: H(s) = σ √(L/(πV)) (1 + √3 (L/V) s) / (1 + (L/V) s)², driven by
  // white noise of intensity π (the spec's convention: variance σ², correlation
  // (1 − Vτ/(2L)) exp(−Vτ/L)). With z'' T² + 2T z' + z = n, T = L/V, the output is
  // K (z + √3 T z'), K = σ √(L/(πV)).
  const auto second = [&](double* x, double sigma, double length) {
    const double T = length / V;
    const double n = std::sqrt(kPi / dt) * normal_(rng_);
    const double z = x[0];
    const double zd = x[1];
    x[0] = z + zd * dt;
    x[1] = zd + (n - z - 2.0 * T * zd) / (T * T) * dt;
    return sigma * std::sqrt(length / (kPi * V)) * (x[0] + std::sqrt(3.0) * T * x[1]);
  };
  const double v = second(v_, scales.sigma.y(), scales.length.y());
  const double w = second(w_, scales.sigma.z(), scales.length.z());
  return {scales.sigma.x() * u_, v, w};
}

Wind::Wind(WindConfig config, std::uint64_t seed)
    : config_(std::move(config)),
      along_(config_.steady_W.head<2>().norm() > 1e-9
                 ? Vector3(config_.steady_W.x(), config_.steady_W.y(), 0.0).normalized()
                 : Vector3::UnitX()),
      across_(-along_.y(), along_.x(), 0.0),
      turbulence_(seed),
      current_(config_.steady_W)
{
}

Vector3 Wind::step(const Vector3& p_W, const Vector3& v_W, double dt)
{
  current_ = config_.steady_W;
  if (config_.turbulence_w20 <= 0.0) {
    return current_;
  }
  const DrydenScales scales = lowAltitudeScales(p_W.z(), config_.turbulence_w20);
  const Vector3 gust = turbulence_.step(scales, (v_W - config_.steady_W).norm(), dt);
  current_ += gust.x() * along_ + gust.y() * across_ + gust.z() * Vector3::UnitZ();
  return current_;
}

}  // namespace quad::plant
