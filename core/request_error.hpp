#pragma once
// A request the core cannot carry out, naming the offending field. kind tells the front end whether the
// request was malformed (invalid: HTTP 400, CLI exit 2) or well-formed but impossible (unprocessable: 422).
#include <stdexcept>
#include <string>

namespace lienewton {

class RequestError : public std::invalid_argument {
 public:
  enum class Kind { invalid, unprocessable };
  RequestError(Kind kind, std::string field, const std::string& message)
      : std::invalid_argument(message), kind_(kind), field_(std::move(field)) {}
  Kind kind() const { return kind_; }
  const std::string& field() const { return field_; }

 private:
  Kind kind_;
  std::string field_;
};

}  // namespace lienewton
