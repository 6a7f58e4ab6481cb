// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/event_log.hpp"

#include <gtest/gtest.h>

namespace quad::display {
namespace {

using Level = LogLine::Level;

TEST(EventLog, TheControllersStatusIsLoggedAtEachChangeOnly)
{
  EventLog log;
  const auto first = log.status(1, "CONTROL_TAKEOFF", "FAILSAFE_COMMANDED", false);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->level, Level::kInfo);
  EXPECT_EQ(first->source, "control");
  EXPECT_EQ(first->text, "CONTROL_TAKEOFF (FAILSAFE_COMMANDED)");
  EXPECT_FALSE(log.status(2, "CONTROL_TAKEOFF", "FAILSAFE_COMMANDED", false).has_value());
  EXPECT_EQ(log.status(3, "CONTROL_HOVER", "", false)->text, "CONTROL_HOVER");
  const auto failsafe = log.status(3, "CONTROL_LAND", "FAILSAFE_STALE_PATH", true);
  ASSERT_TRUE(failsafe.has_value());
  EXPECT_EQ(failsafe->level, Level::kWarning);
  EXPECT_EQ(failsafe->t_ns, 3);
  EXPECT_NE(failsafe->text.find("FAILSAFE_STALE_PATH"), std::string::npos);
  EXPECT_FALSE(log.status(4, "CONTROL_LAND", "FAILSAFE_STALE_PATH", true).has_value());
}

TEST(EventLog, PathsAreLoggedPerGoalAndStatusAndFailuresWarn)
{
  EventLog log;
  ASSERT_TRUE(log.path(1, 1, "PLAN_OK", true, 40.0, 12).has_value());
  EXPECT_FALSE(log.path(2, 1, "PLAN_OK", true, 39.0, 11).has_value());  // a replan: no line
  const auto no_path = log.path(3, 1, "PLAN_NO_PATH", false, 0.0, 0);
  ASSERT_TRUE(no_path.has_value());
  EXPECT_EQ(no_path->level, Level::kWarning);
  ASSERT_TRUE(log.path(4, 2, "PLAN_OK", true, 10.0, 3).has_value());  // a new goal
}

TEST(EventLog, RefusalsWarnAndCollisionsAreErrors)
{
  const EventLog log;
  EXPECT_EQ(log.goalAnswer(1, 7, false, "outside the bounds").level, Level::kWarning);
  EXPECT_EQ(log.goalAnswer(1, 7, true, "planning").level, Level::kInfo);
  EXPECT_EQ(log.commandAnswer(1, "COMMAND_LAND", false, "disarmed").level, Level::kWarning);
  using C = EventLog::EventClass;
  EXPECT_EQ(log.event(1, "EVENT_COLLISION", "tree 3", C::kCollision, false).level, Level::kError);
  EXPECT_EQ(log.event(1, "EVENT_FAULT_APPLIED", "imu dropout", C::kFault, false).level, Level::kWarning);
  const auto killed = log.event(1, "EVENT_FAULT_APPLIED", "planning killed", C::kFault, true);
  EXPECT_EQ(killed.source, "fault");
  EXPECT_EQ(log.event(1, "EVENT_GROUND_CONTACT", "", C::kOther, false).text, "EVENT_GROUND_CONTACT");
}

}  // namespace
}  // namespace quad::display
