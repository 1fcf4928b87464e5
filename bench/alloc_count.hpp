#pragma once
// Heap allocations made by the calling thread (malloc, hence also operator new and Eigen's dynamic matrices),
// counted by the malloc interposer in alloc_count.cpp. For "no allocation inside an SO(3) iteration".
namespace lienewton::bench {

long thread_allocations();

// Allocations made by f() on this thread.
template <class F>
long allocations_in(F&& f) {
  const long before = thread_allocations();
  f();
  return thread_allocations() - before;
}

}  // namespace lienewton::bench
