// SPDX-License-Identifier: BSD-3-Clause
// Recordings compared message by message: equal ones agree, and the first differing member,
// count or topic is named, whatever the ignored members hold.
#include "quad/bag/compare.hpp"

#include <gtest/gtest.h>

#include "quad/bag/audit.hpp"
#include "quad/introspection/cdr.hpp"

namespace quad::bag {
namespace {

namespace in = quad::introspection;
using Json = nlohmann::ordered_json;

/// A path sample: `n` waypoints along x, stamped `t_ns`, published at `publish_ns`.
std::vector<std::uint8_t> path(std::int64_t t_ns, std::int64_t publish_ns, int n, double replan_s = 0.01,
                               std::uint32_t vehicle = 1)
{
  Json waypoints = Json::array();
  for (int i = 0; i < n; ++i) {
    waypoints.push_back({{"x", 1.0 * i}, {"y", 0.0}, {"z", 2.0}});
  }
  const Json v = {{"header", {{"vehicle_id", vehicle}, {"stamp_ns", t_ns}, {"publish_ns", publish_ns}, {"seq", 1}}},
                  {"version", 1},
                  {"waypoints_W", waypoints},
                  {"replan_time_s", replan_s}};
  return in::encodeCdr(in::quadSchema(), "quad::msg::Path", v);
}

/// A recording of one path topic and one clock-less topic of raw bytes.
McapContents recording(std::vector<std::vector<std::uint8_t>> paths, std::vector<std::uint8_t> raw = {1, 2, 3})
{
  McapContents c;
  c.schemas = {{1, "quad::msg::Path", "omgidl", ""}, {2, "other::Blob", "omgidl", ""}};
  c.channels = {{1, 1, "quad/planning/path", "cdr", {}}, {2, 2, "quad/other", "cdr", {}}};
  std::uint64_t t = 1;
  for (auto& p : paths) {
    c.messages.push_back({1, 0, t++, 0, std::move(p)});
  }
  c.messages.push_back({2, 0, t++, 0, std::move(raw)});
  return c;
}

const CompareOptions kIgnoringWallTime{nullptr, {"quad::msg::Header.publish_ns", "quad::msg::Path.replan_time_s"}};

TEST(Compare, RecordingsThatDifferOnlyInIgnoredMembersAgree)
{
  const auto a = recording({path(10, 111, 3, 0.01), path(20, 222, 4, 0.02)});
  const auto b = recording({path(10, 999, 3, 0.05), path(20, 555, 4, 0.07)});
  const Comparison c = compareRecordings(a, b, kIgnoringWallTime);
  EXPECT_TRUE(c.differences.empty());
  EXPECT_EQ(c.topics, 2U);
  EXPECT_EQ(c.messages, 3U);
  // Not ignored, the same members differ.
  const Comparison strict = compareRecordings(a, b, {});
  ASSERT_EQ(strict.differences.size(), 1U);
  EXPECT_EQ(strict.differences[0].field, "header.publish_ns");
  EXPECT_EQ(strict.differences[0].index, 1U);
  EXPECT_EQ(strict.differences[0].first, "111");
  EXPECT_EQ(strict.differences[0].second, "999");
}

TEST(Compare, AFleetsSamplesOfOneStampPairVehicleByVehicleWhateverOrderTheyCameIn)
{
  // Vehicles 1 and 2 publish paths of one stamp; the two recordings hold them in turns of
  // their own.
  const auto a = recording({path(10, 1, 3, 0.01, 1), path(10, 2, 5, 0.01, 2), path(20, 3, 4, 0.01, 2), path(20, 4, 6, 0.01, 1)});
  const auto b = recording({path(10, 1, 5, 0.01, 2), path(10, 2, 3, 0.01, 1), path(20, 3, 6, 0.01, 1), path(20, 4, 4, 0.01, 2)});
  const Comparison c = compareRecordings(a, b, kIgnoringWallTime);
  EXPECT_TRUE(c.differences.empty()) << c.differences.front().topic << " " << c.differences.front().field;
  EXPECT_EQ(c.messages, 5U);
  // One vehicle's path changed is still a difference.
  const auto d = recording({path(10, 1, 5, 0.01, 2), path(10, 2, 3, 0.01, 1), path(20, 3, 6, 0.01, 1), path(20, 4, 7, 0.01, 2)});
  const Comparison changed = compareRecordings(a, d, kIgnoringWallTime);
  ASSERT_EQ(changed.differences.size(), 1U);
  EXPECT_EQ(changed.differences[0].index, 4U);
}

TEST(Compare, TheFirstDifferingMemberIsNamedWithBothValues)
{
  auto changed = path(20, 5, 4);
  auto decoded = in::decodeCdr(in::quadSchema(), "quad::msg::Path", changed);
  decoded["waypoints_W"][2]["x"] = 2.5;
  decoded["waypoints_W"][3]["z"] = 9.0;
  changed = in::encodeCdr(in::quadSchema(), "quad::msg::Path", decoded);
  const Comparison c =
      compareRecordings(recording({path(10, 1, 3), path(20, 2, 4)}), recording({path(10, 3, 3), changed}), kIgnoringWallTime);
  ASSERT_EQ(c.differences.size(), 1U);
  const Difference& d = c.differences[0];
  EXPECT_EQ(d.topic, "quad/planning/path");
  EXPECT_EQ(d.index, 2U);
  EXPECT_EQ(d.stamp_ns, 20);
  EXPECT_EQ(d.field, "waypoints_W[2].x");
  EXPECT_EQ(d.first, "2.0");
  EXPECT_EQ(d.second, "2.5");
}

TEST(Compare, LengthsCountsTopicsAndRawPayloadsAreDifferencesToo)
{
  const auto a = recording({path(10, 1, 3), path(20, 2, 4)});
  // A sequence one element longer.
  auto c = compareRecordings(a, recording({path(10, 1, 3), path(20, 2, 5)}), kIgnoringWallTime);
  ASSERT_EQ(c.differences.size(), 1U);
  EXPECT_EQ(c.differences[0].field, "waypoints_W length");
  EXPECT_EQ(c.differences[0].first, "4");
  EXPECT_EQ(c.differences[0].second, "5");
  // A message fewer, where its recorder counted no loss.
  c = compareRecordings(a, recording({path(10, 1, 3), path(30, 2, 4)}), kIgnoringWallTime);
  ASSERT_EQ(c.differences.size(), 1U);
  EXPECT_EQ(c.differences[0].field, "message");
  EXPECT_EQ(c.differences[0].index, 2U);
  EXPECT_EQ(c.differences[0].stamp_ns, 20);
  EXPECT_EQ(c.differences[0].first, "present");
  EXPECT_EQ(c.differences[0].second, "absent");
  // Counted as lost by its recorder, it is passed over; a resent sample counts once.
  auto lossy = recording({path(10, 1, 3), path(10, 7, 3), path(30, 2, 4)});
  lossy.metadata.push_back({std::string(kLossMetadata), {{"quad/planning/path", toText({3, 1, 0, 0}, 1)}}});
  const auto whole = recording({path(10, 1, 3), path(20, 2, 4), path(30, 3, 4)});
  c = compareRecordings(whole, lossy, kIgnoringWallTime);
  EXPECT_TRUE(c.differences.empty());
  EXPECT_EQ(c.messages, 3U);
  // A type quad's IDL does not define is compared byte for byte.
  c = compareRecordings(a, recording({path(10, 1, 3), path(20, 2, 4)}, {1, 2, 4}), kIgnoringWallTime);
  ASSERT_EQ(c.differences.size(), 1U);
  EXPECT_EQ(c.differences[0].topic, "quad/other");
  EXPECT_EQ(c.differences[0].field, "payload");
  // A topic only one of them has; and a selection that leaves it out.
  auto more = a;
  more.channels.push_back({3, 2, "quad/extra", "cdr", {}});
  more.messages.push_back({3, 0, 99, 0, {7}});
  c = compareRecordings(a, more, kIgnoringWallTime);
  ASSERT_EQ(c.differences.size(), 1U);
  EXPECT_EQ(c.differences[0].topic, "quad/extra");
  EXPECT_EQ(c.differences[0].field, "topic");
  EXPECT_EQ(c.differences[0].first, "absent");
  CompareOptions selected = kIgnoringWallTime;
  selected.selected = [](const std::string& topic) { return topic != "quad/extra"; };
  EXPECT_TRUE(compareRecordings(a, more, selected).differences.empty());
}

/// A recording of a 10 Hz path topic (the rate noted on its channel) at `path_ms` and a sim
/// clock up to 1 s.
McapContents clockedRecording(const std::vector<std::int64_t>& path_ms)
{
  McapContents c;
  c.schemas = {{1, "quad::msg::Path", "omgidl", ""}, {2, "quad::msg::SimClock", "omgidl", ""}};
  c.channels = {{1, 1, "quad/planning/path", "cdr", {{"rate_hz", "10"}}}, {2, 2, "quad/sim/clock", "cdr", {}}};
  std::uint64_t log = 0;
  for (const std::int64_t t : path_ms) {
    c.messages.push_back({1, 0, ++log, 0, path(t * 1'000'000, 0, 2)});
  }
  for (std::int64_t t = 0; t <= 1000; t += 100) {
    const Json clock = {{"header", {{"stamp_ns", t * 1'000'000}}}, {"sim_ns", t * 1'000'000}};
    c.messages.push_back({2, 0, ++log, 0, in::encodeCdr(in::quadSchema(), "quad::msg::SimClock", clock)});
  }
  return c;
}

TEST(Compare, AMessageOnlyOneRecordingHoldsInItsTopicsLastPeriodBeforeTheEndIsPassedOver)
{
  CompareOptions options = kIgnoringWallTime;
  options.clock_topic = "quad/sim/clock";
  // Lost at the end (0.95 s, within 0.1 s of the clock's end at 1 s): nothing later reveals it.
  const Comparison tail = compareRecordings(clockedRecording({100, 500, 950}), clockedRecording({100, 500}), options);
  EXPECT_TRUE(tail.differences.empty());
  // Earlier, the same absence is a difference.
  const Comparison early = compareRecordings(clockedRecording({100, 500, 950}), clockedRecording({100, 950}), options);
  ASSERT_EQ(early.differences.size(), 1U);
  EXPECT_EQ(early.differences[0].field, "message");
  EXPECT_EQ(early.differences[0].stamp_ns, 500'000'000);
}

}  // namespace
}  // namespace quad::bag
