// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Files for tests: an empty scratch folder of their own, and a whole file as a string.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace quad::test {

/// An empty folder under the system's temporary one, named after `name` and this process.
inline std::filesystem::path scratchDir(const std::string& name)
{
  const auto dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The file's contents; empty when it cannot be read.
inline std::string readFile(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace quad::test
