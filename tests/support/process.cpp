#include "process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "quad/common/time.hpp"

extern char** environ;

namespace quad::test {

ChildProcess::ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env)
{
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

  pid_ = fork();
  if (pid_ < 0) {
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid_ == 0) {
    setpgid(0, 0);  // its own process group: whatever it starts is stopped with it
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    // Signals blocked by the test (none normally) must not be inherited blocked.
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    execve(args[0], args.data(), envp.data());
    _exit(127);
  }
  close(fds[1]);
  out_fd_ = fds[0];
}

ChildProcess::~ChildProcess()
{
  if (!status_) {
    kill(-pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  } else {
    kill(-pid_, SIGKILL);  // grandchildren left behind by a child that exited
  }
  close(out_fd_);
}

void ChildProcess::readAvailable(int timeout_ms)
{
  pollfd p{out_fd_, POLLIN, 0};
  while (poll(&p, 1, timeout_ms) > 0 && (p.revents & (POLLIN | POLLHUP)) != 0) {
    char buffer[4096];
    const ssize_t n = read(out_fd_, buffer, sizeof(buffer));
    if (n <= 0) {
      break;
    }
    output_.append(buffer, static_cast<std::size_t>(n));
    timeout_ms = 0;
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
  while (!status_) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      break;
    }
    if (common::steadyTimeNs() >= deadline) {
      break;
    }
    readAvailable(20);  // keeps the pipe drained so the child never blocks on a full pipe
  }
  readAvailable(0);
  return status_;
}

void ChildProcess::signal(int signal) { kill(-pid_, signal); }

}  // namespace quad::test
