#include "launch_command.hpp"

#include <cstdio>

#include "launch_run.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/node.hpp"
#include "quad/dds/topics.hpp"

namespace quad::tools {

namespace fs = std::filesystem;

std::optional<launch::Manifest> loadRunManifest(const LaunchOptions& options)
{
  launch::ManifestOverrides overrides;
  if (options.world) {
    overrides.world = *options.world;
  }
  if (options.realtime) {
    overrides.mode = "realtime";
  } else if (options.lockstep) {
    overrides.mode = "lockstep";
  }
  overrides.seed = options.seed;
  overrides.domain = options.domain;
  overrides.subnet = options.subnet;
  launch::ProgramLookup lookup{buildDir(), QUAD_SOURCE_DIR,
                               [](const std::string& t) { return dds::topics::find(t).has_value(); }};
  try {
    return launch::loadManifest(options.manifest, overrides, lookup);
  } catch (const common::ConfigError& e) {
    for (const auto& p : e.problems()) {
      std::fprintf(stderr, "%s\n", p.c_str());
    }
    return std::nullopt;
  }
}

int runManifest(const launch::Manifest& manifest, const LaunchOptions& options, RunExtension* extension)
{
  int domain = 0;
  try {
    domain = manifest.domain ? *manifest.domain : dds::optionsFromEnvironment("quad_launch").domain_id;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "launch: %s\n", e.what());
    return kExitInvalid;
  }
  const fs::path dir = options.log_dir ? fs::path(*options.log_dir) : fs::path("log") / runFolderName(manifest.name);
  try {
    LaunchRun run(manifest, options, dir, domain);
    return run.execute(extension);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "launch: %s\n", e.what());
    return kExitFailed;
  }
}

int launch(const LaunchOptions& options)
{
  dds::SignalWatcher signals;  // before any thread exists
  signals.onSignal([](int s) { LaunchRun::received_signal.store(s); });

  const auto manifest = loadRunManifest(options);
  if (!manifest) {
    std::fprintf(stderr, "launch: refusing to start with an invalid manifest\n");
    return kExitInvalid;
  }
  if (options.check) {
    std::printf("%s: ok (%zu hosts, %zu modules)\n", manifest->file.string().c_str(), manifest->hosts.size(),
                manifest->modules.size());
    return 0;
  }
  return runManifest(*manifest, options, nullptr);
}

}  // namespace quad::tools
