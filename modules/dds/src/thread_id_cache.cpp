// SPDX-License-Identifier: BSD-3-Clause
// The calling thread's id, asked of the kernel once per thread. Fast DDS 2.9.1 as Debian 12
// builds it keeps its debug assertions (no NDEBUG), and those of a reliable reader's writer
// proxy ask for the thread's id through syscall(SYS_gettid) several times for every sample
// taken in: about 86 system calls a lockstep round of the demo, composed, a sixth of the fast
// loop's time (docs/dds.md). Every quad executable links this definition of syscall() in
// front of the C library's (quad_dds asks the linker for it: LINKER:--undefined=syscall); it
// answers SYS_gettid from a per-thread cache and hands every other call to the C library's.
#include <dlfcn.h>
#include <pthread.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdarg>

namespace {

thread_local long cached_tid = 0;  // 0: not asked yet in this thread

using SyscallFn = long (*)(long, ...);

SyscallFn libcSyscall()
{
  static const auto fn = reinterpret_cast<SyscallFn>(dlsym(RTLD_NEXT, "syscall"));
  return fn;
}

// A child of fork() runs on as a copy of the forking thread, with its cache: it asks again.
[[maybe_unused]] const int kForgetInChild = pthread_atfork(nullptr, nullptr, [] { cached_tid = 0; });

}  // namespace

extern "C" long syscall(long number, ...)  // NOLINT(cert-dcl50-cpp): the C library's signature
{
  if (number == SYS_gettid) {
    if (cached_tid == 0) {
      cached_tid = gettid();
    }
    return cached_tid;
  }
  // Six argument words, as the kernel takes them (and the C library's syscall() reads them):
  // those the call does not use are ignored.
  va_list args;
  va_start(args, number);
  long a[6];
  for (long& word : a) {
    word = va_arg(args, long);
  }
  va_end(args);
  return libcSyscall()(number, a[0], a[1], a[2], a[3], a[4], a[5]);
}
