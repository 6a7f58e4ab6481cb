// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// One mission flown by `quad launch` for a test: its exit status and summary.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "scratch.hpp"

namespace quad::test {

struct Flight {
  int exit_status = -1;
  nlohmann::json summary;  ///< not an object when the run wrote none
  std::string output;      ///< for failure messages only
};

/// Runs `quad launch` (the program `quad`) with `args` and a summary, log folder, quiet output
/// and a 300 s wall timeout of its own, in a scratch folder named after `name`; the folder is
/// removed unless the test has failed.
inline Flight flyMission(const std::string& quad, std::vector<std::string> args, const std::string& name)
{
  using namespace std::chrono_literals;
  const std::filesystem::path dir = scratchDir(name);
  args.insert(args.begin(), {quad, "launch"});
  for (const std::string& a : {std::string("--quiet"), std::string("--wall-timeout"), std::string("300"),
                               std::string("--summary"), (dir / "summary.json").string(), std::string("--log-dir"),
                               (dir / "run").string()}) {
    args.push_back(a);
  }
  ChildProcess launch(args);
  Flight f;
  const auto status = launch.wait(330s);
  f.output = launch.output();
  if (!status) {
    ADD_FAILURE() << name << ": quad launch did not end within 330 s\n" << f.output;
    return f;
  }
  f.exit_status = *status;
  f.summary = nlohmann::json::parse(readFile(dir / "summary.json"), nullptr, false);
  if (!::testing::Test::HasFailure()) {
    std::filesystem::remove_all(dir);
  }
  return f;
}

}  // namespace quad::test
