#pragma once
// CPU time of the calling thread, so that timings of concurrent runs do not include each other's work.
#include <ctime>

namespace lienewton {
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace lienewton
