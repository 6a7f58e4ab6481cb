// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A test's npm package (tests/<name>/: package.json, package-lock.json and its scripts),
/// installed with `npm ci` into the build tree once and its scripts refreshed every time.
/// Tests of one package run side by side: one installs while the others wait (a lock file),
/// or two `npm ci` would unpack into one node_modules at once.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
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

/// An exclusive lock on a file, held while it lives (flock: released if the process dies).
class FileLock {
public:
  explicit FileLock(const std::filesystem::path& file) : fd_(::open(file.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644))
  {
    EXPECT_GE(fd_, 0) << "cannot open " << file;
    if (fd_ >= 0) {
      while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
      }
    }
  }
  ~FileLock()
  {
    if (fd_ >= 0) {
      ::close(fd_);  // releases the lock
    }
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

private:
  int fd_;
};

/// The package's folder in the build tree, installed (a failed npm ci is a test failure).
inline std::filesystem::path installNpmPackage(const NpmPackage& p, std::initializer_list<const char*> scripts)
{
  namespace fs = std::filesystem;
  using namespace std::chrono_literals;
  const fs::path dir = p.build_dir / p.name;
  const fs::path source = p.source_dir / "tests" / p.name;
  fs::create_directories(p.build_dir);
  const FileLock installing(p.build_dir / (p.name + ".install.lock"));
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
