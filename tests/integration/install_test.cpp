// SPDX-License-Identifier: BSD-3-Clause
// An installed quad (cmake --install) works from its prefix, moved or not, from any working
// directory: help, the shipped manifest found by name, and the demo mission flown (domain 230);
// and the Debian package of the same files (tools/check_deb.sh installs it on a clean root).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

/// Runs `argv` in `cwd` (through env -C); its exit status, output in `out`.
std::optional<int> runIn(const fs::path& cwd, std::vector<std::string> argv, std::string* out,
                         std::chrono::milliseconds timeout = 60s)
{
  argv.insert(argv.begin(), {"/usr/bin/env", "-C", cwd.string()});
  ChildProcess p(argv, {{"QUAD_TRANSPORT", "udp"}});
  const auto status = p.wait(timeout);
  *out = p.output();
  return status;
}

TEST(Install, APrefixMovedElsewhereFliesTheDemoFromAnyFolder)
{
  const fs::path dir = quad::test::scratchDir("quad_install");
  std::string out;
  ASSERT_EQ(runIn(dir, {"cmake", "--install", QUAD_BUILD_DIR, "--prefix", (dir / "first").string(), "--strip"}, &out,
                  180s),
            0)
      << out;
  // Relocatable: the prefix moves, nothing in it names where it was.
  fs::rename(dir / "first", dir / "prefix");
  const fs::path quad = dir / "prefix/bin/quad";
  for (const char* file : {"lib/quad/quad_plant_node", "lib/quad/quad_control_node", "lib/quad/quad_display_node",
                           "share/quad/configs/dds/quad_qos.xml",
                           "share/quad/bringup/demo.yaml", "share/quad/idl/quad/msg/VehicleState.idl",
                           "share/man/man1/quad.1", "share/man/man1/quad-launch.1",
                           "share/bash-completion/completions/quad"}) {
    EXPECT_TRUE(fs::exists(dir / "prefix" / file)) << file;
  }
  const fs::path elsewhere = dir / "elsewhere";
  fs::create_directories(elsewhere);
  ASSERT_EQ(runIn(elsewhere, {quad.string(), "--help"}, &out), 0) << out;
  EXPECT_NE(out.find("launch"), std::string::npos) << out;
  // The shipped manifest by name, its programs and configs in the prefix.
  ASSERT_EQ(runIn(elsewhere, {quad.string(), "launch", "demo", "--check"}, &out), 0) << out;
  // The demo mission, flown from the installed files.
  ASSERT_EQ(runIn(elsewhere,
                  {quad.string(), "launch", "demo", "--domain", "230", "--quiet", "--wall-timeout", "240", "--log-dir",
                   (elsewhere / "run").string()},
                  &out, 270s),
            0)
      << out;
  const auto summary = nlohmann::json::parse(quad::test::readFile(elsewhere / "run/summary.json"), nullptr, false);
  ASSERT_TRUE(summary.is_object()) << out;
  EXPECT_EQ(summary["end"], "success") << summary;
  EXPECT_EQ(summary["collisions"], 0) << summary;
  const auto record = nlohmann::json::parse(quad::test::readFile(elsewhere / "run/run.json"), nullptr, false);
  ASSERT_TRUE(record.is_object()) << out;
  EXPECT_EQ(record["manifest"], (dir / "prefix/share/quad/bringup/demo.yaml").string()) << record;
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Install, TheDebianPackageHoldsTheInstallationUnderUsrAndDeclaresItsLibraries)
{
  const fs::path dir = quad::test::scratchDir("quad_package");
  std::string out;
  ASSERT_EQ(runIn(dir, {"cpack", "-G", "DEB", "--config", std::string(QUAD_BUILD_DIR) + "/CPackConfig.cmake", "-B",
                        dir.string()},
                  &out, 300s),
            0)
      << out;
  fs::path deb;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".deb") {
      deb = entry.path();
    }
  }
  ASSERT_FALSE(deb.empty()) << out;
  ASSERT_EQ(runIn(dir, {"dpkg-deb", "--field", deb.string(), "Package", "Depends"}, &out), 0) << out;
  EXPECT_NE(out.find("Package: quad"), std::string::npos) << out;
  // dpkg-shlibdeps found the libraries the programs link
  for (const char* library : {"libfastrtps", "liboctomap", "libspdlog", "libyaml-cpp"}) {
    EXPECT_NE(out.find(library), std::string::npos) << library << " missing from\n" << out;
  }
  ASSERT_EQ(runIn(dir, {"dpkg-deb", "--contents", deb.string()}, &out), 0) << out;
  for (const char* file : {"./usr/bin/quad", "./usr/lib/quad/quad_planning_node", "./usr/share/quad/bringup/demo.yaml",
                           "./usr/share/quad/configs/dds/quad_qos.xml", "./usr/share/man/man1/quad.1",
                           "./usr/share/bash-completion/completions/quad", "./usr/share/doc/quad/LICENSE"}) {
    EXPECT_NE(out.find(file), std::string::npos) << file;
  }
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
