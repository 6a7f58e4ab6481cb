// SPDX-License-Identifier: BSD-3-Clause
// quad's syscall() (src/thread_id_cache.cpp), linked into every executable in front of the
// C library's: SYS_gettid answered per thread as the kernel would, every other call passed on.
#include <gtest/gtest.h>

#include <dlfcn.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <set>
#include <thread>
#include <vector>

namespace {

TEST(ThreadIdCache, IsTheSyscallEveryLibraryOfTheProcessCalls)
{
  // Fast DDS's calls resolve through the process's global scope: to the executable's export.
  void* libc = dlopen("libc.so.6", RTLD_NOW | RTLD_NOLOAD);
  ASSERT_NE(libc, nullptr);
  void* global = dlsym(RTLD_DEFAULT, "syscall");
  ASSERT_NE(global, nullptr);
  EXPECT_NE(global, dlsym(libc, "syscall"));
  dlclose(libc);
}

TEST(ThreadIdCache, EachThreadGetsItsOwnIdAsTheKernelGivesIt)
{
  EXPECT_EQ(syscall(SYS_gettid), gettid());
  EXPECT_EQ(syscall(SYS_gettid), gettid());  // asked again: the same
  std::vector<long> ids(8);
  std::vector<long> kernel(8);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    threads.emplace_back([&, i] {
      ids[i] = syscall(SYS_gettid);
      kernel[i] = gettid();
    });
  }
  for (auto& t : threads) {
    t.join();
  }
  EXPECT_EQ(ids, kernel);
  std::set<long> distinct(ids.begin(), ids.end());
  distinct.insert(gettid());
  EXPECT_EQ(distinct.size(), ids.size() + 1);
}

TEST(ThreadIdCache, AForkedChildAsksAgain)
{
  ASSERT_EQ(syscall(SYS_gettid), gettid());  // cached in this thread
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    _exit(syscall(SYS_gettid) == getpid() ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(ThreadIdCache, OtherCallsReachTheKernelWithTheirArguments)
{
  EXPECT_EQ(syscall(SYS_getpid), getpid());
  // write(2) through syscall(): three arguments, the count returned
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const char text[] = "quad";
  EXPECT_EQ(syscall(SYS_write, fds[1], text, 4), 4);
  char back[4] = {};
  EXPECT_EQ(read(fds[0], back, 4), 4);
  EXPECT_EQ(std::string(back, 4), "quad");
  close(fds[0]);
  close(fds[1]);
  // an error comes back as -1 with errno
  errno = 0;
  EXPECT_EQ(syscall(SYS_close, -1), -1);
  EXPECT_EQ(errno, EBADF);
}

}  // namespace
