#include "server/cli/progress_line.hpp"

#include <cstdio>

namespace lienewton::cli {

ProgressLine::ProgressLine(std::string what, std::string unit, std::size_t total, bool on)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), on_(on), start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() {
  if (drawn_) std::fputs("\r\x1b[K", stderr);  // the answer follows on stdout, not after a stale line
}

void ProgressLine::step() {
  if (!on_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::seconds(1) && done_ != total_) return;
  last_ = now;
  drawn_ = true;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  if (total_ > 0)
    std::fprintf(stderr, "\rlienewton %s: %zu of %zu %s, %.1f s\x1b[K", what_.c_str(), done_, total_, unit_.c_str(),
                 seconds);
  else
    std::fprintf(stderr, "\rlienewton %s: %zu %s, %.1f s\x1b[K", what_.c_str(), done_, unit_.c_str(), seconds);
  std::fflush(stderr);
}

}  // namespace lienewton::cli
