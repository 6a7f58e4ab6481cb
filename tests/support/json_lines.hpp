// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Samples printed by `quad topic echo --json`, one JSON object a line, as a test reads them.

#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace quad::test {

/// Every line of `output` that parses as JSON, in order; other lines are skipped.
inline std::vector<nlohmann::json> jsonLines(const std::string& output)
{
  std::vector<nlohmann::json> out;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    auto sample = nlohmann::json::parse(line, nullptr, false);
    if (!sample.is_discarded()) {
      out.push_back(std::move(sample));
    }
  }
  return out;
}

/// Whether the newest sample in `output` has the number `key` at `value` or past it: an echo
/// may match its writer after the first samples went out, so it waits for "the n-th or later".
inline bool newestReached(const std::string& output, const char* key, std::int64_t value)
{
  const auto samples = jsonLines(output);
  return !samples.empty() && samples.back().contains(key) && samples.back()[key].get<std::int64_t>() >= value;
}

}  // namespace quad::test
