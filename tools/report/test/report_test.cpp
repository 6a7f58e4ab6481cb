// SPDX-License-Identifier: BSD-3-Clause
// A recording read back into a flight, and the report written from it: a synthetic flight
// whose every figure is known, encoded with quad's own schemas as the recorder stores them.
#include "quad/report/report.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <octomap/OcTree.h>

#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"
#include "quad/report/figures.hpp"
#include "quad/report/flight.hpp"
#include "scratch.hpp"

namespace quad::report {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json vec(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
Json header(std::int64_t stamp_ns, std::uint64_t seq, std::uint32_t vehicle = 1)
{
  return {{"vehicle_id", vehicle}, {"stamp_ns", stamp_ns}, {"publish_ns", stamp_ns}, {"seq", seq}};
}

/// A recording as `quad record` writes one: a schema per type, a channel per topic with its rate.
class Recording {
public:
  explicit Recording(const fs::path& file) : writer_(file, 1 << 16, "zstd") {}

  void write(const std::string& topic, const std::string& type, double rate_hz, Json message, std::int64_t stamp_ns,
             std::uint32_t vehicle = 1)
  {
    if (!channels_.contains(topic)) {
      const auto& schema = introspection::quadSchema();
      const auto id = writer_.addSchema(type, "omgidl", schema.flattenedIdl(type));
      channels_[topic] = writer_.addChannel(id, topic, "cdr", {{"rate_hz", std::to_string(rate_hz)}});
    }
    message["header"] = header(stamp_ns, ++seq_[topic], vehicle);
    const auto bytes = introspection::encodeCdr(introspection::quadSchema(), type, message);
    writer_.write(channels_[topic], static_cast<std::uint32_t>(seq_[topic]), static_cast<std::uint64_t>(stamp_ns),
                  static_cast<std::uint64_t>(stamp_ns), bytes.data(), bytes.size());
  }
  void close() { writer_.close(); }

private:
  bag::McapWriter writer_;
  std::map<std::string, std::uint16_t> channels_;
  std::map<std::string, std::uint64_t> seq_;
};

constexpr std::int64_t kMs = 1'000'000;

/// 10 s of flight: up to 2 m, then east at 1 m/s; a path every second, modes TAKEOFF then
/// MISSION, a collision at 6 s, one wall of occupied voxels at x = 8 m.
/// With `second`, a second vehicle (id 2) hovers at (0, 5, 1) beside it, with a path of its own.
void writeFlight(const fs::path& file, bool with_state = true, bool second = false)
{
  Recording r(file);
  if (second) {
    for (int k = 0; k <= 2500; ++k) {
      r.write("quad/sim/state", "quad::msg::VehicleState", 250.0,
              {{"p_W", vec(0, 5, 1)}, {"v_W", vec(0, 0, 0)}, {"q_WB", {{"w", 1.0}, {"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}},
              k * 4 * kMs, 2);
    }
    r.write("quad/planning/path", "quad::msg::Path", 0.0,
            {{"version", 1}, {"goal_id", 1}, {"status", "PLAN_OK"}, {"waypoints_W", {vec(0, 5, 1), vec(9, 5, 1)}},
             {"expansions", 7}, {"replan_time_s", 0.001}},
            0, 2);
  }
  r.write("quad/planning/goal", "quad::msg::Goal", 0.0, {{"goal_id", 1}, {"p_W", vec(10, 0, 2)}, {"tolerance", 0.3}}, 0);
  for (int k = 0; k <= 2500; ++k) {  // 250 Hz
    const double t = k * 0.004;
    const double x = t < 2.0 ? 0.0 : t - 2.0;
    const double z = std::min(t, 2.0);
    const Json state{{"p_W", vec(x, 0, z)}, {"v_W", vec(t < 2.0 ? 0.0 : 1.0, 0, t < 2.0 ? 1.0 : 0.0)},
                     {"q_WB", {{"w", 1.0}, {"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}};
    if (with_state) {
      r.write("quad/sim/state", "quad::msg::VehicleState", 250.0, state, k * 4 * kMs);
    }
    Json estimate = state;
    estimate["p_W"] = vec(x + 0.1, 0, z);
    estimate["p_std"] = vec(0.05, 0.05, 0.05);
    estimate["aligned"] = k >= 250;
    r.write("quad/estimation/state", "quad::msg::EstimatedState", 250.0, estimate, k * 4 * kMs);
    if (k % 50 == 0) {  // 5 Hz of a 20 Hz contract
      r.write("quad/control/status", "quad::msg::ControlStatus", 20.0,
              {{"mode", t < 2.0 ? "CONTROL_TAKEOFF" : "CONTROL_MISSION"}, {"position_error_W", vec(0.3, 0.4, 0)}, {"attitude_error", 0.01}},
              k * 4 * kMs);
    }
    if (k % 250 == 0) {
      r.write("quad/planning/path", "quad::msg::Path", 0.0,
              {{"version", k / 250 + 1}, {"goal_id", 1}, {"status", "PLAN_OK"}, {"waypoints_W", {vec(x, 0, 2), vec(10, 0, 2)}},
               {"expansions", 100 + k}, {"replan_time_s", 0.002}},
              k * 4 * kMs);
    }
  }
  r.write("quad/sim/events", "quad::msg::SimEvent", 0.0, {{"kind", "SIM_EVENT_COLLISION"}, {"p_W", vec(4, 0, 2)}, {"detail", "tree 3"}},
          6000 * kMs);
  octomap::OcTree tree(0.2);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 15; ++j) {
      tree.updateNode(octomap::point3d(8.1F, static_cast<float>(-0.9 + 0.2 * i), static_cast<float>(0.1 + 0.2 * j)), true);
    }
  }
  std::ostringstream bytes;
  tree.writeBinaryConst(bytes);
  const std::string b = bytes.str();
  r.write("quad/mapping/octomap", "quad::msg::MapSnapshot", 1.0,
          {{"update_seq", 1}, {"resolution", 0.2}, {"octree", std::vector<std::uint8_t>(b.begin(), b.end())}}, 9000 * kMs);
  r.close();
}

TEST(ReadFlight, RecoversTheTrajectoryPathsModesEventsMapAndRates)
{
  const fs::path dir = test::scratchDir("report_read");
  writeFlight(dir / "flight.mcap");
  const FlightData f = readFlight(bag::readMcap(dir / "flight.mcap"));
  EXPECT_NEAR(f.t_first_s, 0.0, 1e-9);
  EXPECT_NEAR(f.t_last_s, 10.0, 1e-9);
  // A sample per 40 ms of 10 s, not every one of the 2,501.
  EXPECT_NEAR(static_cast<double>(f.truth.size()), 251.0, 2.0);
  EXPECT_NEAR(f.truth.back().p_W.x(), 8.0, 0.05);
  EXPECT_NEAR(f.estimate.front().t_s, 1.0, 1e-9);  // aligned from 1 s
  ASSERT_EQ(f.goals.size(), 1U);
  EXPECT_NEAR(f.goals[0].p_W.x(), 10.0, 1e-12);
  ASSERT_EQ(f.paths.size(), 11U);
  EXPECT_EQ(f.paths[3].status, "PLAN_OK");
  EXPECT_EQ(f.paths[3].expansions, 850U);
  ASSERT_EQ(f.paths[3].waypoints_W.size(), 2U);
  ASSERT_EQ(f.status.size(), 51U);
  EXPECT_EQ(f.status.front().mode, "CONTROL_TAKEOFF");
  EXPECT_EQ(f.status.back().mode, "CONTROL_MISSION");
  EXPECT_NEAR(f.status.back().position_error_m, 0.5, 1e-12);
  ASSERT_EQ(f.events.size(), 1U);
  EXPECT_EQ(f.events[0].kind, "SIM_EVENT_COLLISION");
  EXPECT_NEAR(f.events[0].t_s, 6.0, 1e-9);
  // The wall: 10 × 15 voxels, each centre on the plane x = 8.1 m.
  EXPECT_NEAR(f.map_resolution_m, 0.2, 1e-12);
  ASSERT_EQ(f.occupied_W.size(), 150U);
  for (const auto& v : f.occupied_W) {
    EXPECT_NEAR(v.x(), 8.1, 0.1 + 1e-9);
  }
  // Rates from the stamps: the state at its contract's, the status at a quarter of it.
  for (const auto& r : f.rates) {
    if (r.topic == "quad/sim/state") {
      EXPECT_NEAR(r.rate_hz, 250.0, 0.1);
      EXPECT_EQ(r.contract_hz, 250.0);
    } else if (r.topic == "quad/control/status") {
      EXPECT_NEAR(r.rate_hz, 5.0, 0.01);
    } else if (r.topic == "quad/planning/path") {
      EXPECT_FALSE(r.contract_hz);  // an event topic has no rate to meet
    }
  }
  // The estimate is 0.1 m off along x, scored from its alignment.
  ASSERT_FALSE(f.estimate_error.empty());
  EXPECT_NEAR(f.estimate_error.back().position_m, 0.1, 1e-9);
  EXPECT_GE(f.estimate_error.front().t_s, 1.0);
}

TEST(ReadFlight, AFleetsRecordingIsReadOneVehicleAtATime)
{
  const fs::path dir = test::scratchDir("report_fleet");
  writeFlight(dir / "fleet.mcap", true, true);
  const auto recording = bag::readMcap(dir / "fleet.mcap");
  try {
    (void)readFlight(recording);
    FAIL() << "two vehicles read as one";
  } catch (const FlightError& e) {
    EXPECT_NE(std::string(e.what()).find("the recording holds vehicles 1, 2"), std::string::npos) << e.what();
  }
  const FlightData first = readFlight(recording, {}, 1U);
  EXPECT_EQ(first.paths.size(), 11U);
  for (const auto& s : first.truth) {
    EXPECT_EQ(s.p_W.y(), 0.0);
  }
  const FlightData second = readFlight(recording, {}, 2U);
  ASSERT_EQ(second.paths.size(), 1U);
  EXPECT_EQ(second.paths[0].expansions, 7U);
  EXPECT_TRUE(second.status.empty());
  ASSERT_FALSE(second.truth.empty());
  for (const auto& s : second.truth) {
    EXPECT_EQ(s.p_W, Vector3(0, 5, 1));
  }
  try {
    (void)readFlight(recording, {}, 3U);
    FAIL() << "a vehicle the recording does not hold";
  } catch (const FlightError& e) {
    EXPECT_NE(std::string(e.what()).find("no state of vehicle 3 (it holds 1, 2)"), std::string::npos) << e.what();
  }
}

TEST(ReadFlight, ARecordingWithoutTheVehicleStateIsRefusedNamingTheTopic)
{
  const fs::path dir = test::scratchDir("report_nostate");
  writeFlight(dir / "flight.mcap", false);
  try {
    (void)readFlight(bag::readMcap(dir / "flight.mcap"));
    FAIL() << "no error";
  } catch (const FlightError& e) {
    EXPECT_NE(std::string(e.what()).find("quad/sim/state"), std::string::npos) << e.what();
  }
}

TEST(WriteReport, ARunFolderGetsAPageThatShowsEveryFigureItWrote)
{
  const fs::path dir = test::scratchDir("report_run");
  writeFlight(dir / kRecordingFile);
  std::ofstream(dir / "summary.json") << R"({"success": true, "outcome": "landed at the goal", "collisions": 0,
      "path_length_m": 12.5, "optimum_m": 12.0, "flown_over_optimum": 1.0417, "time_to_goal_s": 5.31,
      "average_speed_mps": 2.38, "top_speed_mps": 3.04, "min_clearance_m": 0.412, "sim_seconds": 9.5, "wall_seconds": 4.0,
      "processes": {"plant": {"cpu_s": 1.5}},
      "estimate": {"position_rms_m": 0.1, "by_speed": [{"from_mps": 0, "samples": 7}, {"from_mps": 2, "samples": 9}]}})";
  std::vector<std::string> progress;
  const ReportResult r = writeReport({dir, {}, {}}, [&](const std::string& line) { progress.push_back(line); });
  EXPECT_EQ(r.html, dir / "report.html");
  const std::string html = test::readFile(r.html);
  for (const char* figure : {"top_view.svg", "side_view.svg", "motion.svg", "tracking.svg", "timeline.svg", "replanning.svg",
                             "rates.svg", "estimate_error.svg"}) {
    EXPECT_NE(html.find(std::string("src=\"") + figure + "\""), std::string::npos) << figure;
    const std::string svg = test::readFile(dir / figure);
    EXPECT_EQ(svg.rfind("<svg ", 0), 0U) << figure;
    EXPECT_EQ(svg.find("nan"), std::string::npos) << figure;
  }
  EXPECT_EQ(r.figures, 8);
  EXPECT_NE(html.find("<th>estimate.position_rms_m</th><td>0.1</td>"), std::string::npos);
  // a list of objects, a row a member of each (not one cell too wide for the page)
  EXPECT_NE(html.find("<th>estimate.by_speed[1].samples</th><td>9</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<th>path_length_m</th><td>12.5</td>"), std::string::npos);
  // The page opens with the outcome and the flight's figures, the processes' internals below the figures.
  const auto outcome = html.find("<h2>Outcome</h2>");
  ASSERT_NE(outcome, std::string::npos) << html;
  EXPECT_LT(outcome, html.find("<h2>Figures</h2>"));
  EXPECT_LT(html.find("<h2>Figures</h2>"), html.find("<th>processes.plant.cpu_s</th>"));
  for (const char* expected : {"SUCCESS</b> landed at the goal", "5.3 s (sim)", "2.4 m/s average, 3.0 m/s top",
                               "1.042 (12.5 m flown, 12.0 m the known-map optimum)", "<th>closest approach</th><td>0.41 m",
                               "<th>collisions</th><td>0</td>", "9.5 s of sim time in 4.0 s of wall time"}) {
    EXPECT_LT(html.find(expected), html.find("<h2>Figures</h2>")) << expected << "\n" << html;
  }
  EXPECT_EQ(html.find("http"), std::string::npos);  // nothing fetched from elsewhere
  EXPECT_GE(progress.size(), 3U);
  // The views mark the collision and draw the map's wall.
  const std::string top = test::readFile(dir / "top_view.svg");
  EXPECT_NE(top.find(">collision<"), std::string::npos);
  EXPECT_NE(top.find("mapped occupied voxels"), std::string::npos);
}

TEST(WriteReport, AVehicleThatOnlyStoodStillStillGetsEveryFigure)
{
  // A plant alone: no goal, path, status, map or estimate; its state never moves.
  const fs::path dir = test::scratchDir("report_still");
  {
    Recording r(dir / kRecordingFile);
    for (int k = 0; k < 500; ++k) {
      r.write("quad/sim/state", "quad::msg::VehicleState", 250.0,
              {{"p_W", vec(0, 0, 0)}, {"v_W", vec(0, 0, 0)}, {"q_WB", {{"w", 1.0}, {"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}},
              k * 4 * kMs);
    }
    r.close();
  }
  const ReportResult r = writeReport({dir, {}, {}});
  EXPECT_EQ(r.figures, 7);  // no estimate: no estimate figure
  for (const char* figure : {"top_view.svg", "side_view.svg", "motion.svg", "tracking.svg", "timeline.svg", "replanning.svg", "rates.svg"}) {
    const std::string svg = test::readFile(dir / figure);
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << figure;
    EXPECT_EQ(svg.find("nan"), std::string::npos) << figure;
    EXPECT_EQ(svg.find("inf"), std::string::npos) << figure;
  }
  EXPECT_NE(test::readFile(dir / "replanning.svg").find("no data"), std::string::npos);
}

TEST(WriteReport, AFaultRunsVerdictIsTabledAndItsReactionsDrawn)
{
  const fs::path dir = test::scratchDir("report_fault");
  writeFlight(dir / kRecordingFile);
  std::ofstream(dir / "fault_report.json") << R"json({"scenario": "kill_planning", "passed": false, "rows": [
    {"step": "1", "fault": "t=5.0 kill planning", "expectation": "applied", "bound": "", "measured": "at 5.02 s", "pass": true,
     "within_s": null, "measured_s": null},
    {"step": "", "fault": "", "expectation": "mode HOVER", "bound": "<= 1.50 s (sim)", "measured": "1.100 s", "pass": true,
     "within_s": 1.5, "measured_s": 1.1},
    {"step": "", "fault": "", "expectation": "planning back", "bound": "<= 2.00 s (wall)", "measured": "not seen", "pass": false,
     "within_s": 2.0, "measured_s": null}]})json";
  const ReportResult r = writeReport({dir, {}, {}});
  EXPECT_EQ(r.figures, 9);
  const std::string html = test::readFile(r.html);
  EXPECT_NE(html.find("<h2>Faults and reactions</h2>"), std::string::npos);
  EXPECT_NE(html.find("<b>checks failed</b>"), std::string::npos);
  EXPECT_NE(html.find("src=\"reactions.svg\""), std::string::npos);
  const std::string svg = test::readFile(dir / "reactions.svg");
  EXPECT_NE(svg.find("1: mode HOVER"), std::string::npos);
  EXPECT_NE(svg.find("1: planning back (not in time)"), std::string::npos);

  std::ofstream(dir / "fault_report.json") << R"({"rows": [{"step": 1}]})";
  try {
    (void)writeReport({dir, {}, {}});
    FAIL() << "no error";
  } catch (const ReportError& e) {
    EXPECT_NE(std::string(e.what()).find("fault_report.json: rows[0].step: not a string"), std::string::npos) << e.what();
  }
}

TEST(WriteReport, WhatCannotBeReportedIsAnErrorNamingTheFile)
{
  const fs::path dir = test::scratchDir("report_bad");
  const auto message = [](const ReportOptions& o) {
    try {
      (void)writeReport(o);
    } catch (const ReportError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({dir, {}, {}}).find((dir / kRecordingFile).filename().string()), std::string::npos);
  EXPECT_NE(message({dir / "absent.mcap", {}, {}}).find("absent.mcap: no such run folder or recording"), std::string::npos);
  std::ofstream(dir / "junk.mcap") << "not a recording";
  EXPECT_NE(message({dir / "junk.mcap", {}, {}}).find("junk.mcap"), std::string::npos);
  writeFlight(dir / "flight.mcap");
  std::ofstream(dir / "world.yaml") << "bounds: [1, 2";
  EXPECT_NE(message({dir / "flight.mcap", {}, dir / "world.yaml"}).find("world.yaml"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "report.html"));
}

}  // namespace
}  // namespace quad::report
