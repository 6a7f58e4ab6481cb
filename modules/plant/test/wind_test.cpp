// SPDX-License-Identifier: BSD-3-Clause
// Wind against closed forms: MIL-F-8785C's low-altitude scales at the ends of their band,
// and the Dryden filters' variance and correlation (exp(−Vτ/L) along, (1 − Vτ/2L) exp(−Vτ/L)
// across and vertical), measured on a long run with a fixed seed.
#include "quad/plant/wind.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace quad::plant {
namespace {

TEST(Wind, LowAltitudeScalesFollowTheSpecAndMeetAt1000Feet)
{
  // At 10 ft (and below: clamped): σ_w = 0.1 W20, σ_u = σ_w / 0.18523^0.4, L_w = 10 ft,
  // L_u = 10 ft / 0.18523^1.2 = 75.6 ft.
  for (const double h : {3.048, 1.0}) {
    const DrydenScales s = lowAltitudeScales(h, 7.7);
    EXPECT_NEAR(s.sigma.z(), 0.77, 1e-12);
    EXPECT_NEAR(s.sigma.x(), 0.77 * 1.9632, 0.001);
    EXPECT_EQ(s.sigma.x(), s.sigma.y());
    EXPECT_NEAR(s.length.z(), 3.048, 1e-9);
    EXPECT_NEAR(s.length.x(), 75.64 * 0.3048, 0.01);
  }
  // At 1000 ft the low-altitude form is isotropic: σ_u = σ_w, L_u = L_w = h.
  const DrydenScales top = lowAltitudeScales(304.8, 7.7);
  EXPECT_NEAR(top.sigma.x(), top.sigma.z(), 1e-12);
  EXPECT_NEAR(top.length.x(), 304.8, 1e-9);
  EXPECT_NEAR(top.length.z(), 304.8, 1e-9);
  EXPECT_EQ(lowAltitudeScales(2.0, 0.0).sigma, Vector3::Zero());
}

/// Correlation of a series with itself `lag` samples later, over its variance.
double correlation(const std::vector<double>& x, std::size_t lag)
{
  double sum = 0.0;
  for (std::size_t i = 0; i + lag < x.size(); ++i) {
    sum += x[i] * x[i + lag];
  }
  return sum / static_cast<double>(x.size() - lag);
}

TEST(Wind, DrydenFiltersHaveTheirVarianceAndCorrelation)
{
  DrydenScales s;
  s.sigma = Vector3(1.5, 1.5, 0.8);
  s.length = Vector3(5.0, 5.0, 5.0);
  const double V = 5.0;  // T = L/V = 1 s
  const double dt = 1e-3;
  DrydenTurbulence t(42);
  for (int k = 0; k < 50'000; ++k) {
    t.step(s, V, dt);  // from rest to stationary
  }
  std::vector<double> u;
  std::vector<double> v;
  std::vector<double> w;
  constexpr int kEvery = 10;  // a sample each 10 ms
  for (int k = 0; k < 10'000'000; ++k) {
    const Vector3 g = t.step(s, V, dt);
    if (k % kEvery == 0) {
      u.push_back(g.x() / s.sigma.x());
      v.push_back(g.y() / s.sigma.y());
      w.push_back(g.z() / s.sigma.z());
    }
  }
  const std::size_t one = 100;  // τ = 1 s = L/V
  const std::size_t two = 200;  // τ = 2 s: the lateral correlation crosses zero
  for (const auto* x : {&u, &v, &w}) {
    EXPECT_NEAR(correlation(*x, 0), 1.0, 0.06);  // variance σ²
  }
  EXPECT_NEAR(correlation(u, one), std::exp(-1.0), 0.05);
  EXPECT_NEAR(correlation(u, two), std::exp(-2.0), 0.05);
  for (const auto* x : {&v, &w}) {
    EXPECT_NEAR(correlation(*x, one), 0.5 * std::exp(-1.0), 0.05);
    EXPECT_NEAR(correlation(*x, two), 0.0, 0.05);
  }
}

TEST(Wind, SteadyWindIsExactAndTurbulenceRidesOnItAlongTheWind)
{
  Wind calm({Vector3(3, 4, 0), 0.0}, 1);
  EXPECT_EQ(calm.step(Vector3(0, 0, 2), Vector3::Zero(), 1e-3), Vector3(3, 4, 0));
  Wind gusty({Vector3(3, 4, 0), 7.7}, 1);
  const Vector3 along(0.6, 0.8, 0.0);
  const Vector3 across(-0.8, 0.6, 0.0);
  double sum_along = 0.0;
  double sq_along = 0.0;
  double sq_across = 0.0;
  const int n = 2'000'000;
  for (int k = 0; k < n; ++k) {
    const Vector3 gust = gusty.step(Vector3(0, 0, 3.048), Vector3::Zero(), 1e-3) - Vector3(3, 4, 0);
    sum_along += gust.dot(along);
    sq_along += gust.dot(along) * gust.dot(along);
    sq_across += gust.dot(across) * gust.dot(across);
  }
  const DrydenScales s = lowAltitudeScales(3.048, 7.7);
  EXPECT_NEAR(sum_along / n, 0.0, 0.3);  // zero mean (T_u = 4.6 s: 430 correlation times)
  EXPECT_NEAR(std::sqrt(sq_along / n), s.sigma.x(), 0.15 * s.sigma.x());
  EXPECT_NEAR(std::sqrt(sq_across / n), s.sigma.y(), 0.15 * s.sigma.y());
}

}  // namespace
}  // namespace quad::plant
