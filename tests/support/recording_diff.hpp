// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Two recordings compared message by message by `quad bag diff --json`, for the tests that
/// fly a run twice and require the same messages.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "process.hpp"

namespace quad::test {

/// `quad` (the tool's path) finds `first` and `second` identical: every topic paced by sim
/// time holds the same payloads in the same order, but for the members that hold wall-clock
/// and compute times, over at least `min_topics` topics and more than `min_messages` messages.
inline void expectIdenticalRecordings(const std::string& quad, const std::filesystem::path& first,
                                      const std::filesystem::path& second, int min_topics, int min_messages)
{
  using namespace std::chrono_literals;
  ChildProcess diff({quad, "bag", "diff", first.string(), second.string(), "--json"});
  const auto status = diff.wait(120s);
  ASSERT_TRUE(status) << diff.output();
  const auto result = nlohmann::json::parse(diff.output(), nullptr, false);
  ASSERT_FALSE(result.is_discarded()) << diff.output();
  EXPECT_EQ(*status, 0) << result.dump(2);
  EXPECT_TRUE(result["identical"].get<bool>()) << result.dump(2);
  EXPECT_GE(result["topics"].get<int>(), min_topics) << result.dump(2);
  EXPECT_GT(result["equal_messages"].get<int>(), min_messages) << result.dump(2);
}

}  // namespace quad::test
