// SPDX-License-Identifier: BSD-3-Clause
#include "quad/process/spawn.hpp"

#include "quad/common/time.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace quad::process {

Spawned::Spawned(std::vector<std::string> argv, const std::map<std::string, std::string>& env)
{
  if (argv.empty()) {
    throw std::invalid_argument("Spawned: no program");
  }
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  }
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    if (!env.contains(entry.substr(0, entry.find('=')))) {
      env_strings.push_back(entry);
    }
  }
  for (const auto& [key, value] : env) {
    env_strings.push_back(key + "=" + value);
  }
  std::vector<char*> args;
  for (auto& a : argv) {
    args.push_back(a.data());
  }
  args.push_back(nullptr);
  std::vector<char*> envp;
  for (auto& e : env_strings) {
    envp.push_back(e.data());
  }
  envp.push_back(nullptr);

  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid_ == 0) {
    setpgid(0, 0);  // its own process group: whatever it starts is stopped with it
    // Stopped with its parent, even one killed outright: no orphan keeps running.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) {
      _exit(127);  // the parent died before the line above
    }
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    // Signals the parent blocks or ignores must not stay so in the child.
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    ::signal(SIGPIPE, SIG_DFL);
    execvpe(args[0], args.data(), envp.data());
    const std::string why = std::string(args[0]) + ": cannot execute: " + std::strerror(errno) + "\n";
    (void)!write(STDERR_FILENO, why.data(), why.size());
    _exit(127);
  }
  setpgid(pid_, pid_);  // also from here, so a signal sent right away reaches the group
  close(fds[1]);
  out_fd_ = fds[0];
  fcntl(out_fd_, F_SETFL, fcntl(out_fd_, F_GETFL) | O_NONBLOCK);
}

Spawned::~Spawned()
{
  kill(-pid_, SIGKILL);  // also grandchildren left behind by a child that exited
  if (!status_) {
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  close(out_fd_);
}

bool Spawned::readOutput(std::string& out)
{
  char buffer[8192];
  while (true) {
    const ssize_t n = read(out_fd_, buffer, sizeof(buffer));
    if (n > 0) {
      out.append(buffer, static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0) {
      return false;
    }
    return errno == EAGAIN || errno == EINTR;
  }
}

std::optional<int> Spawned::poll()
{
  if (!status_) {
    int status = 0;
    rusage usage{};
    if (wait4(pid_, &status, WNOHANG, &usage) == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      cpu_s_ = common::cpuSeconds(usage);
      max_rss_mib_ = common::maxResidentMiB(usage);
      waits_ = common::waits(usage);
    }
  }
  return status_;
}

void Spawned::signal(int signal) const { kill(-pid_, signal); }

std::string describeStatus(int status)
{
  if (status > 128 && status < 128 + 65) {
    const char* name = sigabbrev_np(status - 128);
    return std::string("killed by SIG") + (name != nullptr ? name : std::to_string(status - 128));
  }
  return "exit " + std::to_string(status);
}

}  // namespace quad::process
