// SPDX-License-Identifier: BSD-3-Clause
// The `quad` command. With manual.cpp, the only translation units that include CLI11 (it costs
// ~9 s each).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <iostream>

#include "fault_command.hpp"
#include "campaign_command.hpp"
#include "command_command.hpp"
#include "launch_command.hpp"
#include "manual.hpp"
#include "plan_command.hpp"
#include "report_command.hpp"
#include "security_command.hpp"
#include "bag_commands.hpp"
#include "bridge_command.hpp"
#include "quad/common/layout.hpp"
#include "quad/so3/so3.hpp"
#include "topic_commands.hpp"

namespace {

void addConnectionOptions(CLI::App* command, quad::topic::ConnectionOptions& connection)
{
  command->add_option("--domain", connection.domain_id,
                      "DDS domain id (default: $QUAD_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
}

/// `--vehicle N` for a command that reads (`help`: only that vehicle's samples) or writes
/// (the vehicle its samples are for).
void addVehicleOption(CLI::App* command, quad::topic::ConnectionOptions& connection, const char* help)
{
  command->add_option("--vehicle", connection.vehicle_id, help)->check(CLI::Range(0, 1'000'000));
}

/// The word where a subcommand is expected that names none ("bridge" in `quad bridge --help`,
/// "topic lst" in `quad topic lst`); empty when there is none. CLI11 reads --help first and
/// would print the main help and succeed.
std::string unknownSubcommand(CLI::App& app, int argc, char** argv)
{
  CLI::App* at = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word.front() == '-') {
      // An option's value (`--domain 66`) is no subcommand: skip it.
      const CLI::Option* option = word.find('=') == std::string::npos ? at->get_option_no_throw(word) : nullptr;
      if (option != nullptr && option->get_type_size_min() > 0) {
        ++i;
      }
      continue;
    }
    const std::vector<CLI::App*> subcommands = at->get_subcommands([](CLI::App*) { return true; });
    if (subcommands.empty()) {
      return "";  // a positional argument of the subcommand reached
    }
    const auto named = std::find_if(subcommands.begin(), subcommands.end(),
                                    [&](CLI::App* s) { return s->check_name(word); });
    if (named == subcommands.end()) {
      return (at == &app ? "" : at->get_name() + " ") + word;
    }
    at = *named;
  }
  return "";
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"quad: run, inspect and test the quad flight stack"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "quad " QUAD_VERSION);

  quad::launch::LaunchOptions launch_options;
  auto* launch = app.add_subcommand("launch", "Start a manifest's modules on their hosts, supervise them, fly its mission");
  launch->add_option("manifest", launch_options.manifest, "Manifest file, or the name of a shipped one (demo: bringup/demo.yaml)")->required();
  launch->add_option("--world", launch_options.world, "Fly this world instead of the manifest's");
  auto* realtime = launch->add_flag("--realtime", launch_options.realtime, "Sim time follows the wall clock");
  launch->add_flag("--lockstep", launch_options.lockstep, "Sim time waits for every module (reproducible)")
      ->excludes(realtime);
  launch->add_option("--state", launch_options.state, "What the stack flies on: estimate, or truth to compare (the manifest's ${state})")
      ->check(CLI::IsMember({"estimate", "truth"}));
  launch->add_option("--seed", launch_options.seed, "${seed} of the manifest (the plant's random draws)");
  launch->add_option("--vehicle", launch_options.vehicle, "A fleet manifest: fly this vehicle alone (its id)")
      ->check(CLI::Range(0, 1'000'000));
  launch->add_option("--layout", launch_options.layout,
                     "distributed: a process per module; composed: the manifest's containers, a process each")
      ->check(CLI::IsMember({"distributed", "composed"}));
  launch->add_option("--domain", launch_options.domain, "DDS domain id (default: the manifest's, else $QUAD_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  launch->add_option("--subnet", launch_options.subnet, "First three numbers of the /24 for network-namespace hosts");
  launch->add_option("--set", launch_options.sets,
                     "MODULE:KEY=VALUE: one module's parameter, over its config and the manifest's set (repeatable)");
  launch->add_option("--summary", launch_options.summary, "Write the mission's summary as JSON to this file");
  auto* launch_record = launch->add_option("--record", launch_options.record,
                                           "Record every topic to this MCAP file (default: the run folder's recording.mcap)");
  launch->add_flag("--no-record", launch_options.no_record, "Record nothing (and so write no report)")->excludes(launch_record);
  launch->add_flag("--no-report", launch_options.no_report, "Write no report.html at the end of the run");
  launch->add_option("--log-dir", launch_options.log_dir, "The run's folder (default: log/<name>-<time>-<pid>)");
  launch->add_option("--wall-timeout", launch_options.wall_timeout_s, "Stop and fail after this many seconds")
      ->check(CLI::NonNegativeNumber);
  launch->add_flag("-q,--quiet", launch_options.quiet, "Modules' output to their log files only");
  launch->add_flag("--check", launch_options.check, "Validate the manifest and exit");

  quad::tools::PlanOptions plan_options;
  plan_options.config = (quad::common::configDir() / "planning.yaml").string();
  auto* plan = app.add_subcommand("plan", "The known-map optimum: plan on the whole world, every obstacle known");
  plan->add_option("--world", plan_options.world, "World file (default: the planning config's)");
  auto* plan_config =
      plan->add_option("--config", plan_options.config, "Planning config (radius, margin, lattice)")->capture_default_str();
  plan->add_option("--manifest", plan_options.manifest,
                   "Plan as this manifest's planning module does (its config and set; its world unless --world)")
      ->excludes(plan_config);
  plan->add_flag("--no-land", plan_options.no_land, "The mission does not land at the goal");
  plan->add_option("--json", plan_options.json, "Write the result as JSON to this file");

  quad::report::ReportOptions report_options;
  bool report_quiet = false;
  auto* report = app.add_subcommand("report", "A run's report: report.html and its figures, from the run's recording");
  report->add_option("input", report_options.input, "A run folder (log/<run>/, with its recording.mcap) or a recording")->required();
  report->add_option("-o,--output", report_options.output, "Folder for report.html and the figures (default: the input's)");
  report->add_option("--world", report_options.world, "World whose obstacles the views draw (default: the run's, from run.json)");
  report->add_option("--vehicle", report_options.vehicle, "A fleet's run: the vehicle to report (its id)");
  report->add_flag("-q,--quiet", report_quiet, "No progress lines");

  quad::tools::CampaignCommandOptions campaign_options;
  auto* campaign = app.add_subcommand(
      "campaign", "Fly the product of worlds, swept parameters and seeds, N runs at a time; a table and JSON of the runs");
  campaign->add_option("worlds", campaign_options.worlds, "World files");
  campaign->add_option("--file", campaign_options.file,
                       "A campaign file: manifest, worlds, seeds, axes, jobs (the options here add to it or replace)");
  campaign->add_option("--set", campaign_options.axes,
                       "An axis: MODULE:KEY=V1,V2,... (a module's parameter) or world:TYPE.KEY=V1,V2,... (the world's "
                       "generators'); FROM..TO for whole numbers (repeatable)");
  campaign->add_option("--seeds", campaign_options.seeds, "Fly each cell with seeds 1 ... N (the plant's ${seed})")
      ->check(CLI::Range(1, 1000));
  campaign->add_option("-j,--jobs", campaign_options.jobs, "Runs flown at once, each on its own DDS domain")
      ->check(CLI::Range(1, 64));
  campaign->add_option("--manifest", campaign_options.manifest, "Manifest flown in every run (default: bringup/demo.yaml)");
  campaign->add_option("--domain", campaign_options.domain,
                       "DDS domain of the first run flying at once; the others take the next ones (default: $QUAD_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  campaign->add_option("--state", campaign_options.state, "What every run flies on: estimate or truth (default: the manifest's)")
      ->check(CLI::IsMember({"estimate", "truth"}));
  campaign->add_option("--layout", campaign_options.layout,
                       "Every run's layout: distributed or composed (default: the manifest's)")
      ->check(CLI::IsMember({"distributed", "composed"}));
  campaign->add_option("--json", campaign_options.json, "Write the runs as JSON here (default: in the campaign's folder)");
  campaign->add_option("--log-dir", campaign_options.dir, "The campaign's folder (default: log/campaign-<time>-<pid>)");
  campaign->add_option("--wall-timeout", campaign_options.wall_timeout_s, "A run still going after this many seconds fails")
      ->check(CLI::PositiveNumber);
  campaign->add_flag("--no-record", campaign_options.no_record,
                     "Record nothing in any run (no recording, no run report): a forest run keeps 2 MB instead of 15");
  auto* slurm = campaign->add_flag("--slurm", campaign_options.slurm,
                                   "Submit the runs without a result to a Slurm cluster as one job array (sbatch), wait, "
                                   "gather; the campaign's folder must be shared by every node");
  campaign->add_option("--sbatch", campaign_options.sbatch_args,
                       "With --slurm, one more sbatch option, as --sbatch=--partition=quad (repeatable)")
      ->needs(slurm);
  campaign->add_option("--task", campaign_options.task, "Fly run N of the campaign alone: what each Slurm task runs")
      ->check(CLI::NonNegativeNumber)
      ->excludes(slurm);
  campaign->add_flag("--check", campaign_options.check,
                     "Check the manifest, every combination of parameters and every world, and exit");

  quad::fault::FaultOptions fault_options;
  auto* fault = app.add_subcommand("fault", "Run a fault-injection scenario: launch, break the stack on its timeline, check the reactions");
  fault->add_option("scenario", fault_options.scenario, "Scenario, e.g. tests/scenarios/kill_planning.yaml")->required();
  fault->add_option("--domain", fault_options.domain, "DDS domain id (default: the manifest's, else $QUAD_DOMAIN_ID, else 0)")
      ->check(CLI::Range(0, 232));
  fault->add_option("--log-dir", fault_options.log_dir, "The run's folder (default: log/fault-<name>-<time>-<pid>)");
  fault->add_option("--layout", fault_options.layout,
                    "distributed: a process per module; composed: the manifest's containers, a process each")
      ->check(CLI::IsMember({"distributed", "composed"}));
  fault->add_option("--wall-timeout", fault_options.wall_timeout_s, "Stop and fail after this many seconds")
      ->check(CLI::NonNegativeNumber);
  fault->add_flag("-q,--quiet", fault_options.quiet, "Modules' output to their log files only");
  fault->add_flag("--no-report", fault_options.no_report, "Write no report.html at the end of the run");
  fault->add_flag("--check", fault_options.check, "Validate the scenario and its manifest and exit");

  quad::record::RecordOptions record_options;
  auto* record = app.add_subcommand("record", "Record topic traffic to an MCAP file (Ctrl-C stops)");
  addConnectionOptions(record, record_options.connection);
  record->add_option("topics", record_options.topics, "Topics or globs (default: every quad topic)");
  record->add_option("-o,--output", record_options.output, "File (default: quad-<time>.mcap)");
  record->add_option("--exclude", record_options.exclude, "Globs of topics not to record");
  record->add_option("--duration", record_options.duration_s, "Stop after this many seconds")
      ->check(CLI::NonNegativeNumber);
  addVehicleOption(record, record_options.connection,
                   "Record only this vehicle's samples (Header.vehicle_id; the display's, without one, all)");
  record->add_flag("-q,--quiet", record_options.quiet, "No progress line");
  record->add_option("--compression", record_options.compression, "Chunk compression: zstd (default) or none")
      ->transform([](std::string v) { return v == "none" ? std::string() : v; })
      ->check(CLI::IsMember({"zstd", ""}));
  record->add_option("--split-size", record_options.split_size_mb, "Start a new file (NAME_001.mcap, ...) past this many MB")
      ->check(CLI::NonNegativeNumber);
  record->add_option("--split-duration", record_options.split_duration_s, "Start a new file after this many seconds")
      ->check(CLI::NonNegativeNumber);
  record->add_option("--chunk-size", record_options.chunk_size, "Bytes of messages per chunk (a killed recorder keeps every complete chunk)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 30));

  quad::bridge::BridgeOptions bridge_options;
  auto* bridge = app.add_subcommand("bridge", "Serve the stack live to Foxglove or Lichtblick (Foxglove WebSocket protocol; Ctrl-C stops)");
  addConnectionOptions(bridge, bridge_options.connection);
  bridge->add_option("--address", bridge_options.address, "Address to listen on (default 127.0.0.1; 0.0.0.0 for every interface)");
  bridge->add_option("--port", bridge_options.port, "Port (default 8765; 0: any free one)");
  bridge->add_option("--client-queue", bridge_options.client_queue_bytes,
                     "Bytes queued per client at most; past it what a slow client is sent is dropped")
      ->check(CLI::Range(std::size_t{1} << 16, std::size_t{1} << 32));
  bridge->add_flag("-q,--quiet", bridge_options.quiet, "No progress line");

  quad::tools::ReplayOptions replay_options;
  auto* replay = app.add_subcommand("replay", "Republish a recording with its original timing");
  addConnectionOptions(replay, replay_options.connection);
  replay->add_option("file", replay_options.file, "MCAP file")->required();
  replay->add_option("topics", replay_options.topics, "Topics or globs (default: every recorded quad topic)");
  replay->add_option("--exclude", replay_options.exclude, "Globs of topics not to replay");
  auto* replay_inputs_of = replay->add_option("--inputs-of", replay_options.inputs_of,
                     "Module in the loop: replay only what this module does not write (plant, mapping, planning, control)")
      ->check(CLI::IsMember({"plant", "mapping", "planning", "control"}));
  replay->add_option("-r,--rate", replay_options.rate, "Speed factor")->check(CLI::PositiveNumber);
  replay->add_option("--from", replay_options.from_s, "Start this many seconds in")->check(CLI::NonNegativeNumber);
  replay->add_option("--to", replay_options.to_s, "Stop this many seconds in")->check(CLI::NonNegativeNumber);
  replay->add_flag("--loop", replay_options.loop, "Start over at the end, until Ctrl-C");
  replay->add_option("--wait-match", replay_options.wait_match_s, "Seconds to wait for readers first")
      ->check(CLI::NonNegativeNumber);
  auto* replay_compare = replay->add_flag(
      "--compare", replay_options.compare,
      "With --inputs-of: start that module alone, drive it in lockstep with its recorded inputs and compare its "
      "outputs with the recorded ones (exit 0 identical, 1 differ, 2 cannot run)")
      ->needs(replay_inputs_of);
  replay->add_option("--run", replay_options.run_dir, "With --compare: the run's folder, holding run.json "
                                                      "(default: the recording's folder)")
      ->needs(replay_compare);
  replay->add_option("--set", replay_options.sets, "With --compare: KEY=VALUE for the module, after the run's own")
      ->needs(replay_compare);
  replay->add_option("--round-timeout", replay_options.round_timeout_s,
                     "With --compare: seconds of wall time a round may wait for the module")
      ->check(CLI::PositiveNumber)
      ->needs(replay_compare);
  replay->add_flag("--json", replay_options.json, "With --compare: the comparison as one JSON object")->needs(replay_compare);

  std::string bag_file;
  auto* bag = app.add_subcommand("bag", "Inspect recordings");
  bag->require_subcommand(1);
  auto* bag_info = bag->add_subcommand("info", "Topics, types, counts, rates, time span and loss of a recording");
  bag_info->add_option("file", bag_file, "MCAP file")->required();
  bool bag_json = false;
  bag_info->add_flag("--json", bag_json, "One JSON object instead of text");
  std::string recover_output;
  auto* bag_recover = bag->add_subcommand("recover", "Rewrite a recording cut short (killed recorder) whole");
  bag_recover->add_option("file", bag_file, "MCAP file")->required();
  bag_recover->add_option("-o,--output", recover_output, "Output (default: FILE.recovered.mcap)");
  quad::tools::BagEchoOptions bag_echo_options;
  auto* bag_echo = bag->add_subcommand("echo", "Print a recording's messages, decoded, in log-time order");
  bag_echo->add_option("file", bag_echo_options.file, "MCAP file")->required();
  bag_echo->add_option("--topics", bag_echo_options.topics, "Topics or globs to print (default: every topic)");
  bag_echo->add_flag("--json", bag_echo_options.json, "One JSON object a line instead of YAML documents");
  bag_echo->add_option("--max-elements", bag_echo_options.max_elements,
                       "Cut longer sequences and arrays to their first N elements (default: whole)");
  quad::tools::BagDiffOptions diff_options;
  auto* bag_diff = bag->add_subcommand(
      "diff", "Compare two recordings message by message (wall-clock and compute-time fields aside)");
  bag_diff->add_option("first", diff_options.first, "MCAP file")->required();
  bag_diff->add_option("second", diff_options.second, "MCAP file")->required();
  bag_diff->add_option("--topics", diff_options.topics, "Topics or globs to compare (default: every topic)");
  bag_diff->add_option("--exclude", diff_options.exclude, "Topics or globs not to compare");
  bag_diff->add_flag("--all-topics", diff_options.all_topics,
                     "Also the topics paced by wall time (heartbeats, display), left out by default");
  bag_diff->add_flag("--json", diff_options.json, "One JSON object instead of text");

  quad::security::InitOptions security_options;
  std::vector<std::string> security_containers;
  auto* security = app.add_subcommand("security", "DDS Security: authorities, identities and permissions");
  security->require_subcommand(1);
  auto* security_init = security->add_subcommand(
      "init", "Create a CA, an identity per module and tool, governance and signed permissions in DIR");
  security_init->add_option("dir", security_options.dir, "Folder for the files (created, mode 0700)")->required();
  security_init->add_option("--days", security_options.days, "Validity of identities and permissions (1..3650)")
      ->check(CLI::Range(1, 3650));
  security_init->add_flag("--force", security_options.force,
                          "Replace an existing CA (identities signed by the old one stop working)");
  security_init->add_option("--container", security_containers,
                            "Also an identity for a container of these modules, comma-separated in its manifest's "
                            "order (e.g. plant,estimation,control); repeatable");

  auto* topic = app.add_subcommand("topic", "Inspect and publish topics of a running stack");
  topic->require_subcommand(1);

  quad::tools::TopicListOptions list_options;
  auto* list = topic->add_subcommand("list", "Topics seen on the domain, with writers and readers");
  addConnectionOptions(list, list_options.connection);
  list->add_option("--wait", list_options.wait_s, "Seconds to listen to discovery")
      ->check(CLI::Range(0.0, 60.0));
  list->add_flag("--contracts", list_options.contracts,
                 "Print quad's declared topics (name, type, QoS, rate, owner) instead");
  list->add_flag("--json", list_options.json, "One JSON object instead of a table");

  quad::tools::TopicEchoOptions echo_options;
  quad::tools::TopicInfoOptions info_options;
  auto* info = topic->add_subcommand("info", "A topic's contract, and its writers and readers with their hosts");
  addConnectionOptions(info, info_options.connection);
  info->add_option("topic", info_options.topic, "Topic name, e.g. quad/sim/state")->required();
  info->add_option("--wait", info_options.wait_s, "Seconds to listen to discovery")->check(CLI::PositiveNumber);
  info->add_flag("--json", info_options.json, "One JSON object instead of text");

  quad::tools::TopicHzOptions hz_options;
  auto* hz = topic->add_subcommand("hz", "A topic's measured rate against its contract's");
  addConnectionOptions(hz, hz_options.connection);
  hz->add_option("topic", hz_options.topic, "Topic name, e.g. quad/sim/state")->required();
  hz->add_option("--duration", hz_options.duration_s, "Stop after this many seconds (0: Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  hz->add_option("--window", hz_options.window_s, "Seconds per line")->check(CLI::PositiveNumber);
  hz->add_flag("--json", hz_options.json, "One JSON object per line instead of text");
  addVehicleOption(hz, hz_options.connection, "Count only this vehicle's samples (Header.vehicle_id)");

  auto* echo = topic->add_subcommand("echo", "Print the samples of a topic, decoded from its IDL");
  addConnectionOptions(echo, echo_options.connection);
  echo->add_option("topic", echo_options.topic, "Topic name, e.g. quad/sim/state")->required();
  echo->add_option("-n,--count", echo_options.count, "Stop after N samples (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  echo->add_option("--timeout", echo_options.timeout_s,
                   "Exit 1 if --count samples did not arrive within this many seconds")
      ->check(CLI::NonNegativeNumber);
  echo->add_flag("--json", echo_options.json, "One JSON object per line");
  echo->add_option("--max-elements", echo_options.max_elements,
                   "Print at most this many elements of each list")
      ->check(CLI::PositiveNumber);
  addVehicleOption(echo, echo_options.connection, "Print only this vehicle's samples (Header.vehicle_id)");

  quad::tools::TopicPubOptions pub_options;
  auto* pub = topic->add_subcommand("pub", "Publish samples given as YAML; the header is filled in");
  addConnectionOptions(pub, pub_options.connection);
  pub->add_option("topic", pub_options.topic, "Topic name, e.g. quad/system/command")->required();
  pub->add_option("values", pub_options.values,
                  "Fields as YAML, e.g. '{kind: COMMAND_TAKEOFF, altitude: 2}'")
      ->required();
  pub->add_option("-n,--count", pub_options.count, "How many samples")->check(CLI::PositiveNumber);
  pub->add_option("-r,--rate", pub_options.rate_hz, "Samples per second")->check(CLI::PositiveNumber);
  pub->add_option("--wait-match", pub_options.wait_match_s,
                  "Seconds to wait for a reader before the first sample")
      ->check(CLI::NonNegativeNumber);
  addVehicleOption(pub, pub_options.connection,
                   "The vehicle the samples are for (Header.vehicle_id; default: $QUAD_VEHICLE_ID, else 0)");

  quad::tools::CommandOptions command_options;
  auto* operator_command = app.add_subcommand(
      "command", "The operator's commands to a running stack, each answered: taken, or refused and why");
  operator_command->require_subcommand(1);
  addConnectionOptions(operator_command, command_options.connection);
  operator_command->add_option("--timeout", command_options.timeout_s, "Seconds for the controller or planner to answer")
      ->check(CLI::PositiveNumber);
  operator_command->footer("Exit status: 0 taken, 1 refused, 2 bad input, 3 no answer within --timeout");
  const auto addVerb = [&](const char* name, const char* help) {
    auto* verb = operator_command->add_subcommand(name, help);
    verb->fallthrough();
    verb->callback([&command_options, name] { command_options.verb = name; });
    return verb;
  };
  addVerb("arm", "Arm the rotors on the ground");
  addVerb("disarm", "Disarm on the ground");
  auto* takeoff = addVerb("takeoff", "Take off (arming first if disarmed) and hold");
  takeoff->add_option("--altitude", command_options.altitude,
                      "Metres above the take-off point (default: the controller's configured altitude)")
      ->check(CLI::PositiveNumber);
  addVerb("hold", "Stop and hold position (the mission resumes only when commanded)");
  addVerb("land", "Land where the vehicle is");
  addVerb("return", "Return to launch: back along the flown path, land at the take-off point");
  for (auto* verb : {addVerb("goal", "Set the goal the planner plans to (x y z, world frame)"),
                     addVerb("goto", "Fly to a position (x y z: the new goal), or to the goal set (no position)")}) {
    verb->add_option("position", command_options.position, "x y z [m], world frame")->expected(0, 3);
    verb->add_option("--tolerance", command_options.tolerance, "Metres within which the goal counts as reached")
        ->check(CLI::PositiveNumber);
  }

  auto* so3 = app.add_subcommand("so3", "Rotations for students: convert, distance, sample");
  so3->require_subcommand(1);
  quad::so3::So3Options so3_options;
  const auto addSo3Options = [&so3_options](CLI::App* command) {
    command->add_flag("--degrees", so3_options.degrees, "Angles in and out in degrees");
    command->add_option("--tolerance", so3_options.tolerance,
                        "Tolerance of the SO(3) check of --matrix input")
        ->check(CLI::PositiveNumber);
  };
  const char* kRotationHelp =
      "Rotations: --matrix r11 r12 r13 r21 r22 r23 r31 r32 r33 | --quat w x y z | "
      "--axis-angle x y z angle | --ypr yaw pitch roll";
  auto* convert = so3->add_subcommand("convert", "Print one rotation in every representation");
  convert->footer(kRotationHelp);
  addSo3Options(convert);
  convert->allow_extras();
  auto* distance = so3->add_subcommand("distance", "Print every distance between two rotations");
  distance->footer(kRotationHelp);
  addSo3Options(distance);
  distance->allow_extras();
  int sample_count = 1;
  std::uint64_t sample_seed = 1;
  std::string sample_as = "quat";
  auto* sample = so3->add_subcommand("sample", "Haar-uniform random rotations (Shoemake 1992)");
  addSo3Options(sample);
  sample->add_option("-n,--count", sample_count, "How many");
  sample->add_option("--seed", sample_seed, "Seed of the generator (same seed, same rotations)");
  sample->add_option("--as", sample_as, "quat (w x y z), matrix (9, row by row), axis-angle or ypr");

  if (argc == 3 && std::string(argv[1]) == "--write-manual") {
    // The build's step that makes the manual pages and the completion (docs/build.md).
    try {
      const int pages = quad::tools::writeManual(app, argv[2], "quad " QUAD_VERSION);
      std::printf("%d manual pages and quad.bash in %s\n", pages, argv[2]);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "quad: %s\n", e.what());
      return 1;
    }
  }
  if (const std::string unknown = unknownSubcommand(app, argc, argv); !unknown.empty()) {
    std::fprintf(stderr, "quad: unknown subcommand '%s' (quad --help lists them)\n", unknown.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Usage errors exit with 2, like every bad input to quad's commands.
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    if (convert->parsed()) {
      quad::so3::so3Convert(convert->remaining(), so3_options, std::cout);
      return 0;
    }
    if (distance->parsed()) {
      quad::so3::so3Distance(distance->remaining(), so3_options, std::cout);
      return 0;
    }
    if (sample->parsed()) {
      quad::so3::so3Sample(sample_count, sample_seed, sample_as, so3_options, std::cout);
      return 0;
    }
  } catch (const quad::so3::UsageError& e) {
    std::fprintf(stderr, "quad so3: %s\n", e.what());
    return 2;
  }

  try {
    if (launch->parsed()) {
      return quad::tools::launch(launch_options);
    }
    if (operator_command->parsed()) {
      return quad::tools::command(command_options);
    }
    if (campaign->parsed()) {
      return quad::tools::campaign(campaign_options);
    }
    if (plan->parsed()) {
      return quad::tools::plan(plan_options);
    }
    if (report->parsed()) {
      return quad::tools::report(report_options, report_quiet);
    }
    if (fault->parsed()) {
      return quad::tools::fault(fault_options);
    }
    if (bridge->parsed()) {
      return quad::tools::bridge(bridge_options);
    }
    if (record->parsed()) {
      return quad::tools::record(record_options);
    }
    if (replay->parsed()) {
      return replay_options.compare ? quad::tools::replayCompare(replay_options) : quad::tools::replay(replay_options);
    }
    if (security_init->parsed()) {
      return quad::tools::securityInit(security_options, security_containers);
    }
    if (bag_info->parsed()) {
      return quad::tools::bagInfo(bag_file, bag_json);
    }
    if (bag_recover->parsed()) {
      return quad::tools::bagRecover(bag_file, recover_output);
    }
    if (bag_diff->parsed()) {
      return quad::tools::bagDiff(diff_options);
    }
    if (bag_echo->parsed()) {
      return quad::tools::bagEcho(bag_echo_options);
    }
    if (list->parsed()) {
      return quad::tools::topicList(list_options);
    }
    if (echo->parsed()) {
      return quad::tools::topicEcho(echo_options);
    }
    if (info->parsed()) {
      return quad::tools::topicInfo(info_options);
    }
    if (hz->parsed()) {
      return quad::tools::topicHz(hz_options);
    }
    if (pub->parsed()) {
      return quad::tools::topicPub(pub_options);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "quad: %s\n", e.what());
    return 1;
  }
  return 0;
}
