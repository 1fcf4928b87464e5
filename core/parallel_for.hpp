#pragma once
// Runs body(i) for i in [0, count) on `threads` worker threads (0: all cores). Items are claimed from an
// atomic counter, so results written to slot i do not depend on the thread count or the schedule.
// body returns false to stop the remaining items (cancellation).
// `order`, when given (a permutation of [0, count)), is the order in which items are claimed: callers put the
// most expensive items first so that no thread is left with one long item at the end (dynamic longest-first
// scheduling). Each body(i) writes its own slot, so the results stay the same for any order or thread count.
#include <functional>
#include <vector>

namespace lienewton {
int resolve_thread_count(int requested);
void parallel_for(int count, int threads, const std::function<bool(int)>& body, const std::vector<int>& order = {});
}  // namespace lienewton
