#pragma once
// An operator set column by column, in order i = 0, 1, ..., by a caller that produces its columns in passes (a
// user's dg_y formed a few directions at a time): a sparse operator keeps the columns' nonzeros only, as
// operator_from_columns does.
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "lie_group.hpp"

namespace lienewton {

template <class G>
class OperatorColumns {
 public:
  explicit OperatorColumns(const G& g) : dim_(g.dim()) {
    if constexpr (!kSparseOperator<G>) m_ = zero_operator(g);
  }
  void set(int i, const typename G::Vector& c) {
    if constexpr (kSparseOperator<G>) {
      for (Eigen::Index r = 0; r < c.size(); ++r)
        if (c[r] != 0.0) entries_.emplace_back(static_cast<int>(r), i, c[r]);
    } else {
      m_.col(i) = c;
    }
  }
  typename G::Operator take() {
    if constexpr (kSparseOperator<G>) {
      m_.resize(dim_, dim_);
      m_.setFromTriplets(entries_.begin(), entries_.end());
      entries_ = {};
    }
    return std::move(m_);
  }

 private:
  int dim_;
  typename G::Operator m_;
  std::vector<Eigen::Triplet<double>> entries_;  // a sparse operator's nonzeros until take()
};

}  // namespace lienewton
