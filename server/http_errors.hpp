#pragma once
// Error responses: always {"error":{"code","field","message"}} with a fixed status, never exception text.
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include "server/http_exchange.hpp"

namespace lienewton::service {

// Thrown inside handlers for an HTTP-level refusal (capacity, deadline, shutdown, 422 from the front end).
class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string code, std::string field, const std::string& message)
      : std::runtime_error(message), status_(status), code_(std::move(code)), field_(std::move(field)) {}
  int status() const { return status_; }
  const std::string& code() const { return code_; }
  const std::string& field() const { return field_; }

 private:
  int status_;
  std::string code_;
  std::string field_;
};

// A JSON error response with the given status.
HttpResponse error_response(int status, std::string_view code, std::string_view field, std::string_view message);

// The response for an exception a handler threw: ApiError (its own status; 503 adds Retry-After) or
// RequestError (400, or 422 for a well-formed but unprocessable request). Other exceptions are rethrown.
HttpResponse error_response(const std::exception_ptr& error);

// Writes an unexpected exception's cause (its what(), or its type unknown) to stderr, with where it happened: the
// client only sees 500 internal_error, the operator must see why.
void log_internal_error(const std::string& where, const std::exception_ptr& error);

}  // namespace lienewton::service
