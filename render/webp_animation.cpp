#include "render/webp_animation.hpp"

#include <webp/encode.h>
#include <webp/mux.h>

#include <string>
#include <stdexcept>

namespace lienewton::render {

struct WebpAnimation::Encoder {
  WebPAnimEncoder* encoder = nullptr;
  WebPConfig config{};
  ~Encoder() {
    if (encoder) WebPAnimEncoderDelete(encoder);
  }
};

namespace {

// Replaces data by the same file with an XMP chunk (the mux sets the VP8X header's XMP flag).
void with_xmp(WebPData& data, const std::string& xmp) {
  WebPMux* mux = WebPMuxCreate(&data, 1);
  if (!mux) throw std::runtime_error("libwebp: cannot reopen the animation to add its metadata");
  const WebPData chunk{reinterpret_cast<const std::uint8_t*>(xmp.data()), xmp.size()};
  WebPData assembled;
  WebPDataInit(&assembled);
  const bool done = WebPMuxSetChunk(mux, "XMP ", &chunk, 1) == WEBP_MUX_OK && WebPMuxAssemble(mux, &assembled) == WEBP_MUX_OK;
  WebPMuxDelete(mux);
  if (!done) throw std::runtime_error("libwebp: cannot add the animation's metadata");
  WebPDataClear(&data);
  data = assembled;
}

}  // namespace

WebpAnimation::WebpAnimation(int width, int height) : encoder_(std::make_unique<Encoder>()), width_(width), height_(height) {
  WebPAnimEncoderOptions options;
  if (!WebPAnimEncoderOptionsInit(&options)) throw std::runtime_error("libwebp: incompatible version");
  options.anim_params.loop_count = 0;  // loop forever, as a player expects of a short motion
  encoder_->encoder = WebPAnimEncoderNew(width, height, &options);
  if (!encoder_->encoder) throw std::runtime_error("libwebp: cannot create the animation encoder");
  if (!WebPConfigInit(&encoder_->config)) throw std::runtime_error("libwebp: incompatible version");
  encoder_->config.lossless = 1;
  encoder_->config.method = 0;    // the fastest: frames are few colours, which compress well at any effort
  encoder_->config.quality = 10;  // in lossless mode: effort, not fidelity
}

WebpAnimation::~WebpAnimation() = default;

void WebpAnimation::add(std::span<const std::uint8_t> rgb, RowOrder order, int timestamp_ms) {
  const std::size_t row = static_cast<std::size_t>(width_) * 3;
  if (rgb.size() != row * static_cast<std::size_t>(height_)) throw std::invalid_argument("frame size mismatch");
  WebPPicture picture;
  if (!WebPPictureInit(&picture)) throw std::runtime_error("libwebp: incompatible version");
  picture.use_argb = 1;
  picture.width = width_;
  picture.height = height_;
  // Import reads rows top down; a GL read-back is bottom up, read with a negative stride from its last row.
  const std::uint8_t* first = order == RowOrder::top_down ? rgb.data() : rgb.data() + row * (height_ - 1);
  const int stride = order == RowOrder::top_down ? static_cast<int>(row) : -static_cast<int>(row);
  const bool imported = WebPPictureImportRGB(&picture, first, stride) != 0;
  const bool added = imported && WebPAnimEncoderAdd(encoder_->encoder, &picture, timestamp_ms, &encoder_->config) != 0;
  WebPPictureFree(&picture);
  if (!added) throw std::runtime_error(std::string("libwebp: cannot add a frame: ") + WebPAnimEncoderGetError(encoder_->encoder));
}

std::vector<std::uint8_t> WebpAnimation::finish(int end_ms, const std::string& xmp) {
  if (!WebPAnimEncoderAdd(encoder_->encoder, nullptr, end_ms, nullptr)) {
    throw std::runtime_error(std::string("libwebp: cannot end the animation: ") + WebPAnimEncoderGetError(encoder_->encoder));
  }
  WebPData data;
  WebPDataInit(&data);
  if (!WebPAnimEncoderAssemble(encoder_->encoder, &data)) {
    throw std::runtime_error(std::string("libwebp: cannot assemble the animation: ") + WebPAnimEncoderGetError(encoder_->encoder));
  }
  if (!xmp.empty()) with_xmp(data, xmp);
  std::vector<std::uint8_t> out(data.bytes, data.bytes + data.size);
  WebPDataClear(&data);
  return out;
}

}  // namespace lienewton::render
