#pragma once
// Users' programs compiled once per request and matrix size. A request's ProblemSpec and its copies (a sweep's
// dimensions and cells, the validation and the run) share one cache, so a program is compiled once for each n
// and then read, never written, by every thread (each keeps its own workspace).
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "user_field/program.hpp"

namespace lienewton {

class ProgramCache {
 public:
  // g with `parameters` compiled for y of size `size` x `size`: on first use, then the same program. Throws
  // RequestError as user_field::compile does (and caches nothing then).
  std::shared_ptr<const user_field::Program> get(const std::string& g, int size, const user_field::Parameters& parameters);

  // Programs compiled through any cache in this process: tests count them per request.
  static std::uint64_t compilations() { return compilations_.load(); }

 private:
  struct Entry {
    std::string g;
    int size;
    user_field::Parameters parameters;
    std::shared_ptr<const user_field::Program> program;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
  static inline std::atomic<std::uint64_t> compilations_{0};
};

}  // namespace lienewton
