// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
//
// LD_PRELOAD shim for scripts/tsan_node, never linked into the package. Debian 12's
// ThreadSanitizer runtimes (GCC 12's libtsan, clang 14's) do not intercept
// pthread_mutex_clocklock, which libstdc++ uses for std::timed_mutex::try_lock_for (the node's
// inspect_mutex_, inspection_action.cpp). TSan then misses that lock: it reports the unlock as
// "unlock of an unlocked mutex" and everything done under the lock as racing with the other
// holders. (The interceptor exists from LLVM 18 on: llvm-project issue 62623.) This forwards the
// call to pthread_mutex_timedlock, which TSan does intercept, with the deadline moved to
// CLOCK_REALTIME: the same lock, now visible to TSan.
#define _GNU_SOURCE
#include <errno.h>
#include <pthread.h>
#include <time.h>

int pthread_mutex_clocklock(pthread_mutex_t* mutex,
                            clockid_t clock,
                            const struct timespec* abstime) {
  if (clock == CLOCK_REALTIME) {
    return pthread_mutex_timedlock(mutex, abstime);
  }
  if (clock != CLOCK_MONOTONIC) {
    return EINVAL;
  }
  struct timespec now_clock;
  struct timespec now_real;
  clock_gettime(CLOCK_MONOTONIC, &now_clock);
  clock_gettime(CLOCK_REALTIME, &now_real);
  long long ns = (long long)(abstime->tv_sec - now_clock.tv_sec) * 1000000000LL +
                 (abstime->tv_nsec - now_clock.tv_nsec) + now_real.tv_nsec;
  struct timespec deadline;
  deadline.tv_sec = now_real.tv_sec + (time_t)(ns / 1000000000LL);
  deadline.tv_nsec = (long)(ns % 1000000000LL);
  if (deadline.tv_nsec < 0) {
    deadline.tv_nsec += 1000000000L;
    deadline.tv_sec -= 1;
  }
  return pthread_mutex_timedlock(mutex, &deadline);
}
