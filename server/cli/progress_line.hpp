#pragma once
// How far a long command has got, on one line of stderr redrawn in place: at the first item and then at most once a
// second, cleared at the end. Only for a person watching: off unless stderr is a terminal, and with --quiet.
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace lienewton::cli {

class ProgressLine {
 public:
  // what: "sweep", "basins", ...; unit: "cells", "rows", ...; total: how many there will be (0: not known).
  ProgressLine(std::string what, std::string unit, std::size_t total, bool on);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // One more item done (from any thread).
  void step();

 private:
  std::string what_, unit_;
  std::size_t total_, done_ = 0;
  bool on_, drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
  std::mutex mutex_;
};

}  // namespace lienewton::cli
