#include "server/http_errors.hpp"

#include "server/json_codec.hpp"

#include <cstdio>

namespace lienewton::service {

HttpResponse error_response(int status, std::string_view code, std::string_view field, std::string_view message) {
  HttpResponse res;
  res.status = status;
  res.content_type = "application/json";
  res.body = dump(error_body(code, field, message));
  return res;
}

HttpResponse error_response(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const ApiError& e) {
    HttpResponse res = error_response(e.status(), e.code(), e.field(), e.what());
    if (e.status() == 503) res.set_header("Retry-After", "1");
    return res;
  } catch (const RequestError& e) {
    HttpResponse res;
    res.status = e.kind() == RequestError::Kind::unprocessable ? 422 : e.kind() == RequestError::Kind::too_large ? 413 : 400;
    res.content_type = "application/json";
    res.body = dump(error_body(e));
    return res;
  }
}

void log_internal_error(const std::string& where, const std::exception_ptr& error) {
  std::string cause = "an exception of unknown type";
  try {
    if (error) std::rethrow_exception(error);
  } catch (const std::exception& e) {
    cause = e.what();
  } catch (...) {
  }
  std::fprintf(stderr, "lienewton-server: internal error in %s: %s\n", where.c_str(), cause.c_str());
}

}  // namespace lienewton::service
