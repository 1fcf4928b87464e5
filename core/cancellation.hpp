#pragma once
// One cancellation token for long work: a deadline, a shutdown flag and a client-gone flag, polled by every
// long loop of the core (each solver iteration, integrate steps and their stage solves, the reference
// solution, work-precision runs, sweep cells) and of the renderer, so that work stops within about one
// iteration and its caller gets its slot back at once.
// The token is ambient: a CancellationScope makes it the current thread's token, parallel_for hands its
// caller's token to its workers, and loops ask cancellation_requested(), so no request type or callback
// signature has to carry it. Without a scope nothing is ever cancelled.
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>

namespace lienewton {

enum class CancelReason { none, deadline, shutdown, client_gone };

class CancellationToken {
 public:
  using Clock = std::chrono::steady_clock;
  CancellationToken() = default;  // never cancelled
  // budget_seconds: the limit the deadline came from, for the message when it passes.
  CancellationToken(Clock::time_point deadline, const std::atomic<bool>* shutdown,
                    std::shared_ptr<const std::atomic<bool>> client_gone, double budget_seconds = 0)
      : deadline_(deadline), shutdown_(shutdown), client_gone_(std::move(client_gone)),
        budget_seconds_(budget_seconds) {}

  // Thread-safe; once cancelled, stays cancelled with the first reason seen.
  bool cancelled() const {
    if (reason_.load(std::memory_order_relaxed) != CancelReason::none) return true;
    if (shutdown_ && shutdown_->load(std::memory_order_relaxed)) return cancel(CancelReason::shutdown);
    if (client_gone_ && client_gone_->load(std::memory_order_relaxed)) return cancel(CancelReason::client_gone);
    if (Clock::now() >= deadline_) return cancel(CancelReason::deadline);
    return false;
  }
  // Cancels from outside the flags (a stream write failed: the client is gone). Returns true.
  bool cancel(CancelReason reason) const {
    CancelReason none = CancelReason::none;
    reason_.compare_exchange_strong(none, reason);
    return true;
  }
  CancelReason reason() const { return reason_.load(); }
  double budget_seconds() const { return budget_seconds_; }

 private:
  Clock::time_point deadline_ = Clock::time_point::max();
  const std::atomic<bool>* shutdown_ = nullptr;
  std::shared_ptr<const std::atomic<bool>> client_gone_;
  double budget_seconds_ = 0;
  mutable std::atomic<CancelReason> reason_{CancelReason::none};
};

// The current thread's token, or nullptr.
const CancellationToken* current_cancellation();
// True when the current thread's token is cancelled.
inline bool cancellation_requested() {
  const CancellationToken* token = current_cancellation();
  return token && token->cancelled();
}

// Makes `token` the current thread's token for the scope's life (nullptr: none); restores the previous one.
class CancellationScope {
 public:
  explicit CancellationScope(const CancellationToken* token);
  ~CancellationScope();
  CancellationScope(const CancellationScope&) = delete;
  CancellationScope& operator=(const CancellationScope&) = delete;

 private:
  const CancellationToken* previous_;
};

// Thrown by loops that have no status to return (the reference solution, work-precision timing) when the
// current token is cancelled; solvers return Status::cancelled instead.
struct Cancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};
inline void throw_if_cancelled() {
  if (cancellation_requested()) throw Cancelled{};
}

}  // namespace lienewton
