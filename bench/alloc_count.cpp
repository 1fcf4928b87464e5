// A malloc interposer for the benchmark binary (glibc): forwards to __libc_malloc and counts per thread. The
// counter is a plain thread_local (static TLS in the executable: no allocation, no contention between the
// sweep's worker threads). calloc/realloc/aligned variants are not counted: Eigen and operator new use malloc.
#include "bench/alloc_count.hpp"

#include <cstddef>

extern "C" void* __libc_malloc(std::size_t size);

namespace {
thread_local long allocations = 0;
}  // namespace

extern "C" void* malloc(std::size_t size) {
  ++allocations;
  return __libc_malloc(size);
}

namespace lienewton::bench {
long thread_allocations() { return allocations; }
}  // namespace lienewton::bench
