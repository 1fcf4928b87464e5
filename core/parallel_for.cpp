#include "parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cancellation.hpp"

namespace lienewton {

int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_for(int count, int threads, const std::function<bool(int)>& body, const std::vector<int>& order) {
  if (!order.empty() && static_cast<int>(order.size()) != count)
    throw std::invalid_argument("parallel_for: order must list every item once");
  std::atomic<int> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const CancellationToken* token = current_cancellation();
  auto worker = [&] {
    const CancellationScope scope(token);  // the caller's token, in every worker
    for (int k; !stop.load() && (k = next.fetch_add(1)) < count;) {
      try {
        if (!body(order.empty() ? k : order[static_cast<std::size_t>(k)])) stop = true;
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
      }
    }
  };
  const int n = std::min(resolve_thread_count(threads), std::max(count, 1));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace lienewton
