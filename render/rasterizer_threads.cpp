#include <cstdlib>
#include <mutex>
#include <string>

#include "render/gl_context.hpp"

namespace lienewton::render {

void set_rasterizer_threads(int threads) {
  // setenv races with getenv in other threads; this runs once, before any context exists.
  static std::once_flag once;
  std::call_once(once, [threads] {
    const std::string value = std::to_string(threads < 0 ? 0 : threads);
    setenv("LP_NUM_THREADS", value.c_str(), /*overwrite=*/0);
  });
}

}  // namespace lienewton::render
