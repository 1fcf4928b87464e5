// A malloc interposer for the benchmark binary (glibc): forwards to __libc_malloc and friends and counts per
// thread: allocations (malloc only: Eigen and operator new use it), and the bytes held (malloc, calloc, realloc
// and free, by malloc_usable_size) with their peak. The counters are plain thread_locals (static TLS in the
// executable: no allocation, no contention between the sweep's worker threads). A block freed by another thread
// than the one that allocated it moves bytes between the two threads' counts: measure single-threaded work.
#include "bench/alloc_count.hpp"

#include <malloc.h>

#include <algorithm>
#include <cstddef>

extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_calloc(std::size_t count, std::size_t size);
extern "C" void* __libc_realloc(void* p, std::size_t size);
extern "C" void __libc_free(void* p);

namespace {
thread_local long allocations = 0;
thread_local long long held = 0, peak = 0;

void* taken(void* p) {
  if (p) peak = std::max(peak, held += static_cast<long long>(malloc_usable_size(p)));
  return p;
}
void given_back(void* p) {
  if (p) held -= static_cast<long long>(malloc_usable_size(p));
}
}  // namespace

extern "C" void* malloc(std::size_t size) {
  ++allocations;
  return taken(__libc_malloc(size));
}
extern "C" void* calloc(std::size_t count, std::size_t size) { return taken(__libc_calloc(count, size)); }
extern "C" void* realloc(void* p, std::size_t size) {
  const long long before = p ? static_cast<long long>(malloc_usable_size(p)) : 0;
  void* moved = __libc_realloc(p, size);
  if (moved || size == 0) held -= before;  // a failed realloc keeps p
  return taken(moved);
}
extern "C" void free(void* p) {
  given_back(p);
  __libc_free(p);
}

namespace lienewton::bench {
long thread_allocations() { return allocations; }
long long thread_held_bytes() { return held; }
void reset_thread_peak() { peak = held; }
long long thread_peak_bytes() { return peak; }
}  // namespace lienewton::bench
