// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A test's npm package (tests/<name>/: package.json, package-lock.json and its scripts),
/// installed with `npm ci` into the build tree once and its scripts refreshed every time.

#include <chrono>
#include <filesystem>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "process.hpp"

namespace quad::test {

struct NpmPackage {
  std::string npm;                    ///< the npm program
  std::filesystem::path source_dir;   ///< the project's source tree
  std::filesystem::path build_dir;    ///< the build tree
  std::string name;                   ///< tests/<name>, installed into <build>/<name>
  std::string installed;              ///< a path under node_modules that shows it installed
};

/// The package's folder in the build tree, installed (a failed npm ci is a test failure).
inline std::filesystem::path installNpmPackage(const NpmPackage& p, std::initializer_list<const char*> scripts)
{
  namespace fs = std::filesystem;
  using namespace std::chrono_literals;
  const fs::path dir = p.build_dir / p.name;
  const fs::path source = p.source_dir / "tests" / p.name;
  if (!fs::exists(dir / "node_modules" / p.installed)) {
    fs::create_directories(dir);
    for (const char* f : {"package.json", "package-lock.json"}) {
      fs::copy_file(source / f, dir / f, fs::copy_options::overwrite_existing);
    }
    ChildProcess npm({p.npm, "ci", "--no-audit", "--no-fund", "--prefix", dir.string()});
    const auto status = npm.wait(300s);
    EXPECT_TRUE(status && *status == 0) << npm.output();
  }
  for (const char* f : scripts) {
    fs::copy_file(source / f, dir / f, fs::copy_options::overwrite_existing);
  }
  return dir;
}

}  // namespace quad::test
