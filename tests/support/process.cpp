// SPDX-License-Identifier: BSD-3-Clause
#include "process.hpp"

#include <poll.h>

#include <algorithm>

#include "quad/common/time.hpp"

namespace quad::test {

ChildProcess::ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env)
    : child_(std::move(argv), env)
{
}

void ChildProcess::readAvailable(int timeout_ms)
{
  pollfd p{child_.outputFd(), POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) > 0) {
    child_.readOutput(output_);
  }
}

const std::string& ChildProcess::output()
{
  readAvailable(0);
  return output_;
}

bool ChildProcess::waitForOutput(const std::string& text, std::chrono::milliseconds timeout)
{
  const std::int64_t deadline = common::steadyTimeNs() + timeout.count() * 1'000'000;
  while (output().find(text) == std::string::npos) {
    const std::int64_t left_ms = (deadline - common::steadyTimeNs()) / 1'000'000;
    if (left_ms <= 0) {
      return false;
    }
    readAvailable(static_cast<int>(std::min<std::int64_t>(left_ms, 50)));
  }
  return true;
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout)
{
  const std::int64_t deadline = common::steadyTimeNs() + timeout.count() * 1'000'000;
  while (!child_.poll() && common::steadyTimeNs() < deadline) {
    readAvailable(20);  // keeps the pipe drained so the child never blocks on a full pipe
  }
  readAvailable(0);
  return child_.poll();
}

void ChildProcess::signal(int signal) { child_.signal(signal); }

}  // namespace quad::test
