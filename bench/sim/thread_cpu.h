// Thread-CPU time for the plant benchmarks that time a loop themselves.
#ifndef KESTREL_BENCH_THREAD_CPU_H
#define KESTREL_BENCH_THREAD_CPU_H

#include <ctime>

// [s] CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID).
inline double thread_cpu_seconds()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

#endif  // KESTREL_BENCH_THREAD_CPU_H
