#include "program_cache.hpp"

namespace lienewton {
namespace {

// Eigen's == asserts on different sizes: compare sizes first.
bool same(const user_field::Parameters& a, const user_field::Parameters& b) {
  if (a.size() != b.size()) return false;
  for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
    if (i->first != j->first || i->second.rows() != j->second.rows() || i->second.cols() != j->second.cols() ||
        i->second != j->second)
      return false;
  return true;
}

}  // namespace

std::shared_ptr<const user_field::Program> ProgramCache::get(const std::string& g, int size,
                                                             const user_field::Parameters& parameters) {
  // Compiled under the lock: threads that need the same program wait for it instead of compiling it again.
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Entry& e : entries_)
    if (e.size == size && e.g == g && same(e.parameters, parameters)) return e.program;
  auto program = user_field::compile(g, size, parameters);
  compilations_.fetch_add(1);
  entries_.push_back({g, size, parameters, program});
  return program;
}

}  // namespace lienewton
