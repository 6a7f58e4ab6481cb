// SPDX-License-Identifier: BSD-3-Clause
#include "quad/fault/run.hpp"

#include <cstdio>
#include <map>

#include "driver.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/environment.hpp"
#include "quad/launch/observer.hpp"
#include "quad/launch/run.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"
#include "quad/topic/samples.hpp"

namespace quad::fault {

namespace fs = std::filesystem;

ScenarioLookup scenarioLookup()
{
  ScenarioLookup lookup;
  lookup.modes = launch::controlModeNames();
  lookup.check_sample = [](const std::string& topic, const std::string& values) -> std::string {
    try {
      topic::sampleValues(topic::requireTopic(topic), values);
      return "";
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
  };
  return lookup;
}

int runScenario(const FaultOptions& options)
{
  Scenario scenario;
  try {
    scenario = loadScenario(options.scenario, scenarioLookup());
  } catch (const common::ConfigError& e) {
    for (const auto& p : e.problems()) {
      std::fprintf(stderr, "%s\n", p.c_str());
    }
    std::fprintf(stderr, "fault: refusing to run an invalid scenario\n");
    return 2;
  }
  launch::LaunchOptions lo;
  lo.manifest = scenario.manifest.string();
  if (scenario.world) {
    lo.world = scenario.world->string();
  }
  lo.geofence = scenario.geofence;
  lo.realtime = scenario.mode == "realtime";
  lo.lockstep = scenario.mode == "lockstep";
  lo.state = scenario.state;
  lo.layout = options.layout;
  lo.domain = options.domain;
  lo.wall_timeout_s = options.wall_timeout_s;
  lo.quiet = options.quiet;
  lo.no_report = options.no_report;
  auto manifest = launch::loadRunManifest(lo);
  if (!manifest) {
    std::fprintf(stderr, "fault: %s: refusing to run with an invalid manifest\n", scenario.file.string().c_str());
    return 2;
  }
  // The scenario speaks of modules, alone or hosted in a container (the composed layout).
  std::vector<std::string> names;
  std::vector<std::string> kinds;
  for (const auto* m : manifest->hostedModules()) {
    names.push_back(m->name);
    kinds.push_back(m->kind);
  }
  std::map<std::string, bool> hosts;
  for (const auto& h : manifest->hosts) {
    hosts[h.name] = h.kind == launch::HostKind::kNetns;
  }
  auto problems = checkAgainstModules(scenario, names, kinds, hosts);
  for (auto& p : checkAgainstVehicles(scenario, manifest->vehicleIds(), !manifest->vehicles.empty())) {
    problems.push_back(std::move(p));
  }
  for (auto& p : checkAgainstContainers(scenario, *manifest)) {
    problems.push_back(std::move(p));
  }
  for (const auto& [name, values] : scenario.sets) {
    launch::Module* m = manifest->findHostedModule(name);
    if (m == nullptr) {
      continue;
    }
    // Over the manifest's: a key it sets too is replaced, the others added.
    for (const auto& [key, value] : values) {
      std::erase_if(m->sets, [&](const auto& kv) { return kv.first == key; });
      m->sets.emplace_back(key, value);
    }
  }
  // A module whose links a step breaks gets the datagram fault layer (UDP only).
  for (const auto& step : scenario.steps) {
    if (step.action.kind != Action::Kind::kDds) {
      continue;
    }
    if (manifest->transport == "shm") {
      problems.push_back(common::configProblem(scenario.file.string(), "steps", step.action.describe(),
                                               manifest->file.filename().string() +
                                                   " runs on shared memory only, which the datagram fault layer "
                                                   "cannot sit in front of"));
      break;
    }
    for (auto& m : manifest->modules) {
      if (m.name == step.action.module) {
        m.environment[dds::environment::kFaultLayer] = "1";
      }
    }
  }
  if (!manifest->mission.enabled && !scenario.end_s) {
    problems.push_back(common::configProblem(scenario.file.string(), "end_at", std::string("(missing)"),
                                             manifest->file.filename().string() +
                                                 " flies no mission, so the scenario must say when it ends"));
  }
  if (!problems.empty()) {
    for (const auto& p : problems) {
      std::fprintf(stderr, "%s\n", p.c_str());
    }
    std::fprintf(stderr, "fault: refusing to run an invalid scenario\n");
    return 2;
  }
  if (options.check) {
    std::printf("%s: ok (%zu steps, manifest %s)\n", scenario.file.string().c_str(), scenario.steps.size(),
                manifest->file.string().c_str());
    return 0;
  }
  const fs::path dir =
      options.log_dir ? fs::path(*options.log_dir) : fs::path("log") / launch::runFolderName("fault-" + scenario.name);
  lo.log_dir = dir.string();
  const fs::path recording = dir / "recording.mcap";
  lo.record = recording.string();
  const auto driver = makeDriver(scenario, recording);
  return launch::runManifest(*manifest, lo, driver.get());
}

}  // namespace quad::fault
