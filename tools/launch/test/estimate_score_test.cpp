// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/estimate_score.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace quad::launch {
namespace {

using geometry::Quaternion;
using geometry::Vector3;

Quaternion yawed(double deg)
{
  const double half = deg * std::numbers::pi / 360.0;
  return {std::cos(half), 0.0, 0.0, std::sin(half)};
}

TEST(EstimateScore, AConstantErrorIsItsOwnRmsAndMaxAndTheNeesFollowsTheSigma)
{
  EstimateScore s;
  EXPECT_FALSE(s.errors()) << "nothing paired yet";
  for (std::int64_t k = 0; k < 500; ++k) {
    const std::int64_t t = k * 4'000'000;
    const Vector3 p(0.1 * static_cast<double>(k), 1.0, 2.0);
    // Either side may come first.
    if (k % 2 == 0) {
      s.onTruth(t, p, yawed(30.0), Vector3(25.0, 0.0, 0.0));
      s.onEstimate(t, p + Vector3(0.03, 0.0, 0.04), yawed(32.0), Vector3(0.015, 0.01, 0.02), true);
    } else {
      s.onEstimate(t, p + Vector3(0.03, 0.0, 0.04), yawed(32.0), Vector3(0.015, 0.01, 0.02), true);
      s.onTruth(t, p, yawed(30.0), Vector3(25.0, 0.0, 0.0));
    }
  }
  const auto e = s.errors();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->samples, 500U);
  EXPECT_NEAR(e->position_rms_m, 0.05, 1e-9);
  EXPECT_NEAR(e->position_max_m, 0.05, 1e-9);
  EXPECT_NEAR(e->attitude_rms_deg, 2.0, 1e-6);
  EXPECT_NEAR(e->attitude_max_deg, 2.0, 1e-6);
  EXPECT_NEAR(e->yaw_rms_deg, 2.0, 1e-6);
  EXPECT_NEAR(e->position_nees_mean, 4.0 + 0.0 + 4.0, 1e-6);  // 2σ on x and z
  EXPECT_NEAR(e->within_3sigma, 1.0, 1e-12);
  // 2 s of pairs every 4 ms: one point each 0.1 s, the first pair of each.
  ASSERT_EQ(s.series().size(), 20U);
  EXPECT_DOUBLE_EQ(s.series()[0].t_s, 0.0);
  EXPECT_NEAR(s.series()[1].t_s, 0.1, 1e-9);
  EXPECT_NEAR(s.series()[19].t_s, 1.9, 1e-9);
  EXPECT_NEAR(s.series()[5].position_m, 0.05, 1e-9);
  EXPECT_NEAR(s.series()[5].position_3sigma_m, 3.0 * std::sqrt(0.015 * 0.015 + 0.01 * 0.01 + 0.02 * 0.02), 1e-9);
  EXPECT_NEAR(s.series()[5].yaw_deg, 2.0, 1e-6);
  const std::string csv = toCsv(s.series());
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t_s,position_m,position_3sigma_m,attitude_deg,yaw_deg");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 21);
}

TEST(EstimateScore, EachSpeedBandHoldsThePairsFlownThatFastAndTheirOwnFigures)
{
  // GIVEN 100 pairs hovering 1 cm off at 1σ = 1 cm, 100 at 3 m/s 2 cm off, and 200 at 8 m/s
  // 6 cm off at 1σ = 2 cm (overconfident at speed)
  EstimateScore s;
  std::int64_t t = 0;
  const auto feed = [&](int n, double speed, double error, double sigma) {
    for (int k = 0; k < n; ++k, t += 4'000'000) {
      const Vector3 p(speed * 0.004 * static_cast<double>(k), 0.0, 2.0);
      s.onTruth(t, p, Quaternion::identity(), Vector3(0.0, speed, 0.0));
      s.onEstimate(t, p + Vector3(error, 0.0, 0.0), Quaternion::identity(), Vector3::Constant(sigma), true);
    }
  };
  feed(100, 0.0, 0.01, 0.01);
  feed(100, 3.0, 0.02, 0.01);
  feed(200, 8.0, 0.06, 0.02);
  const auto e = s.errors();
  ASSERT_TRUE(e);
  // THEN each band says its own error and NEES, and the whole run's mixes them
  ASSERT_EQ(e->by_speed.size(), 3U);
  EXPECT_EQ(e->by_speed[0].from_mps, 0.0);
  EXPECT_EQ(e->by_speed[0].to_mps, 2.0);
  EXPECT_EQ(e->by_speed[0].samples, 100U);
  EXPECT_NEAR(e->by_speed[0].position_rms_m, 0.01, 1e-12);
  EXPECT_NEAR(e->by_speed[0].position_nees_mean, 1.0, 1e-9);
  EXPECT_EQ(e->by_speed[1].samples, 100U);
  EXPECT_NEAR(e->by_speed[1].position_nees_mean, 4.0, 1e-9);
  EXPECT_EQ(e->by_speed[2].from_mps, 5.0);
  EXPECT_TRUE(std::isinf(e->by_speed[2].to_mps));
  EXPECT_EQ(e->by_speed[2].samples, 200U);
  EXPECT_NEAR(e->by_speed[2].position_rms_m, 0.06, 1e-12);
  EXPECT_NEAR(e->by_speed[2].position_nees_mean, 9.0, 1e-9);
  EXPECT_NEAR(e->position_nees_mean, (100 * 1.0 + 100 * 4.0 + 200 * 9.0) / 400.0, 1e-9);
  // AND a run that never flew fast has no band above its speed
  EstimateScore slow;
  slow.onTruth(0, Vector3::Zero(), Quaternion::identity(), Vector3(0.5, 0.0, 0.0));
  slow.onEstimate(0, Vector3::Zero(), Quaternion::identity(), Vector3::Constant(0.1), true);
  ASSERT_TRUE(slow.errors());
  ASSERT_EQ(slow.errors()->by_speed.size(), 1U);
  EXPECT_EQ(slow.errors()->by_speed[0].to_mps, 2.0);
}

TEST(EstimateScore, OnlyAlignedEstimatesWithATruthOfTheirStampCount)
{
  EstimateScore s;
  s.onTruth(0, Vector3::Zero(), Quaternion::identity(), Vector3::Zero());
  s.onEstimate(0, Vector3(5, 0, 0), Quaternion::identity(), Vector3::Constant(0.1), false);  // still aligning
  s.onEstimate(4'000'000, Vector3(5, 0, 0), Quaternion::identity(), Vector3::Constant(0.1), true);  // no truth
  EXPECT_FALSE(s.errors());
  s.onTruth(8'000'000, Vector3::Zero(), Quaternion::identity(), Vector3::Zero());
  s.onEstimate(8'000'000, Vector3(0, 0.5, 0), Quaternion::identity(), Vector3::Constant(0.1), true);
  const auto e = s.errors();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->samples, 1U);
  EXPECT_NEAR(e->position_max_m, 0.5, 1e-12);
  EXPECT_NEAR(e->position_nees_mean, 25.0, 1e-9);
  EXPECT_EQ(e->within_3sigma, 0.0) << "5σ off on y";
}

TEST(EstimateScore, ARunEndedLateScoresWhatAnEndHeardAtOnceScoresAndNothingAfterTheEnd)
{
  // The same seeded pairs, with errors growing over time, fed in two takes' orders: one
  // hears the end before any pair after it, the other only after 3 s of pairs past it, each
  // side in shuffled batches. Both score exactly the pairs up to the end.
  constexpr std::int64_t kStep = 4'000'000;
  constexpr std::int64_t kEnd = 1'000 * kStep;
  const auto feed = [&](EstimateScore& s, std::int64_t k) {
    const std::int64_t t = k * kStep;
    const Vector3 p(0.01 * static_cast<double>(k), 0.0, 2.0);
    s.onTruth(t, p, yawed(10.0), Vector3(2.5, 0.0, 0.0));
    s.onEstimate(t, p + Vector3(1e-5 * static_cast<double>(k), 0.0, 0.0), yawed(10.0 + 0.001 * static_cast<double>(k)),
                 Vector3::Constant(0.02), true);
  };
  EstimateScore at_once;
  EstimateScore late;
  for (std::int64_t k = 0; k <= 1'000; ++k) {
    feed(at_once, k);
  }
  at_once.endAt(kEnd);
  for (std::int64_t k = 1'001; k <= 1'750; ++k) {
    feed(at_once, k);  // the stack runs on after its mission ended
  }
  for (std::int64_t k = 0; k <= 1'750; ++k) {
    feed(late, k);
  }
  late.endAt(kEnd);
  const auto a = at_once.errors();
  const auto b = late.errors();
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->samples, 1'001U);
  EXPECT_EQ(b->samples, 1'001U);
  EXPECT_DOUBLE_EQ(a->position_rms_m, b->position_rms_m);
  EXPECT_DOUBLE_EQ(a->position_max_m, b->position_max_m);
  EXPECT_NEAR(a->position_max_m, 1e-2, 1e-12);  // the pair at the end, k = 1000
  EXPECT_DOUBLE_EQ(a->attitude_max_deg, b->attitude_max_deg);
  EXPECT_DOUBLE_EQ(a->position_nees_mean, b->position_nees_mean);
  ASSERT_EQ(a->samples, b->samples);
  EXPECT_EQ(at_once.series().size(), late.series().size());
  EXPECT_LE(late.series().back().t_s, 4.0 + 1e-9);
}

TEST(EstimateScore, PairsOlderThanTheHoldAreKeptWhateverEndComesAfter)
{
  // An end heard more than kHoldNs of sim time after it no longer revokes what was scored:
  // the hold bounds what is kept per pair (a run of hours keeps only its sums).
  EstimateScore s;
  constexpr std::int64_t kStep = 4'000'000;
  const std::int64_t steps = 2 * EstimateScore::kHoldNs / kStep;
  for (std::int64_t k = 0; k <= steps; ++k) {
    s.onTruth(k * kStep, Vector3::Zero(), Quaternion::identity(), Vector3::Zero());
    s.onEstimate(k * kStep, Vector3(0.01, 0, 0), Quaternion::identity(), Vector3::Constant(0.1), true);
  }
  s.endAt(0);
  const auto e = s.errors();
  ASSERT_TRUE(e);
  // Kept: the pairs stamped more than kHoldNs before the newest (k < steps − kHoldNs / kStep).
  EXPECT_EQ(e->samples, static_cast<std::uint64_t>(steps - EstimateScore::kHoldNs / kStep));
}

}  // namespace
}  // namespace quad::launch
