#include "chain.hpp"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>
#include <unsupported/Eigen/AutoDiff>

namespace lienewton {

namespace {

template <class S>
using V3 = Eigen::Matrix<S, 3, 1>;
template <class S>
using M3 = Eigen::Matrix<S, 3, 3>;
template <class S>
using V6 = Eigen::Matrix<S, 6, 1>;
template <class S>
using Pair = std::pair<V3<S>, V3<S>>;
// Derivatives with respect to one link's 12 perturbation coordinates, or a joint's two links' 24.
using LinkDual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 12, 1>>;
using JointDual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;

// One link's state in scalars S: double, or AutoDiff seeded with the perturbation.
template <class S>
struct Link {
  M3<S> r;
  V3<S> x, w, v;
};

Link<double> link(const Chain::Element& y, int i) {
  const auto b = Chain::Group::body(y, i);
  return {b.topLeftCorner<3, 3>(), b.block<3, 1>(0, 3), b.block<3, 1>(4, 10), b.block<3, 1>(7, 10)};
}

// The link with its 12 perturbation coordinates (u_w, u_r, u_dw, u_dv) as the variables first ... first + 11, to
// first order in them: R (I + hat(u_w)), x + R u_r, w + u_dw, v + u_dv.
template <class S>
Link<S> seeded(const Link<double>& b, int first) {
  V3<S> u[4];
  for (int part = 0; part < 4; ++part)
    for (int c = 0; c < 3; ++c) u[part](c) = S(0.0, S::DerType::RowsAtCompileTime, first + 3 * part + c);
  const M3<S> r = b.r.cast<S>();
  M3<S> turn = M3<S>::Identity();
  turn(0, 1) = -u[0](2), turn(0, 2) = u[0](1), turn(1, 0) = u[0](2);
  turn(1, 2) = -u[0](0), turn(2, 0) = -u[0](1), turn(2, 1) = u[0](0);
  return {r * turn, b.x.cast<S>() + r * u[1], b.w.cast<S>() + u[2], b.v.cast<S>() + u[3]};
}

// The formulas of the model (chain.hpp), once for values and derivatives.
template <class S>
class Formulas {
 public:
  explicit Formulas(const ChainParams& p)
      : p_(p), inertia_(p.inertia.cast<S>()), top_(S(0.0), S(0.0), S(0.5 * p.length)),
        bottom_(S(0.0), S(0.0), S(-0.5 * p.length)) {}

  // Joint j's gap d and its rate d': upper is null for joint 0 (the fixed point, at rest).
  Pair<S> gap(const Link<S>* upper, const Link<S>& lower) const {
    Pair<S> d = point(lower, top_);
    if (upper) {
      const Pair<S> q = point(*upper, bottom_);
      d.first -= q.first;
      d.second -= q.second;
    }
    return d;
  }
  // The link's own (w', v'), without its joints: the gyroscopic terms and gravity.
  V6<S> free_acceleration(const Link<S>& b) const {
    V6<S> out;
    out << inertia_.cwiseProduct(b.w).cross(b.w).cwiseQuotient(inertia_),
        b.v.cross(b.w) + b.r.transpose() * p_.gravity.cast<S>();
    return out;
  }
  // What joint j adds to (w', v') of its upper link (0 for joint 0) and of its lower one, stacked.
  Eigen::Matrix<S, 12, 1> joint_acceleration(const Link<S>* upper, const Link<S>& lower) const {
    const Pair<S> d = gap(upper, lower);
    const V3<S> f = -S(p_.stiffness) * d.first - S(p_.damping) * d.second;  // on the lower link
    Eigen::Matrix<S, 12, 1> out;
    out.template head<6>() = upper ? pushed(*upper, bottom_, V3<S>(-f)) : V6<S>::Zero();
    out.template tail<6>() = pushed(lower, top_, f);
    return out;
  }

 private:
  // A point a of the link (its frame) and that point's velocity R (v + w x a), in space.
  static Pair<S> point(const Link<S>& b, const V3<S>& a) { return {b.x + b.r * a, b.r * (b.v + b.w.cross(a))}; }
  // The (w', v') a force f (space) at the link's point a adds: J^-1 (a x R^T f) and R^T f / m.
  V6<S> pushed(const Link<S>& b, const V3<S>& a, const V3<S>& f) const {
    const V3<S> body_force = b.r.transpose() * f;
    V6<S> out;
    out << a.cross(body_force).cwiseQuotient(inertia_), body_force / S(p_.mass);
    return out;
  }

  const ChainParams& p_;
  V3<S> inertia_, top_, bottom_;
};

}  // namespace

Eigen::VectorXd Chain::coordinates(const Element& y) const {
  const int k = links(y);
  const Formulas<double> f(params_);
  Eigen::VectorXd out(kLinkDim * k);
  for (int i = 0; i < k; ++i) {
    const Link<double> b = link(y, i);
    out.segment<kLinkDim>(kLinkDim * i) << b.w, b.v, f.free_acceleration(b);
  }
  for (int j = 0; j < k; ++j) {
    const Link<double> lower = link(y, j);
    if (j == 0) {
      out.segment<6>(6) += f.joint_acceleration(nullptr, lower).tail<6>();
    } else {
      const Link<double> upper = link(y, j - 1);
      const Eigen::Matrix<double, 12, 1> a = f.joint_acceleration(&upper, lower);
      out.segment<6>(kLinkDim * (j - 1) + 6) += a.head<6>();
      out.segment<6>(kLinkDim * j + 6) += a.tail<6>();
    }
  }
  return out;
}

Chain::Group::Operator Chain::dg_matrix(const Group& group, const Element& y) const {
  const int k = links(y);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(k) * (6 + 6 * 12 + 2 * 12 * 24));
  // rows (row0 + r), cols (col0 + c) of the derivative of `value`, row r of it, by variable c
  const auto add = [&](int row0, int col0, const auto& value, int rows) {
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < value(r).derivatives().size(); ++c)
        if (value(r).derivatives()(c) != 0.0) entries.emplace_back(row0 + r, col0 + c, value(r).derivatives()(c));
  };
  const Formulas<LinkDual> own(params_);
  const Formulas<JointDual> joint(params_);
  for (int i = 0; i < k; ++i) {
    const int at = kLinkDim * i;
    for (int r = 0; r < 6; ++r) entries.emplace_back(at + r, at + 6 + r, 1.0);  // (w, v)' = (u_dw, u_dv)
    add(at + 6, at, own.free_acceleration(seeded<LinkDual>(link(y, i), 0)), 6);
  }
  for (int j = 0; j < k; ++j) {
    if (j == 0) {
      const Eigen::Matrix<JointDual, 12, 1> a = joint.joint_acceleration(nullptr, seeded<JointDual>(link(y, 0), 0));
      add(6, 0, a.tail<6>(), 6);  // link 0's variables are 0 ... 11: the fixed point has none
      continue;
    }
    const Link<JointDual> upper = seeded<JointDual>(link(y, j - 1), 0), lower = seeded<JointDual>(link(y, j), kLinkDim);
    const Eigen::Matrix<JointDual, 12, 1> a = joint.joint_acceleration(&upper, lower);
    add(kLinkDim * (j - 1) + 6, kLinkDim * (j - 1), a.head<6>(), 6);
    add(kLinkDim * j + 6, kLinkDim * (j - 1), a.tail<6>(), 6);
  }
  Group::Operator m(group.dim(), group.dim());
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

namespace {
Pair<double> gap_of(const ChainParams& p, const Chain::Element& y, int j) {
  const Formulas<double> f(p);
  const Link<double> lower = link(y, j);
  if (j == 0) return f.gap(nullptr, lower);
  const Link<double> upper = link(y, j - 1);
  return f.gap(&upper, lower);
}
}  // namespace

Eigen::Vector3d Chain::gap(const Element& y, int j) const { return gap_of(params_, y, j).first; }
Eigen::Vector3d Chain::gap_rate(const Element& y, int j) const { return gap_of(params_, y, j).second; }

double Chain::energy(const Element& y) const {
  const ChainParams& p = params_;
  double e = 0.0;
  for (int i = 0; i < links(y); ++i) {
    const Link<double> b = link(y, i);
    e += 0.5 * p.mass * b.v.squaredNorm() + 0.5 * b.w.dot(p.inertia.cwiseProduct(b.w)) - p.mass * p.gravity.dot(b.x) +
         0.5 * p.stiffness * gap(y, i).squaredNorm();
  }
  return e;
}

double Chain::energy_scale(const Element& y) const {
  const ChainParams& p = params_;
  double e = 0.0;
  for (int i = 0; i < links(y); ++i) {
    const Link<double> b = link(y, i);
    e += 0.5 * p.mass * b.v.squaredNorm() + 0.5 * b.w.dot(p.inertia.cwiseProduct(b.w)) +
         p.mass * p.gravity.norm() * b.x.norm() + 0.5 * p.stiffness * gap(y, i).squaredNorm();
  }
  return e;
}

double Chain::rate() const {
  const ChainParams& p = params_;
  const double s = 1.0 / p.mass + 0.25 * p.length * p.length / std::min(p.inertia.x(), p.inertia.y());
  return std::max({std::sqrt(4.0 * p.stiffness * s), 4.0 * p.damping * s, std::sqrt(p.gravity.norm() / p.length)});
}

Chain::Element Chain::start_strip(int k) const {
  const Group group(k);
  Element y = group.identity();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(params_.tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (int i = 0; i < k; ++i) {
    auto b = Group::body(y, i);
    b.topLeftCorner<3, 3>() = r;
    b.block<3, 1>(0, 3) = r * Eigen::Vector3d(0.0, 0.0, -(i + 0.5) * params_.length);  // centres on the line
  }
  return y;
}

}  // namespace lienewton
