#pragma once
// A WorkFarm in one process for tests of the farm path (the CLI's MPI farm hands items to ranks): it computes
// every item in the reverse of the claim order and delivers each as its bytes, as another rank's result would
// arrive, so results must be filed by item, not by arrival. computes_only: behave like an MPI worker rank.
#include <string>
#include <vector>

#include "core/work_farm.hpp"

namespace lienewton {

class ReversedFarm final : public WorkFarm {
 public:
  explicit ReversedFarm(bool computes_only = false) : computes_only_(computes_only) {}
  bool run(const std::vector<int>& order, const std::function<std::string(int)>& compute,
           const std::function<bool(int, const std::string&)>& deliver) const override {
    for (auto item = order.rbegin(); item != order.rend(); ++item) {
      const std::string bytes = compute(*item);
      if (!computes_only_ && !deliver(*item, bytes)) break;
    }
    return !computes_only_;
  }

 private:
  bool computes_only_;
};

}  // namespace lienewton
