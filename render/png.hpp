#pragma once
// PNG encoding tuned for speed: encoding, not drawing, dominates a render (zlib level 1, filters none/sub).
#include <cstdint>
#include <span>
#include <vector>

namespace lienewton::render {

enum class RowOrder { top_down, bottom_up };

// rgb holds width * height pixels of 3 bytes. bottom_up takes GL's read-back order and flips it.
// Throws std::invalid_argument on a size mismatch, std::runtime_error if libpng fails.
std::vector<std::uint8_t> encode_png(std::span<const std::uint8_t> rgb, int width, int height, RowOrder order);

}  // namespace lienewton::render
