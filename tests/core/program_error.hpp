#pragma once
// The request error a user's program gets when compiled (a test failure when it compiles).
#include <gtest/gtest.h>

#include <string>

#include "core/request_error.hpp"
#include "core/user_field/program.hpp"

namespace lienewton {

inline RequestError compile_error(const std::string& source, int n = 3, const user_field::Parameters& p = {}) {
  try {
    user_field::compile(source, n, p);
  } catch (const RequestError& e) {
    return e;
  }
  ADD_FAILURE() << "compiled: " << source.substr(0, 80);
  return RequestError(RequestError::Kind::invalid, "", "");
}

}  // namespace lienewton
