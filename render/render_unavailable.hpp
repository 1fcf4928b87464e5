#pragma once
// The one error a render can raise that is not the caller's fault: no GL context (or font) could be had.
// The service answers it with 503; everything else it can report as a bad request or a bug.
#include <stdexcept>

namespace lienewton::render {

class RenderUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lienewton::render
