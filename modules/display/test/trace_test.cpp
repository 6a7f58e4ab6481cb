// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quad/geometry/distance.hpp"

namespace quad::display {
namespace {

double length(const std::vector<TracePose>& poses)
{
  double l = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    l += (poses[i].p_W - poses[i - 1].p_W).norm();
  }
  return l;
}

/// A random walk of `n` samples, 1 cm to 3 cm apart, turning slowly; seeded.
std::vector<TracePose> walk(std::size_t n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.01, 0.03);
  std::normal_distribution<double> heading_change(0.0, 0.05);
  std::vector<TracePose> out;
  Vector3 p = Vector3::Zero();
  double heading = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    heading += heading_change(rng);
    p += step(rng) * Vector3(std::cos(heading), std::sin(heading), 0.1);
    out.push_back({static_cast<std::int64_t>(i + 1) * 4'000'000, p, geometry::fromAxisAngle(Vector3::UnitZ(), heading)});
  }
  return out;
}

TEST(Trace, KeptPosesAreSpacedOrTurnedAndShortenThePathOnly)
{
  Trace trace({.spacing = 0.1, .turn = 0.3, .max_poses = 100000});
  const auto samples = walk(5000, 7);
  for (const auto& s : samples) {
    trace.add(s);
  }
  const auto& kept = trace.poses();
  ASSERT_GE(kept.size(), 2U);
  EXPECT_EQ(kept.front().t_ns, samples.front().t_ns);
  for (std::size_t i = 1; i < kept.size(); ++i) {
    const bool moved = (kept[i].p_W - kept[i - 1].p_W).norm() >= 0.1;
    const bool turned = geometry::geodesicAngle(kept[i].q_WB, kept[i - 1].q_WB) >= 0.3;
    EXPECT_TRUE(moved || turned) << i;
  }
  // A polyline through some of the samples is no longer than through all of them, and
  // misses at most one spacing at the end.
  EXPECT_LE(length(kept), length(samples) + 1e-9);
  EXPECT_LE((kept.back().p_W - samples.back().p_W).norm(), 0.1);
}

TEST(Trace, ALongFlightStaysWithinItsBoundWithTheFirstAndNewestPose)
{
  Trace trace({.spacing = 0.02, .turn = 3.0, .max_poses = 500});
  const auto samples = walk(50000, 11);
  for (const auto& s : samples) {
    trace.add(s);
    ASSERT_LE(trace.poses().size(), 500U);
  }
  EXPECT_EQ(trace.poses().front().t_ns, samples.front().t_ns);
  EXPECT_GT(trace.spacing(), 0.02);  // thinned
  EXPECT_LE((trace.poses().back().p_W - samples.back().p_W).norm(), trace.spacing());
  // Thinned evenly: no gap wider than a few of the spacings now kept.
  for (std::size_t i = 1; i < trace.poses().size(); ++i) {
    EXPECT_LE((trace.poses()[i].p_W - trace.poses()[i - 1].p_W).norm(), 2.0 * trace.spacing() + 0.06) << i;
  }
}

TEST(Trace, SamplesNotNewerThanTheLastAreRefused)
{
  Trace trace({});
  EXPECT_TRUE(trace.add({10, Vector3::Zero(), {}}));
  EXPECT_FALSE(trace.add({10, Vector3(5, 0, 0), {}}));
  EXPECT_FALSE(trace.add({5, Vector3(5, 0, 0), {}}));
  EXPECT_TRUE(trace.add({11, Vector3(5, 0, 0), {}}));
  EXPECT_EQ(trace.poses().size(), 2U);
}

TEST(Trace, NonPositiveParametersAreRefused)
{
  EXPECT_THROW(Trace({.spacing = 0.0}), std::invalid_argument);
  EXPECT_THROW(Trace({.spacing = 0.1, .turn = -1.0}), std::invalid_argument);
  EXPECT_THROW(Trace({.spacing = 0.1, .turn = 0.1, .max_poses = 1}), std::invalid_argument);
}

}  // namespace
}  // namespace quad::display
