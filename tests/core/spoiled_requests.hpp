#pragma once
// Refusals of a built-in problem's parameters: each case spoils one field of a valid integrate request, and the
// request must be a 422 naming exactly that field.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "core/integrate.hpp"
#include "core/request_error.hpp"

namespace lienewton::test {

struct SpoiledField {
  const char* field;
  std::function<void(ProblemSpec&)> spoil;
};

inline void expect_each_refused_naming_its_field(const IntegrateRequest& valid,
                                                const std::vector<SpoiledField>& cases) {
  for (const SpoiledField& c : cases) {
    IntegrateRequest req = valid;
    c.spoil(req.problem);
    try {
      validate(req);
      ADD_FAILURE() << c.field << " was accepted";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.kind(), RequestError::Kind::unprocessable) << c.field << ": " << e.what();
      EXPECT_EQ(e.field(), c.field) << e.what();
    }
  }
}

}  // namespace lienewton::test
