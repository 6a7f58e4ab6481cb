// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A command line as one string, for comparing the commands the launcher would run.

#include <string>
#include <vector>

namespace quad::launch::test {

inline std::string joined(const std::vector<std::string>& argv)
{
  std::string out;
  for (const auto& a : argv) {
    out += (out.empty() ? "" : " ") + a;
  }
  return out;
}

}  // namespace quad::launch::test
