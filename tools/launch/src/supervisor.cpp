// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/supervisor.hpp"

#include <poll.h>
#include <signal.h>

#include <algorithm>
#include <thread>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "quad/common/time.hpp"

namespace quad::launch {

namespace {
std::string timestamp()
{
  const std::int64_t ns = common::wallTimeNs();
  const std::time_t seconds = static_cast<std::time_t>(ns / common::kNanosecondsPerSecond);
  return fmt::format("{:%Y-%m-%d %H:%M:%S}.{:03d}", fmt::localtime(seconds),
                     static_cast<int>(ns / 1'000'000 % 1000));
}
}  // namespace

Supervisor::Supervisor(std::filesystem::path log_dir, std::FILE* console, bool echo)
    : log_dir_(std::move(log_dir)), console_(console), echo_(echo)
{
  std::filesystem::create_directories(log_dir_);
  launch_log_.open(log_dir_ / "launch.log", std::ios::app);
}

void Supervisor::say(const std::string& line)
{
  if (console_ != nullptr) {
    std::fprintf(console_, "%-*s | %s\n", static_cast<int>(width_), "launch", line.c_str());
    std::fflush(console_);
  }
  launch_log_ << timestamp() << " " << line << '\n' << std::flush;
}

void Supervisor::start(const std::string& name, const std::vector<std::string>& argv,
                       const std::map<std::string, std::string>& env)
{
  width_ = std::max(width_, name.size());
  Child& child = children_[name];
  if (child.process && !child.exited) {
    throw std::logic_error("Supervisor: " + name + " is already running");
  }
  if (!child.log.is_open()) {
    child.log.open(log_dir_ / (name + ".log"), std::ios::app);
  }
  std::string command;
  for (const auto& a : argv) {
    command += (command.empty() ? "" : " ") + a;
  }
  child.process = std::make_unique<process::Spawned>(argv, env);
  child.exited = false;
  child.eof = false;
  child.partial.clear();
  child.log << "--- " << timestamp() << " started, pid "
            << child.process->pid() << ": " << command << '\n' << std::flush;
}

bool Supervisor::running(const std::string& name) const
{
  const auto it = children_.find(name);
  return it != children_.end() && it->second.process && !it->second.exited;
}

std::optional<pid_t> Supervisor::pid(const std::string& name) const
{
  if (!running(name)) {
    return std::nullopt;
  }
  return children_.at(name).process->pid();
}

void Supervisor::forward(const std::string& name, Child& child, bool flush_partial)
{
  if (!child.eof && !child.process->readOutput(child.partial)) {
    child.eof = true;
  }
  std::size_t start = 0;
  while (true) {
    const auto newline = child.partial.find('\n', start);
    if (newline == std::string::npos) {
      break;
    }
    std::string line = child.partial.substr(start, newline - start);
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();  // from a remote terminal (ssh -tt)
    }
    child.log << line << '\n';
    if (console_ != nullptr && echo_) {
      std::fprintf(console_, "%-*s | %s\n", static_cast<int>(width_), name.c_str(), line.c_str());
    }
    start = newline + 1;
  }
  child.partial.erase(0, start);
  if (flush_partial && !child.partial.empty()) {
    child.log << child.partial << '\n';
    if (console_ != nullptr && echo_) {
      std::fprintf(console_, "%-*s | %s\n", static_cast<int>(width_), name.c_str(), child.partial.c_str());
    }
    child.partial.clear();
  }
  child.log.flush();
  if (console_ != nullptr) {
    std::fflush(console_);
  }
}

std::vector<Supervisor::Exit> Supervisor::pump(int timeout_ms)
{
  // Wakes on output or a closed pipe. A closed pipe is polled no more (it would wake us at
  // once for ever); its process's exit is then caught within 20 ms.
  std::vector<pollfd> fds;
  bool closing = false;
  for (auto& [name, child] : children_) {
    if (!child.exited && !child.eof) {
      fds.push_back({child.process->outputFd(), POLLIN, 0});
    }
    closing = closing || (!child.exited && child.eof);
  }
  const int wait_ms = closing ? std::min(timeout_ms, 20) : std::min(timeout_ms, 100);
  if (fds.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
  } else {
    ::poll(fds.data(), fds.size(), wait_ms);
  }
  std::vector<Exit> exits;
  for (auto& [name, child] : children_) {
    if (child.exited) {
      continue;
    }
    const auto status = child.process->poll();
    forward(name, child, status.has_value());
    if (status) {
      ended(child);
      child.log << "--- " << timestamp() << " ended: "
                << process::describeStatus(*status) << '\n' << std::flush;
      exits.push_back({name, *status});
    }
  }
  return exits;
}

void Supervisor::ended(Child& child)
{
  child.exited = true;
  if (const auto cpu = child.process->cpuSeconds()) {
    child.cpu_s = child.cpu_s.value_or(0.0) + *cpu;
  }
  if (const auto rss = child.process->maxResidentMiB()) {
    child.max_rss_mib = std::max(child.max_rss_mib.value_or(0.0), *rss);
  }
  if (const auto w = child.process->waits()) {
    child.waits = child.waits.value_or(0) + *w;
  }
}

std::optional<double> Supervisor::cpuSeconds(const std::string& name) const
{
  const auto it = children_.find(name);
  return it == children_.end() ? std::nullopt : it->second.cpu_s;
}

std::optional<double> Supervisor::maxResidentMiB(const std::string& name) const
{
  const auto it = children_.find(name);
  return it == children_.end() ? std::nullopt : it->second.max_rss_mib;
}

std::optional<std::uint64_t> Supervisor::waits(const std::string& name) const
{
  const auto it = children_.find(name);
  return it == children_.end() ? std::nullopt : it->second.waits;
}

bool Supervisor::signal(const std::string& name, int signal)
{
  if (!running(name)) {
    return false;
  }
  children_.at(name).process->signal(signal);
  return true;
}

std::optional<int> Supervisor::stop(const std::string& name, double grace_s)
{
  if (!running(name)) {
    return std::nullopt;
  }
  Child& child = children_.at(name);
  child.process->signal(SIGTERM);
  child.process->signal(SIGCONT);  // a paused process must run to stop
  const std::int64_t deadline = common::steadyTimeNs() + common::toNanoseconds(grace_s);
  bool killed = false;
  while (true) {
    const auto status = child.process->poll();
    forward(name, child, status.has_value());
    if (status) {
      ended(child);
      child.log << "--- " << timestamp() << " stopped: "
                << process::describeStatus(*status) << '\n' << std::flush;
      return status;
    }
    if (!killed && common::steadyTimeNs() >= deadline) {
      say(fmt::format("{} did not stop within {:.1f} s of SIGTERM: SIGKILL", name, grace_s));
      child.process->signal(SIGKILL);
      killed = true;
    }
    if (child.eof) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    } else {
      pollfd p{child.process->outputFd(), POLLIN, 0};
      ::poll(&p, 1, 20);
    }
  }
}

std::string moduleTunables(const std::string& given)
{
  if (given.find("glibc.malloc.hugetlb") != std::string::npos) {
    return given;
  }
  return given.empty() ? "glibc.malloc.hugetlb=1" : given + ":glibc.malloc.hugetlb=1";
}

}  // namespace quad::launch
