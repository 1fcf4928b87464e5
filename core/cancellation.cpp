#include "cancellation.hpp"

namespace lienewton {
namespace {
thread_local const CancellationToken* t_current = nullptr;
}  // namespace

const CancellationToken* current_cancellation() { return t_current; }

CancellationScope::CancellationScope(const CancellationToken* token) : previous_(t_current) { t_current = token; }
CancellationScope::~CancellationScope() { t_current = previous_; }

}  // namespace lienewton
