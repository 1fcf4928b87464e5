#pragma once
// Heap allocations made by the calling thread (malloc, hence also operator new and Eigen's dynamic matrices),
// counted by the malloc interposer in alloc_count.cpp. For "no allocation inside an SO(3) iteration", and for
// the heap a computation needs at its peak.
namespace lienewton::bench {

long thread_allocations();
// Bytes the calling thread holds on the heap, and the most it held since reset_thread_peak().
long long thread_held_bytes();
void reset_thread_peak();
long long thread_peak_bytes();

// Allocations made by f() on this thread.
template <class F>
long allocations_in(F&& f) {
  const long before = thread_allocations();
  f();
  return thread_allocations() - before;
}

// The most bytes f() held on this thread at once beyond what the thread held before it.
template <class F>
long long peak_bytes_in(F&& f) {
  const long long before = thread_held_bytes();
  reset_thread_peak();
  f();
  return thread_peak_bytes() - before;
}

}  // namespace lienewton::bench
