#pragma once
// Animated WebP (libwebpmux's WebPAnimEncoder): what every current browser plays in an <img>, and what the
// dashboard steps through frame by frame (ImageDecoder). Lossless: the scenes are flat colours and thin lines,
// which lossy coding smears, and the encoder stores only the rectangle that changed from one frame to the next.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "render/png.hpp"

namespace lienewton::render {

class WebpAnimation {
 public:
  WebpAnimation(int width, int height);
  ~WebpAnimation();
  WebpAnimation(const WebpAnimation&) = delete;
  WebpAnimation& operator=(const WebpAnimation&) = delete;

  // One frame of RGB pixels shown from timestamp_ms on (increasing); throws std::runtime_error if encoding fails.
  void add(std::span<const std::uint8_t> rgb, RowOrder order, int timestamp_ms);
  // The file; the last frame is shown until end_ms. A non-empty xmp packet is stored as the file's XMP metadata
  // (a WebP "XMP " chunk), which travels with the file and which a page can read without decoding a frame.
  std::vector<std::uint8_t> finish(int end_ms, const std::string& xmp = {});

 private:
  struct Encoder;
  std::unique_ptr<Encoder> encoder_;
  int width_, height_;
};

}  // namespace lienewton::render
