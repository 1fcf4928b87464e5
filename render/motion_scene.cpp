#include "render/motion_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "render/colormap.hpp"

namespace lienewton::render {
namespace {

constexpr Color kGray{110, 110, 110, 255};
constexpr Color kFaint{215, 215, 215, 255};
constexpr Color kAxisX{215, 35, 35, 255}, kAxisY{25, 150, 55, 255}, kAxisZ{35, 75, 215, 255};
constexpr double kBound = 1e6;

// Mechanics draws z up: the world turned so that its z is the camera's up (y) and its y points away.
const Eigen::Matrix3d& z_up() {
  static const Eigen::Matrix3d m = (Eigen::Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  return m;
}

// World (turned) to the unit ball the camera frames: everything the scene can ever show, at any state, fits.
struct Fit {
  Eigen::Vector3d center;
  double scale;
  Eigen::Vector3d operator()(const Eigen::Vector3d& world) const { return scale * (z_up() * world - center); }
};

Fit fit(const Motion& m) {
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // the origin is shown
  const auto take = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = z_up() * p;
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  };
  // Every vertex of every body at every state: the tightest box the motion stays in.
  for (const Motion::Body& b : m.bodies) {
    const Mesh& mesh = m.meshes[static_cast<std::size_t>(b.mesh)];
    for (std::size_t i = 0; i < b.position.size(); ++i)
      for (const Eigen::Vector3d& v : mesh.vertices) take(b.rotation[i] * v + b.position[i]);
  }
  for (const Eigen::Vector3d& p : m.trace) take(p);
  if (m.sphere) return {Eigen::Vector3d::Zero(), 0.95 / *m.sphere};  // the path lies on it
  const Eigen::Vector3d center = 0.5 * (low + high);
  return {center, 0.95 / std::max(0.5 * (high - low).norm(), 1e-12)};
}

void check_vector(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kBound)
    throw std::invalid_argument(std::string(what) + " is non-finite or beyond 1e6");
}

void arrow(Canvas& canvas, Point from, Point to, float width, Color color) {
  canvas.line(from, to, width, color);
  const float dx = to.x - from.x, dy = to.y - from.y, length = std::hypot(dx, dy);
  if (length < 1) return;
  const float ux = dx / length, uy = dy / length, head = std::min(10.0f, 0.4f * length);
  canvas.triangle(to, {to.x - head * ux - 0.5f * head * uy, to.y - head * uy + 0.5f * head * ux},
                  {to.x - head * ux + 0.5f * head * uy, to.y - head * uy - 0.5f * head * ux}, color);
}

// The world's axes at the origin: x, y, z (z up), short and thin, labelled at their tips.
void world_axes(Canvas& canvas, const Camera& camera, const Fit& f, double length) {
  const Point o = camera.project(f(Eigen::Vector3d::Zero()));
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  const Color colors[3] = {kAxisX, kAxisY, kAxisZ};
  static constexpr const char* kNames[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d tip = f(Eigen::Vector3d::Zero()) + length * (z_up() * axes[i]);
    arrow(canvas, o, camera.project(tip), 1.5f, mix(colors[i], kWhite, 0.35));
    const Point label = camera.project(f(Eigen::Vector3d::Zero()) + 1.18 * length * (z_up() * axes[i]));
    canvas.text(kNames[i], label.x, label.y, TextSize::small, colors[i], Align::center);
  }
}

// A point on the far side of the sphere (seen through it) is drawn faint.
bool behind(const Camera& camera, const Eigen::Vector3d& p) { return camera.depth(p) < 0; }

void sphere(Canvas& canvas, const Camera& camera, const Fit& f, const Motion& m) {
  const Point c = camera.project(f(Eigen::Vector3d::Zero()));
  const float radius = static_cast<float>(*m.sphere * f.scale * camera.pixels_per_unit());
  constexpr int kOutline = 128;
  for (int i = 0; i < kOutline; ++i) {
    const double t0 = 2 * std::numbers::pi * i / kOutline, t1 = 2 * std::numbers::pi * (i + 1) / kOutline;
    canvas.line({c.x + radius * float(std::cos(t0)), c.y + radius * float(std::sin(t0))},
                {c.x + radius * float(std::cos(t1)), c.y + radius * float(std::sin(t1))}, 1.5f, kGray);
  }
  for (const auto& curve : m.sphere_curves) {
    for (std::size_t i = 1; i < curve.size(); ++i) {
      const Eigen::Vector3d a = f(curve[i - 1]) - f(Eigen::Vector3d::Zero()), b = f(curve[i]) - f(Eigen::Vector3d::Zero());
      const bool back = behind(camera, a + b);
      canvas.line(camera.project(f(curve[i - 1])), camera.project(f(curve[i])), back ? 1.0f : 1.2f,
                  back ? mix(kFaint, kWhite, 0.5) : mix(kGray, kWhite, 0.5));
    }
  }
}

// The path up to state `at`, each segment coloured by its time.
void trace(Canvas& canvas, const Camera& camera, const Fit& f, const Motion& m, std::size_t at) {
  const double t0 = m.times.front(), span = std::max(m.times.back() - t0, 1e-300);
  const Eigen::Vector3d origin = f(Eigen::Vector3d::Zero());
  for (std::size_t i = 1; i <= at && i < m.trace.size(); ++i) {
    const Color color = viridis((m.times[i] - t0) / span);
    const bool back = m.sphere && behind(camera, f(m.trace[i]) - origin);
    canvas.line(camera.project(f(m.trace[i - 1])), camera.project(f(m.trace[i])), back ? 2.0f : 3.0f,
                back ? mix(color, kWhite, 0.45) : color);
  }
}

// Bottom left: the time colours from t_0 to t_end, the path's name, and the time shown.
void legend(Canvas& canvas, const Motion& m, std::size_t at) {
  const float x = 10, bar = 120, y = canvas.scene_height() - 14;
  char text[64];
  if (!m.trace.empty()) {
    for (int i = 0; i < int(bar); ++i)
      canvas.rect(x + float(i), y - 5, x + float(i + 1), y + 5, viridis(i / (bar - 1)));
    std::snprintf(text, sizeof text, "%s = %.3g", m.time_name.c_str(), m.times.front());
    canvas.text(text, x, y - 16, TextSize::small, kTextColor);
    std::snprintf(text, sizeof text, "%.3g", m.times.back());
    canvas.text(text, x + bar, y - 16, TextSize::small, kTextColor, Align::right);
    canvas.text(m.trace_label, x + bar + 10, y, TextSize::small, kTextColor);
  }
  std::snprintf(text, sizeof text, "%s = %.4g", m.time_name.c_str(), m.times[at]);
  canvas.text(text, float(canvas.width()) - 10, 16, TextSize::large, kTextColor, Align::right);
  if (!m.sphere_label.empty()) canvas.text(m.sphere_label, x, 16, TextSize::small, kGray);
}

}  // namespace

void check_motion(const Motion& m) {
  const std::size_t states = m.times.size();
  if (states == 0) throw std::invalid_argument("a motion needs at least one state");
  for (double t : m.times)
    if (!std::isfinite(t)) throw std::invalid_argument("a time is non-finite");
  if (!m.trace.empty() && m.trace.size() != states) throw std::invalid_argument("the path must have a point per state");
  for (const Eigen::Vector3d& p : m.trace) check_vector(p, "a point of the path");
  for (const Motion::Body& b : m.bodies) {
    if (b.mesh < 0 || static_cast<std::size_t>(b.mesh) >= m.meshes.size())
      throw std::invalid_argument("a body's mesh index is out of range");
    if (b.rotation.size() != states || b.position.size() != states)
      throw std::invalid_argument("every body must have a pose per state");
    for (const Eigen::Vector3d& p : b.position) check_vector(p, "a body's position");
    for (const Eigen::Matrix3d& r : b.rotation)
      if (!r.allFinite() || r.cwiseAbs().maxCoeff() > 10) throw std::invalid_argument("a body's rotation is not one");
  }
  for (const Mesh& mesh : m.meshes)
    for (const Eigen::Vector3d& v : mesh.vertices) check_vector(v, "a mesh vertex");
  if (m.sphere && !(std::isfinite(*m.sphere) && *m.sphere > 0 && *m.sphere <= kBound))
    throw std::invalid_argument("the sphere's radius must be positive and at most 1e6");
}

void draw_motion(Canvas& canvas, const Camera& camera, const Motion& m, std::size_t at) {
  check_motion(m);
  if (at >= m.times.size()) throw std::invalid_argument("no such state");
  const Fit f = fit(m);
  const Eigen::Vector3d origin = f(Eigen::Vector3d::Zero());
  if (m.gravity && m.gravity->norm() > 0) {
    // The vertical through the pivot, dashed across the scene, and gravity's arrow at the right.
    const Eigen::Vector3d down = z_up() * m.gravity->normalized();
    dashed_line(canvas, camera.project(origin - 1.0 * down), camera.project(origin + 1.0 * down), 1.2f, kFaint);
    const Point top{float(canvas.width()) - 24, 40}, tip = {top.x + 40 * float(camera.right().dot(down)),
                                                            top.y - 40 * float(camera.up().dot(down))};
    arrow(canvas, top, tip, 2.0f, kGray);
    canvas.text("g", top.x - 12, 0.5f * (top.y + tip.y), TextSize::small, kGray, Align::right);
  }
  if (m.sphere) sphere(canvas, camera, f, m);
  world_axes(canvas, camera, f, 0.25);
  trace(canvas, camera, f, m, at);
  std::vector<PlacedSolid> solids;
  for (const Motion::Body& b : m.bodies) {
    solids.push_back({&m.meshes[static_cast<std::size_t>(b.mesh)], f.scale * z_up() * b.rotation[at],
                      f(b.position[at]), b.color});
  }
  draw_solids(canvas, camera, solids);
  if (!m.trace.empty()) {
    const Point head = camera.project(f(m.trace[at]));
    if (m.trace_arrow) arrow(canvas, camera.project(origin), head, 2.5f, kTextColor);
    canvas.rect(head.x - 3, head.y - 3, head.x + 3, head.y + 3, kTextColor);
  }
  if (m.pivot) {
    const Point p = camera.project(origin);
    canvas.triangle({p.x, p.y}, {p.x - 7, p.y + 10}, {p.x + 7, p.y + 10}, kGray);
  }
  legend(canvas, m, at);
}

}  // namespace lienewton::render
