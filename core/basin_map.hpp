#pragma once
// The basin map of any equation f(y) = 0 on a group G (basins.hpp builds the implicit Euler one of a request):
// every pixel's solve, and the classification of rows in order. Tests use it with equations whose roots are
// known.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numeric>

#include "core/basins.hpp"
#include "core/byte_buffer.hpp"
#include "core/cancellation.hpp"
#include "core/parallel_for.hpp"
#include "core/solvers/run_method.hpp"

namespace lienewton {

// The plane of starts and what runs from each: y_0 = z exp(a b1 + b b2) over the grid of basin_axis(size, radius).
struct BasinPlane {
  Eigen::VectorXd b1, b2;  // unit directions, algebra coordinates
  int size = kDefaultBasinSize;
  std::optional<double> radius;  // r; absent: G's log radius
  std::vector<Method> methods;
  SolverOptions solver;  // basin_map() turns off per-iterate timing and iterates
  int threads = 0;
  std::optional<Shard> shard;  // only the rows basin_shard_rows(size, shard)
};

// Whether converged ys a and b are one root: ||log(a^-1 b)|| < kRootDistance. ||I - R||_F / sqrt(2) <= ||log R||
// (chord against arc, in the coordinate norm), so ys farther apart than that in Frobenius norm need no log.
template <LieGroup G>
bool same_root(const G& group, const typename G::Element& a, const typename G::Element& b) {
  if ((b - a).norm() > std::sqrt(2.0) * kRootDistance * 1.01) return false;
  double angle = 0;
  try {
    return group.log_vector(group.compose(group.inverse(a), b), angle).norm() < kRootDistance;
  } catch (const LogDomainError&) {
    return false;
  }
}

// What one solve left in its pixel until its row is classified.
template <LieGroup G>
struct Slot {
  Status status = Status::cancelled;
  int iterations = 0;
  typename G::Element y;  // converged pixels only
};

// One map of an equation on group G: the equation is shared (read-only) by the workers; each pixel solves a
// copy started at its own y_0.
template <LieGroup G>
class BasinMap {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;

  BasinMap(const Equation<G>& eq, const BasinPlane& plane, const BasinRowCallback& on_row, const WorkFarm* farm)
      : group_(eq.group()), eq_(eq), plane_(untimed(plane)), on_row_(on_row), farm_(farm), size_(plane.size),
        methods_(static_cast<int>(plane.methods.size())), rows_(basin_shard_rows(plane.size, plane.shard)),
        b1_(plane.b1), b2_(plane.b2) {
    const double radius = plane.radius.value_or(G::kLogRadius);
    result_.grid = {basin_axis(size_, radius), radius, plane.b1, plane.b2, group_.matrix(eq.z())};
    result_.shard = plane.shard;
  }

  BasinResult run() {
    const int per_row = size_ * methods_;
    // Items and slots are numbered by the row's place in rows_ (the part's rows), then column, then method.
    const int row_count = static_cast<int>(rows_.size());
    slots_.resize(rows_.size() * static_cast<std::size_t>(per_row));
    remaining_ = std::vector<std::atomic<int>>(rows_.size());
    for (auto& r : remaining_) r = per_row;
    if (farm_) {
      // A farm's items are whole rows (a pixel is too small to send to another process).
      std::vector<int> rows(rows_.size());
      std::iota(rows.begin(), rows.end(), 0);
      if (!farm_->run(rows, [&](int row) { return solve_row(row, per_row); },
                      [&](int row, const std::string& bytes) { return file_row(row, per_row, bytes); }))
        return {};  // a process that only computed rows for the farm
    } else {
      // Items in pixel order (row, column, method): rows complete roughly in order, so few wait to be classified.
      parallel_for(static_cast<int>(slots_.size()), plane_.threads, [&](int k) {
        if (!solve_pixel(k, per_row)) return false;
        if (remaining_[static_cast<std::size_t>(k / per_row)].fetch_sub(1) == 1) classify_completed_rows();
        return !stop_.load();
      });
    }
    result_.complete = static_cast<int>(result_.rows.size()) == row_count;
    result_.methods = basin_summaries(result_.rows, plane_.methods);
    return std::move(result_);
  }

 private:
  // Solves pixel item k into its slot; false when the map was stopped or cancelled.
  bool solve_pixel(int k, int per_row) {
    if (stop_.load() || cancellation_requested()) return !(stop_ = true);
    const int row = k / per_row, column = (k % per_row) / methods_, m = k % methods_;
    Equation<G> eq = eq_;
    const std::vector<double>& axis = result_.grid.axis;
    const double b = axis[static_cast<std::size_t>(rows_[static_cast<std::size_t>(row)])];
    eq.start_at(group_.times_exp(eq_.z(), Vector(axis[static_cast<std::size_t>(column)] * b1_ + b * b2_)));
    SolveResult r;
    try {
      r = run_method(plane_.methods[static_cast<std::size_t>(m)], eq, plane_.solver, {});
    } catch (const Cancelled&) {  // inside a finite-difference differential
      return !(stop_ = true);
    }
    if (r.status == Status::cancelled) return !(stop_ = true);
    Slot<G>& slot = slots_[static_cast<std::size_t>(k)];
    slot.status = r.status;
    slot.iterations = r.total_iterations();
    if (r.status == Status::converged) slot.y = typename G::Element(r.y);
    return true;
  }

  // A farm item: every pixel of a row as bytes (status, iterations and, when converged, y bit for bit); empty
  // when stopped.
  std::string solve_row(int row, int per_row) {
    ByteWriter out;
    for (int k = row * per_row; k < (row + 1) * per_row; ++k) {
      if (!solve_pixel(k, per_row)) return {};
      const Slot<G>& slot = slots_[static_cast<std::size_t>(k)];
      out.put(slot.status).put(slot.iterations);
      if (slot.status != Status::converged) continue;
      out.put(slot.y.rows()).put(slot.y.cols()).put_doubles(slot.y.data(), static_cast<std::size_t>(slot.y.size()));
    }
    return out.take();
  }

  // Files a farm item's row into its slots (the ones solve_row wrote if this process computed it) and classifies
  // the rows now complete, in order.
  bool file_row(int row, int per_row, const std::string& bytes) {
    if (bytes.empty()) return !(stop_ = true);
    ByteReader in(bytes);
    for (int k = row * per_row; k < (row + 1) * per_row; ++k) {
      Slot<G>& slot = slots_[static_cast<std::size_t>(k)];
      slot.status = in.get<Status>();
      slot.iterations = in.get<int>();
      if (slot.status != Status::converged) continue;
      const auto rows = in.get<Eigen::Index>(), cols = in.get<Eigen::Index>();
      slot.y.resize(rows, cols);
      in.get_doubles(slot.y.data(), static_cast<std::size_t>(slot.y.size()));
    }
    remaining_[static_cast<std::size_t>(row)] = 0;
    classify_completed_rows();
    return !stop_.load();
  }

  // Classifies the rows that are complete and next in order, under the lock: root ids are handed out in pixel
  // order whatever the schedule.
  void classify_completed_rows() {
    std::lock_guard lock(mutex_);
    while (next_row_ < static_cast<int>(rows_.size()) &&
           remaining_[static_cast<std::size_t>(next_row_)].load() == 0 && !stop_.load()) {
      BasinRow row;
      row.row = rows_[static_cast<std::size_t>(next_row_)];
      row.b = result_.grid.axis[static_cast<std::size_t>(row.row)];
      row.pixels.assign(static_cast<std::size_t>(methods_), std::vector<BasinPixel>(static_cast<std::size_t>(size_)));
      for (int column = 0; column < size_; ++column) {
        for (int m = 0; m < methods_; ++m) {
          Slot<G>& slot = slots_[(static_cast<std::size_t>(next_row_) * size_ + column) * methods_ + m];
          BasinPixel& pixel = row.pixels[static_cast<std::size_t>(m)][static_cast<std::size_t>(column)];
          pixel.status = slot.status;
          pixel.iterations = slot.iterations;
          if (slot.status == Status::converged) pixel.root = root_of(slot.y, row.new_roots);
          if constexpr (Element::SizeAtCompileTime == Eigen::Dynamic) slot.y.resize(0, 0);  // free row by row
        }
      }
      result_.rows.push_back(std::move(row));
      ++next_row_;
      if (on_row_ && !on_row_(result_.rows.back(), result_.roots)) stop_ = true;
    }
  }

  // The id of the root y belongs to, adding a root when it is new.
  int root_of(const Element& y, std::vector<int>& new_roots) {
    for (std::size_t i = 0; i < root_ys_.size(); ++i)
      if (same_root(group_, root_ys_[i], y)) return static_cast<int>(i);
    BasinRoot root;
    root.id = static_cast<int>(root_ys_.size());
    root.y = group_.matrix(y);
    const auto p = eq_.at(y, Equation<G>::Need::residual);
    root.residual = p.residual;
    root.distance_from_z = p.v.norm();
    if (eq_.is_implicit_euler()) root.hg_angle = group_.angle(group_.spectral(p.hg));
    root_ys_.push_back(y);
    result_.roots.push_back(std::move(root));
    new_roots.push_back(result_.roots.back().id);
    return result_.roots.back().id;
  }

  // No per-iterate clock (a system call costs more than an SO(3) iteration) and no stored iterates.
  static BasinPlane untimed(BasinPlane plane) {
    plane.solver.timed = false;
    plane.solver.include_iterates = false;
    return plane;
  }

  const G& group_;
  const Equation<G>& eq_;
  const BasinPlane plane_;
  const BasinRowCallback& on_row_;
  const WorkFarm* farm_;
  int size_, methods_;
  std::vector<int> rows_;  // the map's rows this part computes, in order
  Vector b1_, b2_;
  BasinResult result_;
  std::vector<Slot<G>> slots_;
  std::vector<std::atomic<int>> remaining_;  // unsolved items per row
  std::atomic<bool> stop_{false};
  std::mutex mutex_;  // guards the classification: next_row_, root_ys_, result_.rows/roots and on_row_
  int next_row_ = 0;
  std::vector<Element> root_ys_;
};


// The map of eq over the plane (basins() without a request: no validation here).
template <LieGroup G>
BasinResult basin_map(const Equation<G>& eq, const BasinPlane& plane, const BasinRowCallback& on_row = {},
                      const WorkFarm* farm = nullptr) {
  return BasinMap<G>(eq, plane, on_row, farm).run();
}

// The two rotation groups' maps are compiled once, in basins.cpp (as the solvers are: rotation_instances.hpp).
extern template BasinResult basin_map<SO3Group>(const Equation<SO3Group>&, const BasinPlane&,
                                                const BasinRowCallback&, const WorkFarm*);
extern template BasinResult basin_map<SONGroup>(const Equation<SONGroup>&, const BasinPlane&,
                                                const BasinRowCallback&, const WorkFarm*);

}  // namespace lienewton
