#pragma once
// Runs body(i) for i in [0, count) on `threads` worker threads (0: all cores). Items are claimed from an
// atomic counter, so results written to slot i do not depend on the thread count or the schedule.
// body returns false to stop the remaining items (cancellation).
#include <functional>

namespace lienewton {
int resolve_thread_count(int requested);
void parallel_for(int count, int threads, const std::function<bool(int)>& body);
}  // namespace lienewton
