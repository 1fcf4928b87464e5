#pragma once
// A request the core cannot carry out, naming the offending field. kind tells the front end whether the
// request was malformed (invalid: HTTP 400, CLI exit 2), well-formed but impossible (unprocessable: 422) or
// beyond what the server spends on one request (too_large: 413).
// A field that is a program (g) also names the line and column of the fault (1-based; 0 when none).
#include <stdexcept>
#include <string>

namespace lienewton {

class RequestError : public std::invalid_argument {
 public:
  enum class Kind { invalid, unprocessable, too_large };
  RequestError(Kind kind, std::string field, const std::string& message, int line = 0, int column = 0)
      : std::invalid_argument(message), kind_(kind), field_(std::move(field)), line_(line), column_(column) {}
  Kind kind() const { return kind_; }
  const std::string& field() const { return field_; }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  Kind kind_;
  std::string field_;
  int line_, column_;
};

}  // namespace lienewton
