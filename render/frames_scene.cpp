#include "render/frames_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace lienewton::render {
namespace {

constexpr Color kSphereOutline{190, 190, 190, 255};
constexpr Color kGreatCircle{222, 222, 222, 255};

// Rotations have entries in [-1, 1]; the loose bound only keeps projected coordinates within float range.
void check_entries(const Eigen::Matrix3d& m, const char* what) {
  if (!m.allFinite() || m.cwiseAbs().maxCoeff() > 10.0) {
    throw std::invalid_argument(std::string(what) + " is not a rotation: an entry is non-finite or above 10");
  }
}

// The great circle spanned by the unit vectors a and b.
void great_circle(Canvas& canvas, const Camera& camera, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  constexpr int kSegments = 96;
  Point previous = camera.project(a);
  for (int i = 1; i <= kSegments; ++i) {
    const double t = 2 * std::numbers::pi * i / kSegments;
    const Point next = camera.project(std::cos(t) * a + std::sin(t) * b);
    canvas.line(previous, next, 1.0f, kGreatCircle);
    previous = next;
  }
}

// The three axes of one frame, farthest first so that nearer axes cover it.
std::array<int, 3> back_to_front(const Camera& camera, const Eigen::Matrix3d& frame) {
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
    return camera.depth(frame.col(i)) < camera.depth(frame.col(j));
  });
  return order;
}

// The start's legend word: z, the start point, where a solve's picture has one.
void legend(Canvas& canvas, const char* start = "start z") {
  const float x = 10, line_height = 17;
  float y = canvas.scene_height() - 10 - 2 * line_height;
  const Color gray{110, 110, 110, 255};
  dashed_line(canvas, {x, y}, {x + 24, y}, 2.0f, gray);
  canvas.text(start, x + 32, y, TextSize::small, kTextColor);
  y += line_height;
  canvas.line({x, y}, {x + 24, y}, 1.5f, mix(gray, canvas.background(), 0.6));
  canvas.text("earlier", x + 32, y, TextSize::small, kTextColor);
  y += line_height;
  canvas.line({x, y}, {x + 24, y}, kFinalAxisWidth, gray);
  canvas.text("last", x + 32, y, TextSize::small, kTextColor);
}

}  // namespace

void draw_frames(Canvas& canvas, const Camera& camera, const std::vector<Eigen::Matrix3d>& frames,
                 const Eigen::Matrix3d& start) {
  check_entries(start, "start");
  for (const Eigen::Matrix3d& frame : frames) check_entries(frame, "frame");

  const Point origin = camera.project(Eigen::Vector3d::Zero());
  const float radius = static_cast<float>(camera.pixels_per_unit());
  great_circle(canvas, camera, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  great_circle(canvas, camera, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());
  great_circle(canvas, camera, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  // The sphere's silhouette: under an orthographic camera always a circle of the projected radius.
  constexpr int kOutlineSegments = 128;
  for (int i = 0; i < kOutlineSegments; ++i) {
    const double t0 = 2 * std::numbers::pi * i / kOutlineSegments;
    const double t1 = 2 * std::numbers::pi * (i + 1) / kOutlineSegments;
    canvas.line({origin.x + radius * float(std::cos(t0)), origin.y + radius * float(std::sin(t0))},
                {origin.x + radius * float(std::cos(t1)), origin.y + radius * float(std::sin(t1))}, 1.5f,
                kSphereOutline);
  }

  // Earlier frames go from nearly background (oldest) to clearly colored (the one before the last).
  const std::size_t count = frames.size();
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const double age = 1.0 - static_cast<double>(i + 1) / static_cast<double>(count);
    for (int axis : back_to_front(camera, frames[i])) {
      canvas.line(origin, camera.project(frames[i].col(axis)), 1.5f,
                  mix(kAxisColors[axis], canvas.background(), 0.3 + 0.55 * age));
    }
  }
  // The start goes over the earlier frames: y_0 = z would otherwise hide it.
  for (int axis : back_to_front(camera, start)) {
    dashed_line(canvas, origin, camera.project(start.col(axis)), 2.0f, kAxisColors[axis]);
  }
  if (count > 0) {
    const Eigen::Matrix3d& last = frames.back();
    for (int axis : back_to_front(camera, last)) {
      canvas.line(origin, camera.project(last.col(axis)), kFinalAxisWidth, kAxisColors[axis]);
      // Label just beyond the tip, pushed outward from the origin.
      const Point tip = camera.project(1.13 * last.col(axis));
      // The frame's axes y e_k, not the space's x, y, z (z is the start point, as in the legend).
      static constexpr const char* kNames[3] = {"e\u2081", "e\u2082", "e\u2083"};
      canvas.text(kNames[axis], tip.x, tip.y, TextSize::large, kAxisColors[axis], Align::center);
    }
  }
  legend(canvas);
}

namespace {

// Where each world point of the bodies' scene goes: into the unit ball, centered on everything drawn.
struct BodiesFit {
  Eigen::Vector3d center;
  double scale;  // unit-ball lengths per world length
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const { return scale * (p - center); }
};

BodiesFit fit_bodies(const std::vector<std::vector<BodyFrame>>& states, const std::vector<BodyFrame>& start) {
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // the origin is drawn too
  const auto take = [&](const std::vector<BodyFrame>& bodies) {
    for (const BodyFrame& b : bodies) low = low.cwiseMin(b.position), high = high.cwiseMax(b.position);
  };
  for (const auto& state : states) take(state);
  take(start);
  const Eigen::Vector3d center = 0.5 * (low + high);
  const double radius = std::max(0.5 * (high - low).norm(), 1e-12);
  return {center, 0.85 / radius};
}

// The chain's polyline through the bodies' positions, from the origin.
std::vector<Point> chain(const Camera& camera, const BodiesFit& fit, const std::vector<BodyFrame>& bodies) {
  std::vector<Point> out{camera.project(fit(Eigen::Vector3d::Zero()))};
  for (const BodyFrame& b : bodies) out.push_back(camera.project(fit(b.position)));
  return out;
}

void check_bodies(const std::vector<BodyFrame>& bodies, std::size_t count) {
  if (bodies.size() != count) throw std::invalid_argument("every state must have the same number of bodies");
  for (const BodyFrame& b : bodies) {
    check_entries(b.rotation, "a body's rotation");
    if (!b.position.allFinite() || b.position.cwiseAbs().maxCoeff() > 1e6)
      throw std::invalid_argument("a body's position is non-finite or beyond 1e6");
  }
}

}  // namespace

void draw_bodies(Canvas& canvas, const Camera& camera, const std::vector<std::vector<BodyFrame>>& given_states,
                 const std::vector<BodyFrame>& given_start) {
  check_bodies(given_start, given_start.size());
  for (const auto& state : given_states) check_bodies(state, given_start.size());
  // Mechanics draws z up: the world turned so that its z is the camera's up (y) and its y points away.
  Eigen::Matrix3d z_up;
  z_up << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  const auto turned = [&](std::vector<BodyFrame> bodies) {
    for (BodyFrame& b : bodies) b = {z_up * b.rotation, z_up * b.position};
    return bodies;
  };
  std::vector<std::vector<BodyFrame>> states;
  for (const auto& state : given_states) states.push_back(turned(state));
  const std::vector<BodyFrame> start = turned(given_start);
  const BodiesFit fit = fit_bodies(states, start);
  // Axes as long as a third of the mean spacing of the last state's bodies: neighbours' axes do not cross.
  const std::vector<BodyFrame>& last = states.empty() ? start : states.back();
  double spacing = 0.0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (const BodyFrame& b : last) spacing += (b.position - previous).norm(), previous = b.position;
  const double axis = std::clamp(fit.scale * spacing / std::max<double>(1.0, double(last.size())) / 3.0, 0.03, 0.3);

  const Color gray{110, 110, 110, 255};
  // Earlier states: their chains only, at most 24 of them, from nearly background (oldest) to clearly drawn.
  const std::size_t count = states.size(), stride = std::max<std::size_t>(1, count / 24);
  for (std::size_t i = (count - 1) % stride; i + 1 < count; i += stride) {
    const double age = 1.0 - static_cast<double>(i + 1) / static_cast<double>(count);
    const std::vector<Point> line = chain(camera, fit, states[i]);
    for (std::size_t j = 1; j < line.size(); ++j)
      canvas.line(line[j - 1], line[j], 1.5f, mix(gray, canvas.background(), 0.3 + 0.6 * age));
  }
  const std::vector<Point> first = chain(camera, fit, start);
  for (std::size_t j = 1; j < first.size(); ++j) dashed_line(canvas, first[j - 1], first[j], 2.0f, gray);
  const std::vector<Point> line = chain(camera, fit, last);
  for (std::size_t j = 1; j < line.size(); ++j) canvas.line(line[j - 1], line[j], 2.5f, gray);
  // The last state's axes, farthest body first.
  std::vector<std::size_t> order(last.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return camera.depth(last[a].position) < camera.depth(last[b].position);
  });
  for (std::size_t i : order) {
    const Point at = camera.project(fit(last[i].position));
    for (int a : back_to_front(camera, last[i].rotation)) {
      const Eigen::Vector3d tip = fit(last[i].position) + axis * last[i].rotation.col(a);
      canvas.line(at, camera.project(tip), 2.5f, kAxisColors[a]);
    }
  }
  const Point pivot = camera.project(fit(Eigen::Vector3d::Zero()));
  canvas.rect(pivot.x - 3, pivot.y - 3, pivot.x + 3, pivot.y + 3, kTextColor);
  legend(canvas, "start");
}

}  // namespace lienewton::render
