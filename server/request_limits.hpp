#pragma once
// Body and header rules checked before cpp-httplib 0.11.4 reads a request body. That version caps only
// Content-Length bodies (a chunked body bypasses the cap), inflates Content-Encoding bodies without a cap and
// turns multi-range requests into large multipart copies, so all of these are refused up front.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "server/http_exchange.hpp"

namespace lienewton::service {

struct Rejection {
  int status;
  std::string code;
  std::string message;
};

// kind: what the matched route accepts.
enum class BodyKind { none, json };

std::optional<Rejection> check_body_rules(const HttpRequest& request, BodyKind kind, std::size_t max_body);

// Long work must not be started by another site's page (an <img src>, a form posted cross-site): refuses
// Sec-Fetch-Site: cross-site, and an Origin whose host[:port] is not the request's Host (or "null"), with 403.
std::optional<Rejection> check_same_origin(const HttpRequest& request);

// The quality (RFC 9110 12.5.1) an Accept header gives a media type: that of the most specific range matching it
// (type/subtype, then type/*, then */*), names compared case-insensitively; 0 when none does. exact: only a range
// naming the type itself counts.
double accept_quality(std::string_view accept, std::string_view type, bool exact = false);

// Accepts ^[A-Za-z0-9._-]{1,64}$ only, so the id can be echoed and logged verbatim.
bool valid_request_id(std::string_view id);
std::string generate_request_id();

}  // namespace lienewton::service
