// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/module_check.hpp"

#include <sstream>

#include "quad/process/run.hpp"
#include "quad/process/spawn.hpp"

namespace quad::launch {

namespace fs = std::filesystem;

std::vector<std::string> checkModuleParameters(const Manifest& manifest)
{
  // The state folder does not exist yet; parameters naming files in it are only paths here.
  const fs::path state_dir = fs::temp_directory_path() / "quad-check-state";
  std::vector<std::string> problems;
  for (const Module& mod : manifest.modules) {
    const bool quad_module = mod.kind == kContainerKind || (!mod.kind.empty() && mod.kind != "quad");
    if (!quad_module || manifest.host(mod.host).kind == HostKind::kSsh) {
      continue;
    }
    std::vector<std::string> argv = processCommand(mod, state_dir);
    argv.emplace_back("--check");
    const process::RunResult result = process::run(argv);
    if (result.status == 0) {
      continue;
    }
    std::istringstream lines(result.output);
    bool any = false;
    for (std::string line; std::getline(lines, line);) {
      if (!line.empty()) {
        problems.push_back(mod.name + ": " + line);
        any = true;
      }
    }
    if (!any) {
      problems.push_back(mod.name + ": " + mod.program.string() + " --check failed (" +
                         process::describeStatus(result.status) + ")");
    }
  }
  return problems;
}

}  // namespace quad::launch
