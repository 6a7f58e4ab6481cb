// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/haar.hpp"

#include <algorithm>
#include <cmath>

namespace quad::geometry {

Quaternion uniformRotation(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double u1 = uniform(rng);
  const double u2 = uniform(rng);
  const double u3 = uniform(rng);
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  const Quaternion q{b * std::cos(2.0 * kPi * u3), a * std::sin(2.0 * kPi * u2),
                     a * std::cos(2.0 * kPi * u2), b * std::sin(2.0 * kPi * u3)};
  return q.canonical();
}

std::vector<Quaternion> uniformRotations(std::size_t count, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::vector<Quaternion> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    out.push_back(uniformRotation(rng));
  }
  return out;
}

double haarAngleDensity(double theta) { return (1.0 - std::cos(theta)) / kPi; }

double haarAngleCdf(double theta) { return (theta - std::sin(theta)) / kPi; }

double kolmogorovSmirnov(std::vector<double> samples, const std::function<double(double)>& cdf)
{
  std::sort(samples.begin(), samples.end());
  const double n = static_cast<double>(samples.size());
  double d = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double f = cdf(samples[i]);
    const double i_d = static_cast<double>(i);
    d = std::max({d, (i_d + 1.0) / n - f, f - i_d / n});
  }
  return d;
}

}  // namespace quad::geometry
