#pragma once
// Why long work should stop: the request's deadline passed, the server is shutting down, or the client left.
// The core's callbacks return !should_stop(), so a solve or sweep ends within one iteration or cell.
#include <atomic>
#include <chrono>

namespace lienewton::service {

enum class StopReason { none, deadline, shutdown, client_gone };

class StopCheck {
 public:
  using Clock = std::chrono::steady_clock;
  // budget_seconds: the limit the deadline came from, for the message when it passes.
  StopCheck(Clock::time_point deadline, const std::atomic<bool>& abort, double budget_seconds = 0)
      : deadline_(deadline), abort_(abort), budget_seconds_(budget_seconds) {}

  bool should_stop() {
    if (reason_ != StopReason::none) return true;
    if (abort_.load()) reason_ = StopReason::shutdown;
    else if (Clock::now() >= deadline_) reason_ = StopReason::deadline;
    return reason_ != StopReason::none;
  }
  void client_gone() { reason_ = StopReason::client_gone; }
  StopReason reason() const { return reason_; }
  double budget_seconds() const { return budget_seconds_; }

 private:
  Clock::time_point deadline_;
  const std::atomic<bool>& abort_;
  double budget_seconds_;
  StopReason reason_ = StopReason::none;
};

}  // namespace lienewton::service
