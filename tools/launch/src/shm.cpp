// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/shm.hpp"

#include <fstream>
#include <set>
#include <system_error>

namespace quad::launch {

namespace fs = std::filesystem;

namespace {

bool isFastDdsFile(const std::string& name)
{
  return name.starts_with("fastrtps_") || name.starts_with("fast_datasharing_") ||
         name.starts_with("sem.fastrtps_");
}

/// Every file under `dir` that a process has open or mapped.
std::set<fs::path> heldFiles(const fs::path& dir)
{
  std::set<fs::path> held;
  std::error_code ec;
  for (const auto& proc : fs::directory_iterator("/proc", ec)) {
    const std::string pid = proc.path().filename().string();
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    std::error_code fd_ec;
    for (const auto& fd : fs::directory_iterator(proc.path() / "fd", fd_ec)) {
      std::error_code link_ec;
      const fs::path target = fs::read_symlink(fd.path(), link_ec);
      if (!link_ec && target.parent_path() == dir) {
        held.insert(target);
      }
    }
    std::ifstream maps(proc.path() / "maps");
    std::string line;
    while (std::getline(maps, line)) {
      const auto at = line.find(dir.string() + "/");
      if (at != std::string::npos) {
        std::string path = line.substr(at);
        if (const auto deleted = path.find(" (deleted)"); deleted != std::string::npos) {
          path.resize(deleted);
        }
        held.insert(path);
      }
    }
  }
  return held;
}

}  // namespace

std::vector<fs::path> staleSharedMemory(const fs::path& dir, std::chrono::seconds min_age)
{
  std::vector<fs::path> stale;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  std::set<fs::path> held;
  bool scanned = false;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    std::error_code time_ec;
    const auto written = fs::last_write_time(entry.path(), time_ec);
    if (!isFastDdsFile(name) || time_ec || now - written < min_age) {
      continue;
    }
    if (!scanned) {
      held = heldFiles(dir);
      scanned = true;
    }
    if (held.contains(entry.path())) {
      continue;
    }
    // A lock file ("..._el", "..._mutex") goes only with its segment.
    std::string base = name;
    for (const char* suffix : {"_el", "_mutex", "_sl"}) {
      if (base.ends_with(suffix)) {
        base.resize(base.size() - std::string(suffix).size());
      }
    }
    if (base != name && held.contains(dir / base)) {
      continue;
    }
    stale.push_back(entry.path());
  }
  return stale;
}

Cleaned cleanStaleSharedMemory(const fs::path& dir, std::chrono::seconds min_age)
{
  Cleaned cleaned;
  for (const auto& path : staleSharedMemory(dir, min_age)) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (fs::remove(path, ec) && !ec) {
      ++cleaned.files;
      cleaned.bytes += size;
    }
  }
  return cleaned;
}

}  // namespace quad::launch
