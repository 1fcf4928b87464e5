#include "render/motion_of_problem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace lienewton::render {
namespace {

constexpr Color kBody{96, 132, 196, 255};
constexpr Color kBodyAlternate{214, 140, 70, 255};
constexpr Color kRod{120, 120, 120, 255};

// A mesh moved into its body's frame: turned so that its z lies along `axis`, then shifted by `offset`.
Mesh placed(Mesh mesh, const Eigen::Vector3d& axis, const Eigen::Vector3d& offset) {
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis.normalized()).toRotationMatrix();
  for (Eigen::Vector3d& v : mesh.vertices) v = turn * v + offset;
  return mesh;
}

std::vector<BodyFrame> frames_of(const ProblemSpec& p, const Eigen::MatrixXd& y) { return p.family().body_frames(p.n, y); }

// One body per frame, all with mesh 0 (chain: alternating colours, so that neighbours are told apart).
void add_bodies(Motion& m, const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  const std::size_t count = frames_of(p, states.front()).size();
  m.bodies.resize(count);
  for (std::size_t b = 0; b < count; ++b) m.bodies[b].color = b % 2 ? kBodyAlternate : kBody;
  for (const Eigen::MatrixXd& y : states) {
    const std::vector<BodyFrame> frames = frames_of(p, y);
    for (std::size_t b = 0; b < count; ++b) {
      m.bodies[b].rotation.push_back(frames[b].rotation);
      m.bodies[b].position.push_back(frames[b].position);
    }
  }
}

void heavy_top(Motion& m, const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  const HeavyTopParams& top = p.heavy_top;
  const Eigen::Vector3d chi = top.center.norm() > 0 ? top.center : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d disc = inertia_ellipsoid(top.inertia, top.mass);
  m.meshes.push_back(placed(ellipsoid_mesh(disc), Eigen::Vector3d::UnitZ(), top.center));
  const double rod = 0.06 * std::max(disc.maxCoeff(), chi.norm());
  m.meshes.push_back(placed(ellipsoid_mesh(Eigen::Vector3d(rod, rod, 0.5 * chi.norm()), 12), chi, 0.5 * top.center));
  add_bodies(m, p, states);
  m.bodies.front().color = kBody;
  m.bodies.push_back(m.bodies.front());
  m.bodies.back().mesh = 1;
  m.bodies.back().color = kRod;
  // The symmetry axis' tip: where the axis through the centre of mass leaves the disc.
  const Eigen::Vector3d axis = chi.normalized();
  const Eigen::Vector3d tip = top.center + disc.cwiseProduct(axis.cwiseAbs()).norm() * axis;
  for (const Eigen::MatrixXd& y : states) m.trace.push_back(frames_of(p, y).front().rotation * tip);
  m.trace_label = "the symmetry axis' tip";
  m.pivot = true;
  m.gravity = top.gravity;
}

void rigid_body(Motion& m, const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  const Eigen::Vector3d& inertia = p.rigid_body.inertia;
  const Eigen::Vector3d& momentum = p.rigid_body.momentum;
  for (const Eigen::MatrixXd& y : states) m.trace.push_back(frames_of(p, y).front().rotation.transpose() * momentum);
  const Eigen::Vector3d& start = m.trace.front();
  m.sphere = std::max(momentum.norm(), 1e-300);
  m.sphere_curves = energy_curves(inertia, *m.sphere, 9, 0.5 * start.dot(start.cwiseQuotient(inertia)));
  m.trace_label = "body momentum M(t) = y(t)\u1d40 m";
  m.trace_arrow = true;
  m.sphere_label = "sphere |M| = |m|, grey: energy levels M\u00b7I\u207b\u00b9M/2 = E";
}

void stiff_body(Motion& m, const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  const Eigen::Vector3d axes = inertia_ellipsoid(p.stiff_body.J, 1.0);
  m.meshes.push_back(ellipsoid_mesh(axes));
  add_bodies(m, p, states);
  Eigen::Index longest;
  axes.maxCoeff(&longest);
  const Eigen::Vector3d tip = axes[longest] * Eigen::Vector3d::Unit(longest);
  for (const Eigen::MatrixXd& y : states) m.trace.push_back(frames_of(p, y).front().rotation * tip);
  m.trace_label = "the tip of its longest axis";
}

void chain(Motion& m, const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  const ChainParams& c = p.chain;
  // A rod's radius from its moment about its own axis (m r^2 / 2), its length from joint to joint.
  const double radius = std::clamp(std::sqrt(2 * c.inertia.z() / c.mass), 0.02 * c.length, 0.3 * c.length);
  m.meshes.push_back(ellipsoid_mesh(Eigen::Vector3d(radius, radius, 0.5 * c.length), 16));
  add_bodies(m, p, states);
  for (const Eigen::MatrixXd& y : states) {
    const BodyFrame last = frames_of(p, y).back();
    m.trace.push_back(last.position + last.rotation * Eigen::Vector3d(0, 0, -0.5 * c.length));
  }
  m.trace_label = "the free end";
  m.pivot = true;
  m.gravity = c.gravity;
}

void any_bodies(Motion& m, const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  add_bodies(m, p, states);
  // Sized from the bodies' spacing, a third of it, or a unit body when they share one place.
  double spread = 0;
  for (const Motion::Body& b : m.bodies)
    for (const Eigen::Vector3d& x : b.position) spread = std::max(spread, (x - m.bodies.front().position.front()).norm());
  const double size = m.bodies.size() > 1 && spread > 0 ? spread / (3.0 * double(m.bodies.size())) : 1.0;
  m.meshes.push_back(ellipsoid_mesh(size * Eigen::Vector3d(0.6, 0.35, 0.2)));
  const Motion::Body& first = m.bodies.front();
  for (std::size_t i = 0; i < states.size(); ++i)
    m.trace.push_back(first.position[i] + first.rotation[i] * Eigen::Vector3d(0.6 * size, 0, 0));
  m.trace_label = "the first body's e\u2081 tip";
}

}  // namespace

Motion motion_of(const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states, const std::vector<double>& times) {
  Motion m;
  m.times = times;
  if (states.empty() || states.size() != times.size()) throw std::invalid_argument("a state per time is needed");
  if (p.is(ProblemKind::heavy_top)) heavy_top(m, p, states);
  else if (p.is(ProblemKind::rigid_body)) rigid_body(m, p, states);
  else if (p.is(ProblemKind::stiff_body)) stiff_body(m, p, states);
  else if (p.is(ProblemKind::chain)) chain(m, p, states);
  else any_bodies(m, p, states);
  return m;
}

std::vector<std::vector<Eigen::Vector3d>> energy_curves(const Eigen::Vector3d& inertia, double radius, int levels,
                                                        double own_energy) {
  const double r2 = radius * radius;
  const double least = 0.5 * r2 / inertia.maxCoeff(), most = 0.5 * r2 / inertia.minCoeff();
  // The motion's own level, and the separatrices through the middle axis' poles (where rotations turn over).
  Eigen::Vector3d sorted = inertia;
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> energies{own_energy, 0.5 * r2 / sorted[1]};
  for (int i = 1; i <= levels; ++i) energies.push_back(least + (most - least) * i / (levels + 1));
  // The sphere's grid: longitude phi in [0, 2 pi), latitude theta in [-pi/2, pi/2].
  constexpr int kLon = 96, kLat = 48;
  const auto point = [&](double phi, double theta) {
    return Eigen::Vector3d(radius * std::cos(theta) * std::cos(phi), radius * std::cos(theta) * std::sin(phi),
                           radius * std::sin(theta));
  };
  const auto energy = [&](const Eigen::Vector3d& x) { return 0.5 * x.dot(x.cwiseQuotient(inertia)); };
  std::vector<std::vector<Eigen::Vector3d>> out;
  for (double e : energies) {
    for (int i = 0; i < kLon; ++i) {
      for (int j = 0; j < kLat; ++j) {
        const double phi[2] = {2 * std::numbers::pi * i / kLon, 2 * std::numbers::pi * (i + 1) / kLon};
        const double theta[2] = {std::numbers::pi * j / kLat - std::numbers::pi / 2,
                                 std::numbers::pi * (j + 1) / kLat - std::numbers::pi / 2};
        // The cell's corners counter-clockwise, and where the level crosses each edge.
        const Eigen::Vector3d c[4] = {point(phi[0], theta[0]), point(phi[1], theta[0]), point(phi[1], theta[1]),
                                      point(phi[0], theta[1])};
        std::vector<Eigen::Vector3d> crossings;
        for (int k = 0; k < 4; ++k) {
          const double a = energy(c[k]) - e, b = energy(c[(k + 1) % 4]) - e;
          if ((a < 0) != (b < 0)) {
            const Eigen::Vector3d x = c[k] + (a / (a - b)) * (c[(k + 1) % 4] - c[k]);
            crossings.push_back(radius * x.normalized());
          }
        }
        for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) out.push_back({crossings[k], crossings[k + 1]});
      }
    }
  }
  return out;
}

}  // namespace lienewton::render
