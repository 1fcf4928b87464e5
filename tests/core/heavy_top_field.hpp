#pragma once
// The heavy top (the benchmark of Lie group integrators for multibody systems) as a user's field on SO(3) x R^3
// ("group": "SOxR"), state y = [[R, 0], [0, [[I, w], [0, 1]]]] (7 x 7, core/groups/mechanics_groups.hpp):
//   R' = R hat(w),  J w' = (J w) x w + m chi x (R^T gamma),
// m = 15, J = diag(15.234375, 0.46875, 15.234375) about the pivot (as Exudyn's TestModels/heavyTop.py builds it from
// the benchmark's diag(0.234375, 0.46875, 0.234375) about the centre of mass), chi = (0, 1, 0), gamma = (0, 0, -9.81), R(0) = I,
// w(0) = (0, 150, -4.61538). Its invariants: the energy 1/2 w^T J w - m gamma^T R chi and the vertical angular
// momentum e3^T R J w.
#include <Eigen/Dense>

namespace lienewton::test {

inline constexpr const char* kHeavyTopProgram =
    "R = y(1:3,1:3); w = y(4:6,7); J = [15.234375; 0.46875; 15.234375]; "
    "dw = (cross(J .* w, w) + 15 * cross([0; 1; 0], R' * [0; 0; -9.81])) ./ J; "
    "W = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]; g = [W zeros(3,4); zeros(4,3) [zeros(3) dw; zeros(1,4)]]";

inline const Eigen::Vector3d kHeavyTopInertia{15.234375, 0.46875, 15.234375};
inline const Eigen::Vector3d kHeavyTopOmega0{0.0, 150.0, -4.61538};

// The 7 x 7 state of rotation r and angular velocity w.
inline Eigen::MatrixXd heavy_top_state(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Identity(7, 7);
  y.topLeftCorner(3, 3) = r;
  y.block(3, 6, 3, 1) = w;
  return y;
}

inline double heavy_top_energy(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) {
  return 0.5 * w.dot(kHeavyTopInertia.cwiseProduct(w)) - 15.0 * Eigen::Vector3d(0, 0, -9.81).dot(r.col(1));
}
inline double heavy_top_vertical_momentum(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) {
  return (r * kHeavyTopInertia.cwiseProduct(w)).z();
}

}  // namespace lienewton::test
