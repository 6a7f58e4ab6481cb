// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/module_main.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "quad/common/identity.hpp"
#include "quad/common/logging.hpp"
#include "quad/common/yaml_input.hpp"

namespace quad::runtime {

namespace {

/// How long a container waits for one of its nodes to stop before it tells the next.
constexpr auto kNodeStopWait = std::chrono::seconds(3);

/// Ends the process of `nodes`, which stopped: their participant removed, so that its peers
/// see it leave at once, the logs and the streams flushed, then the exit, without destroying
/// the nodes. The system takes their memory back whole: freed block by block (the planner's
/// and the mapper's millions), it took most of the 0.3 s between a container's stop and its
/// exit. Whatever a node must leave behind (a recording, a map, a checkpoint) it wrote in
/// onStop().
[[noreturn]] void endProcess(std::vector<std::unique_ptr<Node>>& nodes, int status)
{
  for (auto& node : nodes) {
    node->quiesce();
  }
  if (!nodes.empty()) {
    nodes.front()->participant().shared()->close();
  }
  spdlog::shutdown();
  std::fflush(nullptr);
  std::_Exit(status);
}

/// Runs the nodes `make` builds, the first on this thread and each other on one of its own,
/// until all have stopped: a node that stops on its own, or fails, stops the others; a
/// signal stops them all. They stop in the reverse of the order `make` gives them (a
/// container's modules in the order named, but its recorders first, so stopped last), each done
/// before the next is told, as a launcher stops a process per module (the plant's clock ends
/// before the controller that answers it). Then ends the process (endProcess): 1 when
/// building or running any failed, else 0.
[[noreturn]] void runHosted(std::string_view process_name, const std::function<std::vector<std::unique_ptr<Node>>()>& make)
{
  SignalWatcher signals;
  std::vector<std::unique_ptr<Node>> nodes;
  std::unique_ptr<std::atomic<bool>[]> ended;
  std::once_flag stopping;
  std::atomic<int> status{0};
  const auto stopAll = [&] {
    std::call_once(stopping, [&] {
      for (std::size_t i = nodes.size(); i-- > 0;) {
        nodes[i]->stop();
        const auto until = std::chrono::steady_clock::now() + kNodeStopWait;
        while (!ended[i].load() && std::chrono::steady_clock::now() < until) {
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
      }
    });
  };
  const auto runOne = [&](std::size_t i) {
    try {
      nodes[i]->run();
    } catch (const std::exception& e) {
      spdlog::critical("{}: {}", nodes[i]->moduleName(), e.what());
      status = 1;
    }
    ended[i] = true;
    stopAll();
  };
  try {
    nodes = make();
    ended = std::make_unique<std::atomic<bool>[]>(nodes.size());
    signals.onSignal([&stopAll](int signal) {
      spdlog::info("signal {} received, stopping", signal);
      stopAll();
    });
    if (signals.received() != 0) {
      stopAll();  // a signal that came while the nodes were being built
    }
    spdlog::info("{} running on domain {}", process_name, nodes.front()->participant().options().domain_id);
    std::vector<std::thread> others;
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      others.emplace_back([&runOne, i] { runOne(i); });
    }
    runOne(0);
    for (auto& thread : others) {
      thread.join();
    }
    spdlog::info("{} stopped", process_name);
  } catch (const std::exception& e) {
    spdlog::critical("{}: {}", process_name, e.what());
    status = 1;
  }
  signals.onSignal({});  // before the process ends
  endProcess(nodes, status);
}

/// One module's part of a command line: `--config FILE` and `--set KEY=VALUE`s.
struct ModuleArgs {
  std::optional<std::string> config;
  std::vector<std::string> sets;
};

/// `module`'s params of `args` (its schema plus the logging keys); throws common::ConfigError
/// listing every problem, or std::exception for a file it cannot read.
common::Params moduleParams(const ModuleArgs& args, const common::ParamSchema& schema)
{
  std::vector<common::ParamOverride> overrides;
  for (const auto& s : args.sets) {
    overrides.push_back(common::parseOverride(s));
  }
  return args.config ? common::parseParams(common::readTextFile(*args.config), *args.config, schema, overrides)
                     : common::parseParams("", "<defaults>", schema, overrides);
}

/// The lines of a schema's parameters, for --help.
std::string parameterHelp(const common::ParamSchema& schema)
{
  std::string out;
  for (const common::ParamSpec& p : schema.specs()) {
    std::string line = fmt::format("  {}: {}", p.key, common::toString(p.type));
    if (p.default_value) {
      line += " = " + common::formatValue(*p.default_value);
    } else {
      line += " (required)";
    }
    if (!p.unit.empty()) {
      line += " [" + p.unit + "]";
    }
    out += fmt::format("{:<48} {}\n", line, p.description);
  }
  return out;
}

std::string programName(char** argv) { return std::filesystem::path(argv[0]).filename().string(); }

/// Logs a usage error as every quad program does (exit status 2).
int usageError(std::string_view name, const std::string& what, const std::string& usage)
{
  common::setupLogging(name);
  spdlog::critical("{}: {}; usage: {} (--help)", name, what, usage);
  return 2;
}

}  // namespace

int runNode(std::string_view module_name, const std::function<std::unique_ptr<Node>()>& make)
{
  runHosted(module_name, [&] {
    std::vector<std::unique_ptr<Node>> nodes;
    nodes.push_back(make());
    return nodes;
  });
}

int runNodeMain(int argc, char** argv, std::string_view module_name, common::ParamSchema schema,
                const std::function<std::unique_ptr<Node>(const common::Params&)>& make)
{
  common::addLoggingParams(schema);
  const std::string program = programName(argv);
  const std::string usage = program + " [--config FILE] [--set KEY=VALUE]... [--check]";
  ModuleArgs args;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--check") {
      check = true;
    } else if (arg == "--config" && i + 1 < argc) {
      args.config = argv[++i];
    } else if (arg == "--set" && i + 1 < argc) {
      args.sets.emplace_back(argv[++i]);
    } else if (arg == "--help" || arg == "-h") {
      const std::string help = fmt::format(
          "usage: {} | --help | --version\n\n"
          "quad's {} module, a DDS participant. Its parameters come from FILE (YAML) and --set\n"
          "(YAML values under dotted keys), checked against the list below (--check: only that,\n"
          "then exit); the participant's domain and transport come from the environment\n"
          "(QUAD_DOMAIN_ID, ...).\n\nparameters:\n",
          usage, module_name);
      std::fputs((help + parameterHelp(schema)).c_str(), stdout);
      return 0;
    } else if (arg == "--version") {
      std::printf("%s %s\n", program.c_str(), QUAD_VERSION);
      return 0;
    } else {
      return usageError(module_name, "unexpected argument '" + arg + "'", usage);
    }
  }
  common::Params params;
  try {
    params = moduleParams(args, schema);
    common::setupLogging(module_name, common::logOptionsFrom(params));
  } catch (const common::ConfigError& e) {
    common::setupLogging(module_name);
    for (const auto& problem : e.problems()) {
      spdlog::critical("{}", problem);
    }
    spdlog::critical("{}: refusing to start with an invalid config", module_name);
    return 1;
  } catch (const std::exception& e) {
    common::setupLogging(module_name);
    spdlog::critical("{}: {}", module_name, e.what());
    return 1;
  }
  if (check) {
    std::printf("%s: parameters ok\n", std::string(module_name).c_str());
    return 0;
  }
  return runNode(module_name, [&] { return make(params); });
}

int runModule(int argc, char** argv, const ModuleEntry& module)
{
  return runNodeMain(argc, argv, module.name, module.schema, [&](const common::Params& params) {
    return module.make(params, dds::Participant(dds::optionsFromEnvironment(module.name)));
  });
}

int runContainer(int argc, char** argv, const std::vector<ModuleEntry>& known)
{
  const std::string program = programName(argv);
  const std::string usage = program + " --module NAME [--config FILE] [--set KEY=VALUE]... [--module NAME ...] [--check]";
  std::string known_names;
  for (const auto& m : known) {
    known_names += (known_names.empty() ? "" : ", ") + m.name;
  }
  std::vector<const ModuleEntry*> hosted;
  std::vector<ModuleArgs> args;
  std::vector<std::string> names;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--check") {
      check = true;
      continue;
    }
    if (arg == "--help" || arg == "-h") {
      std::string help = fmt::format(
          "usage: {} | --help | --version\n\n"
          "Hosts several of quad's modules in one process, on one DDS participant: each is a node\n"
          "with its own readers, writers and thread, on the same dds::topics as when it runs alone.\n"
          "Each --module takes its own --config and --set, as that module's program does; the\n"
          "participant's domain and transport come from the environment (QUAD_DOMAIN_ID, ...).\n"
          "A module that stops or fails stops the container; --check only checks every module's\n"
          "parameters and exits. Modules: {}.\n",
          usage, known_names);
      for (const auto& m : known) {
        help += "\n" + m.name + " parameters:\n" + parameterHelp(m.schema);
      }
      std::fputs(help.c_str(), stdout);
      return 0;
    }
    if (arg == "--version") {
      std::printf("%s %s\n", program.c_str(), QUAD_VERSION);
      return 0;
    }
    if (arg == "--module" && i + 1 < argc) {
      const std::string name = argv[++i];
      const auto it = std::find_if(known.begin(), known.end(), [&](const ModuleEntry& m) { return m.name == name; });
      if (it == known.end()) {
        return usageError(program, "no module '" + name + "' (modules: " + known_names + ")", usage);
      }
      if (std::find(names.begin(), names.end(), name) != names.end()) {
        return usageError(program, "module '" + name + "' named twice: a process hosts a module once", usage);
      }
      hosted.push_back(&*it);
      names.push_back(name);
      args.emplace_back();
    } else if ((arg == "--config" || arg == "--set") && i + 1 < argc && !args.empty()) {
      if (arg == "--config") {
        args.back().config = argv[++i];
      } else {
        args.back().sets.emplace_back(argv[++i]);
      }
    } else {
      return usageError(program,
                        args.empty() ? "'" + arg + "' before the first --module" : "unexpected argument '" + arg + "'",
                        usage);
    }
  }
  if (hosted.empty()) {
    return usageError(program, "no module to host", usage);
  }
  std::vector<std::string> named;  // a recorder's name is not the container's
  for (std::size_t i = 0; i < hosted.size(); ++i) {
    if (!hosted[i]->records) {
      named.push_back(names[i]);
    }
  }
  if (named.empty()) {
    return usageError(program, "no module to host but a recorder: it records the modules beside it", usage);
  }
  const std::string name = common::containerName(named);
  std::vector<common::Params> params(hosted.size());
  std::vector<std::string> problems;
  for (std::size_t i = 0; i < hosted.size(); ++i) {
    common::ParamSchema schema = hosted[i]->schema;
    common::addLoggingParams(schema);
    try {
      params[i] = moduleParams(args[i], schema);
    } catch (const common::ConfigError& e) {
      for (const auto& problem : e.problems()) {
        problems.push_back(names[i] + ": " + problem);
      }
    } catch (const std::exception& e) {
      problems.push_back(names[i] + ": " + e.what());
    }
  }
  try {
    // One process, one log: the first module's logging keys set it up.
    common::setupLogging(name, problems.empty() ? common::logOptionsFrom(params.front()) : common::LogOptions{});
  } catch (const std::exception& e) {
    problems.emplace_back(e.what());
    common::setupLogging(name);
  }
  if (!problems.empty()) {
    for (const auto& problem : problems) {
      spdlog::critical("{}", problem);
    }
    spdlog::critical("{}: refusing to start with an invalid config", name);
    return 1;
  }
  if (check) {
    std::printf("%s: parameters ok\n", name.c_str());
    return 0;
  }
  runHosted(name, [&] {
    std::vector<std::unique_ptr<Node>> nodes;
    std::optional<dds::Participant> first(dds::optionsFromEnvironment(name));
    const std::shared_ptr<dds::SharedParticipant> shared = first->shared();
    // The modules, then the recorders (which record what the modules write), each put first:
    // runHosted stops the nodes from the last to the first.
    for (const bool recorders : {false, true}) {
      std::vector<std::size_t> group;
      for (std::size_t i = 0; i < hosted.size(); ++i) {
        if (hosted[i]->records == recorders) {
          group.push_back(i);
        }
      }
      // Built side by side, a thread each: a node's construction is mostly its own work (its
      // core's tables, its endpoints' payload pools, its types' sizes); the participant
      // serialises what they share, and no node handles a sample before it runs.
      std::vector<std::unique_ptr<Node>> built(group.size());
      std::vector<std::exception_ptr> failures(group.size());
      std::vector<std::thread> builders;
      for (std::size_t k = 0; k < group.size(); ++k) {
        dds::Participant participant = first ? std::move(*first) : dds::Participant(shared);
        first.reset();
        builders.emplace_back([&, k, participant = std::move(participant)]() mutable {
          try {
            built[k] = hosted[group[k]]->make(params[group[k]], std::move(participant));
          } catch (...) {
            failures[k] = std::current_exception();
          }
        });
      }
      for (auto& builder : builders) {
        builder.join();
      }
      for (const auto& failure : failures) {
        if (failure) {
          std::rethrow_exception(failure);  // the first module named that failed
        }
      }
      for (auto& node : built) {
        nodes.insert(recorders ? nodes.begin() : nodes.end(), std::move(node));
      }
    }
    return nodes;
  });
}

}  // namespace quad::runtime
