#pragma once
#include <Eigen/Core>

namespace lienewton {

// Parameters of the chain (chain.hpp): k equal links hanging from the origin, neighbours joined by penalty
// spherical joints (a spring k_s and a damper c between attachment points), under gravity. Each link is a rod of
// mass m and length L whose joints sit at its ends, (0, 0, +-L/2) in its frame. The defaults make a picture of a
// swinging chain and a stiff test, read off the linearisation at the hanging rest (dg's eigenvalues, measured for
// k = 1, 2, 4, 8):
//  - m = 1 kg, L = 0.5 m, J = a solid rod of radius 0.05 m about its centre: m (3 r^2 + L^2) / 12 across,
//    m r^2 / 2 along its axis;
//  - gamma = (0, 0, -9.81): the chain hangs along -z;
//  - k_s = 1e5 N/m: a joint's period is about 2 pi sqrt(m / k_s) = 0.02 s (the joint modes' |lambda| 190 ... 1500
//    rad/s: periods 0.004 ... 0.03 s), against the swing's 1.16 s for one link and 1.66 s for two (|lambda| 5.4
//    and 3.8 rad/s; longer chains swing slower): stiff by a factor of 50 ... 400, which grows like sqrt(k_s);
//  - c = 200 N s/m: every joint mode damped (damping ratio 0.1 ... 1, the least damped decaying like
//    exp(-38 t) at k = 2), so it dies within a few of its periods, while the swing, which barely stretches the
//    joints, keeps its energy for many: the stiff-and-damped regime the implicit integrators are for;
//  - tilt = 0.6 rad: the chain starts straight, at rest and with closed joints, turned by 0.6 rad (34 degrees)
//    about x from hanging straight down, so it swings visibly and its links fold as it does.
struct ChainParams {
  double mass = 1.0;                                                // m of each link
  // J about the centre: a solid rod of radius 0.05 m, m (3 r^2 + L^2) / 12 across and m r^2 / 2 along its axis z
  Eigen::Vector3d inertia{(3 * 0.05 * 0.05 + 0.5 * 0.5) / 12, (3 * 0.05 * 0.05 + 0.5 * 0.5) / 12, 0.05 * 0.05 / 2};
  double length = 0.5;                                              // L: joint to joint
  double stiffness = 1e5;                                           // k_s
  double damping = 200.0;                                           // c
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};                         // gamma in space
  double tilt = 0.6;                                                // the start's angle about x from hanging down

  // The largest size a parameter may have: beyond it the field's values overflow long before any step is taken.
  static constexpr double kBound = 1e8;
};

}  // namespace lienewton
