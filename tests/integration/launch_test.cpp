// SPDX-License-Identifier: BSD-3-Clause
// quad launch: the demo mission end to end, across network namespaces, and supervision.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "json_lines.hpp"
#include "process.hpp"
#include "recording_diff.hpp"
#include "scratch.hpp"
#include "wait.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

fs::path writeManifest(const fs::path& dir, const std::string& text)
{
  const fs::path file = dir / "m.yaml";
  std::ofstream(file) << text;
  return file;
}

/// The run's run.json; null until the launcher wrote it.
nlohmann::json runRecord(const fs::path& run_dir)
{
  const auto j = nlohmann::json::parse(quad::test::readFile(run_dir / "run.json"), nullptr, false);
  return j.is_discarded() ? nlohmann::json() : j;
}

/// Waits up to `timeout` for the run's run.json to satisfy `holds`; the last one read.
nlohmann::json waitForRecord(const fs::path& run_dir, const std::function<bool(const nlohmann::json&)>& holds,
                             std::chrono::milliseconds timeout)
{
  nlohmann::json last;
  quad::test::waitFor(
      [&] {
        last = runRecord(run_dir);
        return !last.is_null() && holds(last);
      },
      timeout);
  return last;
}

/// Whether `module` of a run.json is running (its heartbeat came) after its `starts`-th start.
auto runningAfterStart(const std::string& module, int starts = 1)
{
  return [=](const nlohmann::json& r) {
    const auto& m = r["modules"][module];
    return m["phase"] == "running" && m["starts"] == starts;
  };
}

/// The demo's containers (bringup/demo.yaml): one, hosting every module.
const std::vector<std::string> kDemoContainers{"stack"};

/// Flies a shipped manifest's mission (or the manifest at an absolute path) and checks the
/// summary and the run folder; given `recording`, records the run and keeps the file there,
/// and given `scores`, the summary. Composed, the processes are `containers`.
void flyMission(const std::string& manifest, int domain, std::vector<std::string> extra, const fs::path& recording = {},
                nlohmann::json* scores = nullptr, const std::vector<std::string>& containers = kDemoContainers)
{
  const fs::path dir = quad::test::scratchDir("quad_launch_" + std::to_string(domain));
  if (!recording.empty()) {
    extra.insert(extra.end(), {"--record", (dir / "run.mcap").string()});
  }
  const std::string manifest_file =
      manifest.starts_with("/") ? manifest : std::string(QUAD_SOURCE_DIR) + "/bringup/" + manifest;
  std::vector<std::string> argv{QUAD_TOOL, "launch", manifest_file,
                                "--domain", std::to_string(domain), "--quiet", "--wall-timeout", "300",
                                "--summary", (dir / "summary.json").string(), "--log-dir", (dir / "run").string()};
  argv.insert(argv.end(), extra.begin(), extra.end());
  ChildProcess launch(argv);
  const auto status = launch.wait(330s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 0) << launch.output();
  const auto summary = nlohmann::json::parse(quad::test::readFile(dir / "summary.json"), nullptr, false);
  ASSERT_FALSE(summary.is_discarded()) << launch.output();
  if (scores != nullptr) {
    *scores = summary;
  }
  EXPECT_EQ(summary["end"], "success") << summary;
  EXPECT_EQ(summary["outcome"], "landed at the goal") << summary;
  EXPECT_EQ(summary["collisions"], 0) << summary;
  EXPECT_EQ(summary["state"], "estimate") << summary;  // the shipped manifests fly on the estimate
  // A process per module, or in the composed layout, per container of the manifest's.
  const bool composed = std::find(extra.begin(), extra.end(), "composed") != extra.end();
  const std::vector<std::string> processes = composed ? containers
                                                      : std::vector<std::string>{"plant", "control", "mapping",
                                                                                 "planning", "estimation"};
  for (const auto& process : processes) {
    EXPECT_TRUE(fs::exists(dir / "run" / (process + ".log"))) << process;
  }
  for (const char* file : {"launch.log", "summary.json"}) {
    EXPECT_TRUE(fs::exists(dir / "run" / file)) << file;
  }
  // What the run cost: sim over wall time, and each process's CPU time over the wall time.
  // Together they cannot have kept more cores busy than the machine has.
  const double wall = summary["wall_seconds"].get<double>();
  EXPECT_NEAR(summary["real_time_factor"].get<double>(), summary["sim_seconds"].get<double>() / wall, 1e-9) << summary;
  // The start-up (every module started and the lockstep barrier met) and the flight that
  // followed fit in the run's wall time; every process held some memory, a modest amount.
  const double startup = summary["startup_seconds"].get<double>();
  const double flight = summary["flight_wall_seconds"].get<double>();
  EXPECT_GT(startup, 0.0) << summary;
  EXPECT_GT(flight, 0.0) << summary;
  EXPECT_LE(startup + flight, wall) << summary;
  double busy = 0.0;
  std::vector<std::string> costed = processes;
  costed.emplace_back("launch");
  for (const auto& process : costed) {
    const auto& cost = summary["processes"][process];
    ASSERT_TRUE(cost["cpu_seconds"].is_number()) << process << " " << summary;
    EXPECT_GT(cost["cpu_seconds"].get<double>(), 0.0) << process;
    EXPECT_NEAR(cost["busy_share"].get<double>(), cost["cpu_seconds"].get<double>() / wall, 1e-9) << process;
    busy += cost["busy_share"].get<double>();
    ASSERT_TRUE(cost["max_rss_mib"].is_number()) << process << " " << summary;
    EXPECT_GT(cost["max_rss_mib"].get<double>(), 1.0) << process;
    EXPECT_LT(cost["max_rss_mib"].get<double>(), 4096.0) << process;
    ASSERT_TRUE(cost["waits"].is_number_unsigned()) << process << " " << summary;
    EXPECT_GT(cost["waits"].get<std::uint64_t>(), 0U) << process;  // each waited for its inputs
  }
  EXPECT_LE(busy, static_cast<double>(std::thread::hardware_concurrency()) + 0.05) << summary;
  const auto record = runRecord(dir / "run");
  EXPECT_EQ(record["exit_code"], 0) << record;
  for (const auto& process : processes) {
    EXPECT_EQ(record["modules"][process]["starts"], 1) << record;  // nothing died on the way
  }
  // The controller flew the planner's paths: it took off, followed a mission, landed.
  EXPECT_GT(summary["paths"].get<int>(), 0) << summary;
  std::vector<std::string> modes;  // "12.34 MISSION": the mode after the time
  for (const auto& change : summary["modes"]) {
    const auto text = change.get<std::string>();
    modes.push_back(text.substr(text.find(' ') + 1));
  }
  auto at = modes.begin();
  for (const char* mode : {"TAKEOFF", "MISSION", "LAND"}) {
    at = std::find(at, modes.end(), mode);
    ASSERT_NE(at, modes.end()) << mode << " missing or out of order in " << summary;
  }
  EXPECT_EQ(modes.back(), "IDLE") << summary;
  if (std::find(extra.begin(), extra.end(), "--record") != extra.end()) {
    // The recording holds the run's topics, with no loss on reliable ones.
    ChildProcess info({QUAD_TOOL, "bag", "info", (dir / "run.mcap").string(), "--json"});
    ASSERT_EQ(info.wait(60s), 0) << info.output();
    const auto bag = nlohmann::json::parse(info.output(), nullptr, false);
    ASSERT_TRUE(bag.is_object()) << info.output();
    EXPECT_EQ(bag["complete"], true) << bag;
    std::map<std::string, nlohmann::json> topics;
    for (const auto& t : bag["topics"]) {
      topics[t["topic"]] = t;
    }
    for (const char* topic : {"quad/planning/path", "quad/control/actuators", "quad/sim/state", "quad/mapping/update"}) {
      EXPECT_GT(topics[topic]["messages"].get<int>(), 0) << topic << "\n" << bag;
    }
    const auto& path = topics["quad/planning/path"]["loss"];
    ASSERT_TRUE(path.is_object()) << bag;
    EXPECT_EQ(path["missing"], 0) << bag;
    EXPECT_EQ(path["duplicated"], 0) << bag;
    EXPECT_EQ(path["reordered"], 0) << bag;
    // The run's report, drawn from that recording: a page showing every figure, each written.
    const std::string html = quad::test::readFile(dir / "run" / "report.html");
    for (const char* figure : {"top_view.svg", "side_view.svg", "motion.svg", "tracking.svg", "timeline.svg",
                               "replanning.svg", "rates.svg", "estimate_error.svg"}) {
      EXPECT_NE(html.find(std::string("<img src=\"") + figure + "\""), std::string::npos) << figure << "\n" << html;
      const std::string svg = quad::test::readFile(dir / "run" / figure);
      EXPECT_EQ(svg.rfind("<svg ", 0), 0U) << figure;
      EXPECT_NE(svg.find("</svg>"), std::string::npos) << figure;
    }
    // The top view draws the mapped obstacles and the flown trajectory over the world's trees.
    const std::string top = quad::test::readFile(dir / "run" / "top_view.svg");
    EXPECT_NE(top.find("mapped occupied voxels"), std::string::npos);
    EXPECT_NE(top.find("true obstacles"), std::string::npos);
    // quad report redraws it from the recording alone, elsewhere.
    ChildProcess redraw({QUAD_TOOL, "report", (dir / "run.mcap").string(), "-o", (dir / "again").string(), "-q"});
    ASSERT_EQ(redraw.wait(120s), 0) << redraw.output();
    EXPECT_TRUE(fs::exists(dir / "again" / "report.html"));
    EXPECT_TRUE(fs::exists(dir / "again" / "top_view.svg"));
  } else {
    // Unasked, a run records into its folder and ends with its report.
    EXPECT_TRUE(fs::exists(dir / "run" / "recording.mcap"));
    EXPECT_TRUE(fs::exists(dir / "run" / "report.html"));
    EXPECT_TRUE(fs::exists(dir / "run" / "top_view.svg"));
  }
  if (!recording.empty() && fs::exists(dir / "run.mcap")) {
    fs::copy_file(dir / "run.mcap", recording, fs::copy_options::overwrite_existing);
  }
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);  // kept to look into otherwise
  }
}

TEST(Launch, TheDemoFliesComposedUnderDdsSecurityEachContainerWithAnIdentityOfItsOwn)
{
  // GIVEN a domain's DDS Security files with an identity for each of two containers, and the
  // demo's manifest naming them, its modules split between the two (the fast loop's and the
  // map's), so that samples cross between identities
  const fs::path dir = quad::test::scratchDir("quad_launch_secure");
  const fs::path security = dir / "security";
  ChildProcess init({QUAD_TOOL, "security", "init", security.string(), "--container", "mapping,planning,display",
                     "--container", "estimation,control,plant"});
  const auto made = init.wait(60s);
  ASSERT_TRUE(made.has_value() && *made == 0) << init.output();
  std::string text = quad::test::readFile(fs::path(QUAD_SOURCE_DIR) / "bringup/demo.yaml");
  for (auto at = text.find("../"); at != std::string::npos; at = text.find("../", at)) {
    text.replace(at, 3, std::string(QUAD_SOURCE_DIR) + "/");
  }
  const std::string one = "  stack: [plant, estimation, control, mapping, planning, display]\n";
  const auto stack = text.find(one);
  ASSERT_NE(stack, std::string::npos) << "bringup/demo.yaml's container";
  text.replace(stack, one.size(), "  fast: [plant, estimation, control]\n  slow: [mapping, planning, display]\n");
  const fs::path manifest = dir / "secure_demo.yaml";
  std::ofstream(manifest) << "security: " << security.string() << "\n" << text;
  // WHEN it flies composed and recorded: each container on its own identity, the recorder and
  // the launcher's observer holding the lockstep start on theirs
  // THEN the mission ends at the goal, as the demo's does
  flyMission(manifest.string(), 124, {"--layout", "composed"}, dir / "secure.mcap", nullptr, {"fast", "slow"});
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Launch, DemoMissionReachesTheGoalInLockstepWithoutCollisionAndTwoRunsRecordTheSameMessagesComposedOrNot)
{
  // GIVEN the demo flown three times in lockstep with one seed, each run recorded: twice with
  // a process per module, once with the manifest's containers a process each
  const fs::path dir = quad::test::scratchDir("quad_launch_determinism");
  nlohmann::json first;
  nlohmann::json second;
  nlohmann::json composed;
  flyMission("demo.yaml", 180, {"--seed", "7"}, dir / "first.mcap", &first);
  flyMission("demo.yaml", 63, {"--seed", "7"}, dir / "second.mcap", &second);
  flyMission("demo.yaml", 98, {"--seed", "7", "--layout", "composed"}, dir / "composed.mcap", &composed);
  // WHEN the recordings are compared message by message THEN every topic paced by sim time
  // holds the same payloads in the same order, but for the members that hold wall-clock and
  // compute times, in every layout
  quad::test::expectIdenticalRecordings(QUAD_TOOL, dir / "first.mcap", dir / "second.mcap", 15, 50000);
  quad::test::expectIdenticalRecordings(QUAD_TOOL, dir / "first.mcap", dir / "composed.mcap", 15, 50000);
  // AND the runs score the same: the launcher's observer took in every state from sim time 0
  // (it holds the start, as the recorder does) and every mode the controller passed through,
  // and scored the estimator on exactly the pairs up to the mission's end
  for (const char* score : {"path_length_m", "min_clearance_m", "modes", "estimate"}) {
    EXPECT_EQ(first[score], second[score]) << score;
  }
  // (the composed run's flight; its estimate was once scored on one pair fewer, with the
  // machine loaded, though its messages were the same)
  for (const char* score : {"path_length_m", "min_clearance_m", "modes"}) {
    EXPECT_EQ(first[score], composed[score]) << score;
  }
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

/// `quad replay RECORDING --inputs-of MODULE --compare ...` on `domain`: its exit status and
/// its JSON answer.
std::pair<int, nlohmann::json> replayCompare(const fs::path& recording, const std::string& module, int domain,
                                             const std::vector<std::string>& extra = {})
{
  std::vector<std::string> argv{QUAD_TOOL, "replay", recording.string(), "--inputs-of", module, "--compare", "--json",
                                "--domain", std::to_string(domain)};
  argv.insert(argv.end(), extra.begin(), extra.end());
  ChildProcess replay(argv);
  const auto status = replay.wait(240s);
  const std::string out = replay.output();
  const auto json = nlohmann::json::parse(out.substr(std::min(out.find('{'), out.size())), nullptr, false);
  return {status.value_or(-1), json.is_discarded() ? nlohmann::json{{"output", out}} : json};
}

TEST(Launch, EachModuleReplayedAloneWithItsRecordedInputsWritesWhatItWroteInTheRun)
{
  // GIVEN the demo flown in lockstep, its modules composed into the manifest's containers,
  // recorded into its run folder
  const fs::path dir = quad::test::scratchDir("quad_launch_replay");
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--domain", "64",
                       "--layout", "composed", "--quiet", "--no-report", "--wall-timeout", "300", "--log-dir",
                       (dir / "run").string()});
  const auto status = launch.wait(330s);
  ASSERT_TRUE(status) << launch.output();
  ASSERT_EQ(*status, 0) << launch.output();
  const fs::path recording = dir / "run" / "recording.mcap";
  // WHEN each module is started alone, its own program as the run's record gives it, and
  // driven in lockstep by the recorded clock with its recorded inputs
  // THEN it writes what it wrote in the run, message for message
  for (const auto& [module, at_least] : std::vector<std::pair<std::string, int>>{
           {"planning", 20}, {"mapping", 100}, {"control", 1000}}) {
    const auto [code, result] = replayCompare(recording, module, 65);
    EXPECT_EQ(code, 0) << module << " " << result.dump(2);
    EXPECT_EQ(result["identical"], true) << module << " " << result.dump(2);
    EXPECT_GT(result["equal_messages"].get<int>(), at_least) << module << " " << result.dump(2);
  }
  // AND a planner with a wider safety margin parts from the run at its first different path,
  // named with the member and both values
  const auto [code, result] = replayCompare(recording, "planning", 65, {"--set", "safety_margin=0.5"});
  EXPECT_EQ(code, 1) << result.dump(2);
  ASSERT_EQ(result["identical"], false) << result.dump(2);
  bool path_named = false;
  for (const auto& d : result["differences"]) {
    if (d["topic"] == "quad/planning/path") {
      path_named = true;
      EXPECT_GE(d["index"].get<int>(), 1) << d;
      EXPECT_FALSE(d["field"].get<std::string>().empty()) << d;
      EXPECT_NE(d["first"], d["second"]) << d;
    }
  }
  EXPECT_TRUE(path_named) << result.dump(2);
  // AND a module the recording cannot drive is refused, exit status 2
  EXPECT_EQ(replayCompare(recording, "plant", 65).first, 2);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

/// The participants reading `topic` on `domain`, as discovery shows them within 1.5 s.
std::set<std::string> readersOf(const std::string& topic, int domain)
{
  ChildProcess info({QUAD_TOOL, "topic", "info", topic, "--wait", "1.5", "--json", "--domain", std::to_string(domain)});
  std::set<std::string> names;
  if (info.wait(30s) != 0) {
    return names;
  }
  const auto seen = nlohmann::json::parse(info.output(), nullptr, false);
  if (seen.is_object()) {
    for (const auto& r : seen["readers"]) {
      names.insert(r["participant"].get<std::string>());
    }
  }
  return names;
}

TEST(Launch, InFlightOnlyTheLaunchersObserverReadsTheGroundTruthAndTheEstimatorNoClock)
{
  constexpr int kDomain = 119;
  const fs::path dir = quad::test::scratchDir("quad_launch_truth");
  // The long world (a 130 m line): the run must outlast the looks below, which on a loaded
  // machine took longer than the demo's 45 s flight.
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--world",
                       std::string(QUAD_SOURCE_DIR) + "/configs/worlds/long.yaml", "--domain", std::to_string(kDomain),
                       "--quiet", "--wall-timeout", "300", "--log-dir", (dir / "run").string()});
  // Once control, planning and mapping read the estimate, every module has made its readers.
  const std::set<std::string> flying{"control", "mapping", "planning"};
  std::set<std::string> estimate_readers;
  for (int i = 0; i < 40; ++i) {
    estimate_readers = readersOf("quad/estimation/state", kDomain);
    if (std::includes(estimate_readers.begin(), estimate_readers.end(), flying.begin(), flying.end())) {
      break;
    }
  }
  ASSERT_TRUE(std::includes(estimate_readers.begin(), estimate_readers.end(), flying.begin(), flying.end()))
      << "readers of quad/estimation/state: " << testing::PrintToString(estimate_readers) << "\n" << launch.output();
  // The run's recorder (quad_record) stores every topic, once it saw its writer, and the
  // display draws the truth beside the estimate for viewers; neither flies anything, and no
  // module reads what they write. The recorder may be among the readers or not yet.
  // On a loaded machine one look may end before discovery has shown even the launcher, so
  // look again until it has; every module's readers already exist, so none can come later.
  std::set<std::string> truth_readers;
  for (int i = 0; i < 40 && truth_readers.count("quad_launch") == 0; ++i) {
    truth_readers = readersOf("quad/sim/state", kDomain);
  }
  truth_readers.erase("quad_record");
  truth_readers.erase("display");
  EXPECT_EQ(truth_readers, std::set<std::string>{"quad_launch"});
  // The estimator is paced by the IMU samples, and a lockstep run tells it so from its start:
  // the clock's sample of every round is not sent to it. (It flies: the controller needs its
  // estimate, and every module made its readers before its first sample.)
  // Looked at again until a look has shown the controller, as above.
  std::set<std::string> clock_readers;
  for (int i = 0; i < 40 && !clock_readers.contains("control"); ++i) {
    clock_readers = readersOf("quad/sim/clock", kDomain);
  }
  EXPECT_TRUE(clock_readers.contains("control")) << testing::PrintToString(clock_readers);
  EXPECT_FALSE(clock_readers.contains("estimation")) << testing::PrintToString(clock_readers);
  launch.signal(SIGINT);
  EXPECT_TRUE(launch.wait(60s)) << launch.output();
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Launch, ThreeHostManifestFliesTheMissionAcrossNetworkNamespaces)
{
  if (::geteuid() != 0) {
    GTEST_SKIP() << "network namespaces need root";
  }
  flyMission("three_hosts.yaml", 181, {"--subnet", "10.181.0"});
}

/// Runs a shell command line as root; its exit status.
int sh(const std::string& line)
{
  return std::system(line.c_str());
}

/// Whether `quad topic echo --json` in network namespace `ns` gets `count` samples of `topic` on
/// `domain` within 8 s; its output in `out`.
bool echoes(const std::string& ns, int domain, const std::string& topic, int count, std::string* out)
{
  ChildProcess echo({"/usr/bin/env", "ip", "netns", "exec", ns, QUAD_TOOL, "topic", "echo", topic, "--domain",
                     std::to_string(domain), "-n", std::to_string(count), "--timeout", "8", "--json"},
                    {{"QUAD_TRANSPORT", "udp"}});
  const auto status = echo.wait(30s);
  *out = echo.output();
  return status && *status == 0;
}

/// Whether `quad topic echo` in network namespace `ns` gets a vehicle state on `domain`
/// within 8 s; its output in `out`.
bool echoesAState(const std::string& ns, int domain, std::string* out)
{
  return echoes(ns, domain, "quad/sim/state", 1, out);
}

TEST(Launch, TheFirewallAdmitsTheManifestsHostsAndDropsAnyoneElseOnTheLink)
{
  if (::geteuid() != 0) {
    GTEST_SKIP() << "network namespaces and firewall rules need root";
  }
  // The plant alone on one namespace host, a second manifest host beside it, and a rogue
  // namespace on the same bridge that the manifest does not name. Without the firewall the
  // rogue reads the vehicle state; with it, it gets nothing while the manifest's host does.
  for (const bool firewall : {false, true}) {
    const int domain = firewall ? 198 : 197;
    const std::string subnet = firewall ? "10.198.0" : "10.197.0";
    const fs::path dir = quad::test::scratchDir("quad_launch_firewall_" + std::to_string(domain));
    const std::string root = QUAD_SOURCE_DIR;
    const auto manifest = writeManifest(dir, "mode: realtime\ntransport: udp\nnetwork: {interfaces: hosts, firewall: " +
                                                 std::string(firewall ? "true" : "false") + R"(}
hosts:
  sim: {type: netns}
  ops: {type: netns}
modules:
  plant:
    host: sim
    config: )" + root + R"(/configs/plant.yaml
    set: {world: )" + root + R"(/configs/worlds/demo.yaml, sim.mode: realtime, sim.duration: 120.0}
)");
    ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", std::to_string(domain), "--subnet", subnet,
                         "--log-dir", (dir / "run").string()});
    const auto record = waitForRecord(dir / "run", runningAfterStart("plant"), 30s);
    ASSERT_TRUE(runningAfterStart("plant")(record)) << record << launch.output();
    EXPECT_EQ(record["hosts"]["sim"]["kind"], "netns") << record;
    EXPECT_EQ(record["firewall"], firewall) << record;
    // The namespaces are quad-<run>-<host>, on the bridge qb<run>.
    const std::string ns = record["hosts"]["sim"]["namespace"];
    ASSERT_TRUE(ns.starts_with("quad-") && ns.ends_with("-sim")) << record;
    const std::string run = ns.substr(5, ns.size() - 9);
    const std::string rogue = "qrogue" + std::to_string(::getpid());
    const std::string veth = "qr" + std::to_string(::getpid());
    ASSERT_EQ(sh("ip netns add " + rogue + " && ip link add " + veth + "a type veth peer name " + veth + "b && ip link set " +
                 veth + "b netns " + rogue + " && ip link set " + veth + "a master qb" + run + " up && ip -n " + rogue +
                 " addr add " + subnet + ".200/24 dev " + veth + "b && ip -n " + rogue + " link set " + veth +
                 "b up && ip -n " + rogue + " link set lo up && ip -n " + rogue + " route add 224.0.0.0/4 dev " + veth + "b"),
              0);
    std::string out;
    const bool rogue_reads = echoesAState(rogue, domain, &out);
    EXPECT_EQ(rogue_reads, !firewall) << out;
    // Hostile datagrams from the rogue host at the plant's ports: without the firewall the
    // plant's validating transport drops the malformed ones and it flies on; with it, none
    // reaches the plant at all. Either way a manifest host still reads the state after.
    ChildProcess hostile({"/usr/bin/env", "ip", "netns", "exec", rogue, QUAD_DATAGRAM_FUZZER, "--domain",
                          std::to_string(domain), "--host", subnet + ".2", "--count", "20000", "--participants", "4",
                          "--seed", "7"});
    ASSERT_EQ(hostile.wait(60s), 0) << hostile.output();
    EXPECT_TRUE(echoesAState("quad-" + run + "-ops", domain, &out)) << out;
    // The plant counts the malformed datagrams its validating transport dropped among its
    // errors (heartbeat): some without the firewall, none with it.
    ASSERT_TRUE(echoes("quad-" + run + "-ops", domain, "quad/system/heartbeat", 2, &out)) << out;
    const auto beats = quad::test::jsonLines(out);
    ASSERT_FALSE(beats.empty()) << out;
    EXPECT_EQ(beats.back()["module_name"], "plant") << out;
    EXPECT_EQ(beats.back()["errors"].get<int>() > 0, !firewall) << out;
    sh("ip netns delete " + rogue);
    launch.signal(SIGTERM);
    const auto status = launch.wait(30s);
    ASSERT_TRUE(status) << launch.output();
    EXPECT_EQ(*status, 0) << launch.output();  // the plant ended cleanly, not by a datagram
    if (!::testing::Test::HasFailure()) {
      fs::remove_all(dir);
    }
  }
}

/// Waits up to 20 s for `module` to run after its `n`-th start (from 1); its pid, 0 if it did not.
int waitForRunning(const fs::path& run_dir, const std::string& module, int n)
{
  const auto record = waitForRecord(run_dir, runningAfterStart(module, n), 20s);
  return runningAfterStart(module, n)(record) ? record["modules"][module]["pid"].get<int>() : 0;
}

TEST(Launch, AKilledModuleIsRespawnedUntilItsLimitThenTheRunFails)
{
  const fs::path dir = quad::test::scratchDir("quad_launch_respawn");
  const auto manifest = writeManifest(dir, R"(
modules:
  mapping: {respawn: 1, backoff: 0.2}
)");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "182", "--log-dir", run.string()});
  const int first = waitForRunning(run, "mapping", 1);
  ASSERT_NE(first, 0) << runRecord(run) << launch.output();
  ASSERT_EQ(::kill(first, SIGKILL), 0);
  const int second = waitForRunning(run, "mapping", 2);
  ASSERT_NE(second, 0) << runRecord(run) << launch.output();
  EXPECT_NE(second, first);
  EXPECT_EQ(runRecord(run)["modules"]["mapping"]["restarts"], 1);
  EXPECT_EQ(runRecord(run)["modules"]["mapping"]["last_exit"], "killed by SIGKILL");
  // Over the limit: the run fails, naming the module.
  ASSERT_EQ(::kill(second, SIGKILL), 0);
  const auto status = launch.wait(20s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 1) << launch.output();
  const auto record = runRecord(run);
  EXPECT_EQ(record["phase"], "ended") << record;
  EXPECT_EQ(record["exit_code"], 1) << record;
  EXPECT_EQ(record["failure"], "mapping failed (killed by SIGKILL) after 1 restarts") << record;
  EXPECT_EQ(record["modules"]["mapping"]["phase"], "failed") << record;
  fs::remove_all(dir);
}

TEST(Launch, AKilledContainerTakesAllItsModulesWithItAndIsRespawnedAsOne)
{
  // GIVEN the mapper and the planner composed into one process, which may restart once
  const fs::path dir = quad::test::scratchDir("quad_launch_container");
  const auto manifest = writeManifest(dir, R"(
layout: composed
modules:
  mapping: {respawn: 1, backoff: 0.2}
  planning: {needs: [quad/mapping/update]}
containers:
  slow: [mapping, planning]
)");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "89", "--log-dir", run.string()});
  // WHEN it runs (both its modules' heartbeats came from its one process) and is killed
  const int first = waitForRunning(run, "slow", 1);
  ASSERT_NE(first, 0) << runRecord(run) << launch.output();
  EXPECT_FALSE(runRecord(run)["modules"].contains("mapping")) << runRecord(run);
  ASSERT_EQ(::kill(first, SIGKILL), 0);
  // THEN it starts again whole, both modules in a new process
  const int second = waitForRunning(run, "slow", 2);
  ASSERT_NE(second, 0) << runRecord(run) << launch.output();
  EXPECT_NE(second, first);
  EXPECT_EQ(runRecord(run)["modules"]["slow"]["last_exit"], "killed by SIGKILL");
  // AND killed past its limit, the run fails naming it
  ASSERT_EQ(::kill(second, SIGKILL), 0);
  const auto status = launch.wait(20s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 1) << launch.output();
  const auto record = runRecord(run);
  EXPECT_EQ(record["failure"], "slow failed (killed by SIGKILL) after 1 restarts") << record;
  EXPECT_EQ(record["modules"]["slow"]["phase"], "failed") << record;
  fs::remove_all(dir);
}

TEST(Launch, CtrlCStopsEveryModuleInReverseOrderAndEndsCleanly)
{
  const fs::path dir = quad::test::scratchDir("quad_launch_stop");
  const auto manifest = writeManifest(dir, R"(
modules:
  mapping: {}
  planning: {needs: [quad/mapping/update]}
)");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "185", "--log-dir", run.string()});
  ASSERT_NE(waitForRunning(run, "planning", 1), 0) << runRecord(run) << launch.output();
  launch.signal(SIGINT);
  const auto status = launch.wait(30s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 0) << launch.output();
  const auto record = runRecord(run);
  EXPECT_EQ(record["stopped_order"], nlohmann::json::array({"planning", "mapping"})) << record;
  for (const char* module : {"planning", "mapping"}) {
    EXPECT_EQ(record["modules"][module]["phase"], "stopped") << record;
    EXPECT_EQ(record["modules"][module]["last_exit"], "exit 0") << record;
  }
  EXPECT_EQ(record["exit_code"], 0) << record;
  EXPECT_EQ(record["failure"], "") << record;
  fs::remove_all(dir);
}

/// A module that needs another's topic starts only if discovery works the manifest's way.
void startsWithDiscovery(const std::string& discovery, int domain, const std::string& server)
{
  const fs::path dir = quad::test::scratchDir("quad_launch_discovery_" + std::to_string(domain));
  const auto manifest = writeManifest(dir, "discovery: " + discovery + R"(
modules:
  mapping: {}
  planning: {needs: [quad/mapping/update], ready_timeout: 15}
)");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", std::to_string(domain), "--log-dir",
                       run.string()});
  ASSERT_NE(waitForRunning(run, "planning", 1), 0) << runRecord(run) << launch.output();
  EXPECT_EQ(runRecord(run)["discovery_server"], server) << runRecord(run);
  launch.signal(SIGTERM);
  const auto status = launch.wait(30s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 0) << launch.output();
  fs::remove_all(dir);
}

TEST(Launch, ADiscoveryServerTheLauncherStartsConnectsTheModules)
{
  startsWithDiscovery("{kind: server, port: 11861}", 186, "127.0.0.1:11861");
}

TEST(Launch, InitialPeersConnectTheModules)
{
  startsWithDiscovery("{kind: initial_peers}", 187, "");
}

TEST(Launch, AMissingModuleFailsStartUpNamingIt)
{
  const fs::path dir = quad::test::scratchDir("quad_launch_missing");
  const auto manifest = writeManifest(dir, R"(
modules:
  control: {needs: [quad/planning/path], ready_timeout: 1.0}
)");
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "183", "--log-dir", (dir / "run").string()});
  const auto status = launch.wait(30s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 1) << launch.output();
  const auto record = runRecord(dir / "run");
  EXPECT_EQ(record["failure"], "control not started: after 1.0 s no writer on quad/planning/path (written by "
                               "planning, which this manifest does not start)")
      << record;
  EXPECT_EQ(record["modules"]["control"]["phase"], "waiting") << record;
  EXPECT_EQ(record["modules"]["control"]["starts"], 0) << record;
  fs::remove_all(dir);
}

TEST(Launch, AMalformedManifestIsRefusedWithFileAndKey)
{
  const fs::path dir = quad::test::scratchDir("quad_launch_malformed");
  const auto manifest = writeManifest(dir, R"(
hosts: {here: {type: local}}
modules:
  control: {respawns: 2}
  plant: {host: there}
  autopilot: {}
)");
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "184"});
  const auto status = launch.wait(20s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 2) << launch.output();
  const std::string file = manifest.string();
  for (const std::string& line : {file + ":modules.control.respawns: 2: unknown key",
                                 file + ":modules.plant.host: there: unknown host (hosts: here)",
                                 file + ":modules.autopilot.module: autopilot: module not found"}) {
    EXPECT_NE(launch.output().find(line), std::string::npos) << line << "\n" << launch.output();
  }
  EXPECT_FALSE(fs::exists(dir / "run"));  // nothing started
  fs::remove_all(dir);
}

TEST(Launch, AnSshHostRunsItsModuleWithTheRunsEnvironmentAndStopsIt)
{
  if (::geteuid() != 0 || !fs::exists("/usr/sbin/sshd")) {
    GTEST_SKIP() << "needs root and openssh-server";
  }
  // A private sshd on 127.0.0.1:2299 that lets this key in, and nothing else.
  const fs::path dir = quad::test::scratchDir("quad_launch_ssh");
  const std::string d = dir.string();
  for (const char* key : {"id", "host"}) {
    ChildProcess keygen({"/usr/bin/ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-f", d + "/" + key});
    ASSERT_EQ(keygen.wait(20s), 0) << keygen.output();
  }
  fs::copy_file(dir / "id.pub", dir / "authorized_keys");
  fs::create_directories("/run/sshd");  // sshd's privilege separation folder
  std::ofstream(dir / "sshd_config") << "Port 2299\nListenAddress 127.0.0.1\nHostKey " << d
                                     << "/host\nAuthorizedKeysFile " << d << "/authorized_keys\nPidFile " << d
                                     << "/sshd.pid\nStrictModes no\nUsePAM no\nPermitRootLogin prohibit-password\n";
  ChildProcess sshd({"/usr/sbin/sshd", "-D", "-e", "-f", d + "/sshd_config"});
  ASSERT_TRUE(sshd.waitForOutput("Server listening on 127.0.0.1 port 2299", 10s)) << sshd.output();
  const auto manifest = writeManifest(dir, "hosts:\n  here: {type: local}\n  far: {type: ssh, address: root@127.0.0.1, "
                                           "port: 2299, options: [-i, " + d + "/id, -o, StrictHostKeyChecking=no, -o, "
                                           "UserKnownHostsFile=/dev/null]}\n"
                                           "modules:\n  mapping: {host: far}\n"
                                           "  planning: {needs: [quad/mapping/update], ready_timeout: 20}\n");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "188", "--log-dir", run.string()});
  // The mapper, started over ssh, got the run's domain: its heartbeat reached the launcher,
  // and the planner, which needs its map, started.
  ASSERT_NE(waitForRunning(run, "planning", 1), 0) << runRecord(run) << launch.output();
  // The planner starts once the mapper's map writer is seen, which can be before its first
  // heartbeat reaches the launcher.
  EXPECT_NE(waitForRunning(run, "mapping", 1), 0) << runRecord(run);
  EXPECT_EQ(runRecord(run)["hosts"]["far"]["kind"], "ssh") << runRecord(run);
  launch.signal(SIGTERM);
  const auto status = launch.wait(30s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 0) << launch.output();
  EXPECT_EQ(runRecord(run)["modules"]["mapping"]["phase"], "stopped") << runRecord(run);
  sshd.signal(SIGTERM);
  sshd.wait(10s);  // it removes its pid file on the way out
  std::error_code ignored;
  fs::remove_all(dir, ignored);
}

}  // namespace
