#pragma once
// The chain's equations (core/chain.hpp) written again, independently, as an ODE in flat coordinates -- per link
// R (9 numbers, column-major), x, w, v: 18 numbers -- with forces and torques summed in space, and integrated by the
// classical RK4 with a fixed step: the reference lienewton's Lie-group integrators are compared with. Nothing here
// calls the chain's code; the strip layout (core/groups/power_group.hpp) is read and written only at the ends.
#include <Eigen/Dense>
#include <vector>

#include "core/chain_params.hpp"
#include "core/groups/mechanics_groups.hpp"

namespace lienewton::test {

class FlatChain {
 public:
  static constexpr int kLink = 18;
  FlatChain(const ChainParams& p, int k) : p_(p), k_(k) {}

  // The strip's links as flat coordinates, and back.
  Eigen::VectorXd flat(const SE3xR6PowerGroup::Element& y) const {
    Eigen::VectorXd s(kLink * k_);
    for (int i = 0; i < k_; ++i) {
      const auto b = SE3xR6PowerGroup::body(y, i);
      const Eigen::Matrix3d r = b.topLeftCorner<3, 3>();
      s.segment<9>(kLink * i) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(r.data());
      s.segment<3>(kLink * i + 9) = b.block<3, 1>(0, 3);
      s.segment<6>(kLink * i + 12) = b.block<6, 1>(4, 10);
    }
    return s;
  }
  SE3xR6PowerGroup::Element strip(const Eigen::VectorXd& s) const {
    SE3xR6PowerGroup::Element y = SE3xR6PowerGroup(k_).identity();
    for (int i = 0; i < k_; ++i) {
      auto b = SE3xR6PowerGroup::body(y, i);
      b.topLeftCorner<3, 3>() = rotation(s, i);
      b.block<3, 1>(0, 3) = s.segment<3>(kLink * i + 9);
      b.block<6, 1>(4, 10) = s.segment<6>(kLink * i + 12);
    }
    return y;
  }

  // d/dt of the flat state: R' = R hat(w), x' = R v; joint j pulls its lower link's top point with
  // F_j = -k_s d_j - c d_j' and its upper link's bottom point with -F_j; the torque about a centre is r x F in
  // space, taken to the body frame; m v' = m v x w + R^T F, J w' = (J w) x w + R^T tau.
  Eigen::VectorXd derivative(const Eigen::VectorXd& s) const {
    const Eigen::Vector3d half(0.0, 0.0, 0.5 * p_.length);
    std::vector<Eigen::Vector3d> force(k_ + 1, Eigen::Vector3d::Zero());  // force[j]: joint j's on its lower link
    for (int j = 0; j < k_; ++j) {
      const Eigen::Matrix3d r = rotation(s, j);
      Eigen::Vector3d gap = position(s, j) + r * half, rate = r * (velocity(s, j) + omega(s, j).cross(half));
      if (j > 0) {
        const Eigen::Matrix3d up = rotation(s, j - 1);
        gap -= position(s, j - 1) - up * half;
        rate -= up * (velocity(s, j - 1) - omega(s, j - 1).cross(half));
      }
      force[j] = -p_.stiffness * gap - p_.damping * rate;
    }
    Eigen::VectorXd out(kLink * k_);
    for (int i = 0; i < k_; ++i) {
      const Eigen::Matrix3d r = rotation(s, i);
      const Eigen::Vector3d w = omega(s, i), v = velocity(s, i);
      const Eigen::Vector3d total = force[i] - force[i + 1] + p_.mass * p_.gravity;
      const Eigen::Vector3d torque = (r * half).cross(force[i]) + (r * -half).cross(-force[i + 1]);
      const Eigen::Matrix3d turn = r * hat(w);
      out.segment<9>(kLink * i) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(turn.data());
      out.segment<3>(kLink * i + 9) = r * v;
      const Eigen::Vector3d jw = p_.inertia.cwiseProduct(w);
      out.segment<3>(kLink * i + 12) = (jw.cross(w) + r.transpose() * torque).cwiseQuotient(p_.inertia);
      out.segment<3>(kLink * i + 15) = v.cross(w) + r.transpose() * total / p_.mass;
    }
    return out;
  }

  // The classical RK4 from s over [0, t_end] in steps of t_end / steps.
  Eigen::VectorXd rk4(Eigen::VectorXd s, double t_end, int steps) const {
    const double h = t_end / steps;
    for (int n = 0; n < steps; ++n) {
      const Eigen::VectorXd k1 = derivative(s), k2 = derivative(s + 0.5 * h * k1), k3 = derivative(s + 0.5 * h * k2),
                            k4 = derivative(s + h * k3);
      s += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return s;
  }

 private:
  Eigen::Matrix3d rotation(const Eigen::VectorXd& s, int i) const {
    return Eigen::Map<const Eigen::Matrix3d>(s.data() + kLink * i);
  }
  Eigen::Vector3d position(const Eigen::VectorXd& s, int i) const { return s.segment<3>(kLink * i + 9); }
  Eigen::Vector3d omega(const Eigen::VectorXd& s, int i) const { return s.segment<3>(kLink * i + 12); }
  Eigen::Vector3d velocity(const Eigen::VectorXd& s, int i) const { return s.segment<3>(kLink * i + 15); }
  static Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
    Eigen::Matrix3d m;
    m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    return m;
  }

  ChainParams p_;
  int k_;
};

}  // namespace lienewton::test
