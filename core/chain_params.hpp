#pragma once
#include <Eigen/Core>

namespace lienewton {

// Parameters of the chain (chain.hpp): k equal links hanging from the origin, neighbours joined by penalty
// spherical joints (a spring k_s and a damper c between attachment points), under gravity. Each link is a rod of
// mass m and length L whose joints sit at its ends, (0, 0, +-L/2) in its frame. The defaults are a bicycle-chain
// sized picture with a stiff joint:
//  - m = 1 kg, L = 0.5 m, J = a solid rod of radius 0.05 m about its centre: m (3 r^2 + L^2) / 12 across,
//    m r^2 / 2 along;
//  - gamma = (0, 0, -9.81): the chain hangs along -z;
//  - k_s = 1e5 N/m: a joint's own period 2 pi sqrt(m / k_s) = 0.02 s (down to ~0.007 s for the links' end rotation,
//    whose effective mass is J / (L/2)^2), against the swing's ~1.2 s for one link (longer for more): stiff by a
//    factor 60..1000 and more as k grows;
//  - c = 200 N s/m: damping ratio c / (2 sqrt(k_s m_eff)) about 0.3 on the stretch mode (m_eff ~ m) and near 1 on
//    the end rotations, so the joint modes die within a few of their periods while the swing (which does not
//    stretch the joints) keeps its energy: the stiff-and-damped regime implicit integrators are for;
//  - tilt = 0.6 rad: the chain starts straight, at rest and with closed joints, turned by 0.6 rad about x from
//    hanging straight down, so it swings visibly (0.6 rad, ~34 degrees) and its links fold as it does.
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
