// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Fast DDS leaves its shared-memory segments in /dev/shm when a process is killed, and
/// `fastdds shm clean` misses some (data-sharing segments, port files). The launcher removes
/// every Fast DDS file there that no running process has open or mapped.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace quad::launch {

/// Fast DDS files in `dir` that no process holds (no /proc/<pid>/fd link, no mapping in
/// /proc/<pid>/maps) and that are older than `min_age` (a segment just created may not be
/// mapped yet).
std::vector<std::filesystem::path> staleSharedMemory(const std::filesystem::path& dir = "/dev/shm",
                                                      std::chrono::seconds min_age = std::chrono::seconds(5));

/// Removes them; returns how many files and bytes went.
struct Cleaned {
  int files = 0;
  std::uintmax_t bytes = 0;
};
Cleaned cleanStaleSharedMemory(const std::filesystem::path& dir = "/dev/shm",
                               std::chrono::seconds min_age = std::chrono::seconds(5));

}  // namespace quad::launch
