#pragma once
// 8-bit RGBA, the precision of the PNG: colors are fixed here so that a test can predict pixels exactly.
#include <cstdint>

namespace lienewton::render {

struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  friend bool operator==(const Color&, const Color&) = default;
};

// t = 0 gives a, t = 1 gives b (each channel rounded).
Color mix(Color a, Color b, double t);

inline constexpr Color kWhite{255, 255, 255, 255};
inline constexpr Color kBlack{0, 0, 0, 255};
inline constexpr Color kTextColor{30, 30, 30, 255};

}  // namespace lienewton::render
