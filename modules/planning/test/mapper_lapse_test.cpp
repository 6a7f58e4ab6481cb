// SPDX-License-Identifier: BSD-3-Clause
#include "quad/planning/mapper_lapse.hpp"

#include <gtest/gtest.h>

namespace {

using quad::planning::MapperLapse;

constexpr std::int64_t kGrace = 500'000'000;

TEST(MapperLapse, InRealTimeALapseCountsAtOnce)
{
  MapperLapse lapse(kGrace);
  EXPECT_FALSE(lapse.update(false, 1'000'000'000, false));
  EXPECT_TRUE(lapse.update(true, 1'000'000'000, false));
  EXPECT_FALSE(lapse.update(false, 1'100'000'000, false));
}

TEST(MapperLapse, InLockstepALapseCountsOnceItHasLastedTheGraceInSimTime)
{
  MapperLapse lapse(kGrace);
  // Lapsed for a long wall time while the clock crept on: not lost.
  for (std::int64_t t = 2'000'000'000; t < 2'000'000'000 + kGrace; t += 4'000'000) {
    EXPECT_FALSE(lapse.update(true, t, true)) << t;
  }
  EXPECT_TRUE(lapse.update(true, 2'000'000'000 + kGrace, true));
  EXPECT_TRUE(lapse.update(true, 9'000'000'000, true));
}

TEST(MapperLapse, ALivelinessRegainedStartsTheNextLapseAfresh)
{
  MapperLapse lapse(kGrace);
  EXPECT_FALSE(lapse.update(true, 0, true));
  EXPECT_FALSE(lapse.update(true, kGrace - 1, true));
  EXPECT_FALSE(lapse.update(false, kGrace, true));
  // A second lapse is timed from its own start, not the first one's.
  EXPECT_FALSE(lapse.update(true, kGrace + 1, true));
  EXPECT_FALSE(lapse.update(true, 2 * kGrace, true));
  EXPECT_TRUE(lapse.update(true, 2 * kGrace + 1, true));
}

}  // namespace
