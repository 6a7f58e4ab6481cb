// SPDX-License-Identifier: BSD-3-Clause
#include "launch_command.hpp"

#include <cstdio>

#include "quad/common/params.hpp"
#include "quad/dds/topics.hpp"
#include "quad/launch/module_check.hpp"
#include "quad/launch/run.hpp"
#include "quad/runtime/node.hpp"

namespace quad::tools {

namespace fs = std::filesystem;

int launch(const launch::LaunchOptions& options)
{
  runtime::SignalWatcher signals;  // before any thread exists
  signals.onSignal([](int s) { launch::LaunchRun::received_signal.store(s); });

  const auto manifest = launch::loadRunManifest(options);
  if (!manifest) {
    std::fprintf(stderr, "launch: refusing to start with an invalid manifest\n");
    return launch::kExitInvalid;
  }
  if (options.check) {
    const auto problems = launch::checkModuleParameters(*manifest);
    for (const auto& p : problems) {
      std::fprintf(stderr, "%s\n", p.c_str());
    }
    if (!problems.empty()) {
      std::fprintf(stderr, "launch: %s: invalid module parameters\n", manifest->file.string().c_str());
      return launch::kExitInvalid;
    }
    std::printf("%s: ok (%zu hosts, %zu modules)\n", manifest->file.string().c_str(), manifest->hosts.size(),
                manifest->modules.size());
    return 0;
  }
  return launch::runManifest(*manifest, options, nullptr);
}

}  // namespace quad::tools
