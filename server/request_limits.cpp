#include "server/request_limits.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <random>

namespace lienewton::service {
namespace {

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The media type without parameters, lower case.
std::string media_type(const std::string& content_type) {
  std::string t = content_type.substr(0, content_type.find(';'));
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.pop_back();
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.erase(t.begin());
  return lower(t);
}

}  // namespace

std::optional<Rejection> check_body_rules(const HttpRequest& req, BodyKind kind, std::size_t max_body) {
  if (req.has_header("Transfer-Encoding")) {
    return Rejection{411, "length_required", "request bodies must be sent with Content-Length, not Transfer-Encoding"};
  }
  if (req.has_header("Content-Encoding")) {
    return Rejection{415, "unsupported_content_encoding", "compressed request bodies are not accepted"};
  }
  const bool has_length = req.has_header("Content-Length");
  std::size_t length = 0;
  if (has_length) {
    if (req.header_count("Content-Length") != 1) {
      return Rejection{400, "invalid_content_length", "Content-Length must be given once"};
    }
    const std::string text = req.header("Content-Length");
    if (text.empty() || text.size() > 19) return Rejection{400, "invalid_content_length", "Content-Length is not a number"};
    for (char c : text) {
      if (c < '0' || c > '9') return Rejection{400, "invalid_content_length", "Content-Length is not a number"};
    }
    length = std::stoull(text);
    if (length > max_body) {
      return Rejection{413, "body_too_large",
                       "the request body is larger than the limit of " + std::to_string(max_body) + " bytes"};
    }
  }
  if (kind == BodyKind::json) {
    if (!has_length) return Rejection{411, "length_required", "POST requests need a Content-Length header"};
    // curl -d sends application/x-www-form-urlencoded; the body is still parsed as JSON.
    const std::string type = media_type(req.header("Content-Type"));
    if (!type.empty() && type != "application/json" && type != "application/x-www-form-urlencoded") {
      return Rejection{415, "unsupported_media_type", "the request body must be application/json"};
    }
  } else if (length > 0) {
    return Rejection{400, "unexpected_body", "this route takes no request body"};
  }
  if (req.ranges.size() > 1) {
    return Rejection{416, "multiple_ranges", "only a single byte range may be requested"};
  }
  return std::nullopt;
}

std::optional<Rejection> check_same_origin(const HttpRequest& req) {
  if (lower(req.header("Sec-Fetch-Site")) == "cross-site") {
    return Rejection{403, "cross_site", "requests from another site may not start work here"};
  }
  if (req.has_header("Origin")) {
    const std::string origin = lower(req.header("Origin"));
    const std::size_t scheme = origin.find("://");
    const std::string authority = scheme == std::string::npos ? "" : origin.substr(scheme + 3);
    if (authority.empty() || authority != lower(req.header("Host"))) {
      return Rejection{403, "cross_site", "the Origin header does not match the Host this request was sent to"};
    }
  }
  return std::nullopt;
}

double accept_quality(std::string_view accept, std::string_view type, bool exact) {
  const std::string wanted = lower(std::string(type));
  const std::string family = wanted.substr(0, wanted.find('/')) + "/*";
  int best = -1;  // 2: type/subtype, 1: type/*, 0: */*
  double quality = 0;
  std::size_t start = 0;
  while (start <= accept.size()) {
    const std::size_t comma = std::min(accept.find(',', start), accept.size());
    const std::string range(accept.substr(start, comma - start));
    start = comma + 1;
    const std::string name = media_type(range);
    const int rank = name == wanted ? 2 : exact ? -1 : name == family ? 1 : name == "*/*" ? 0 : -1;
    if (rank <= best) continue;
    double q = 1;
    for (std::size_t semi = range.find(';'); semi != std::string::npos; semi = range.find(';', semi + 1)) {
      std::string parameter = lower(range.substr(semi + 1, range.find(';', semi + 1) - semi - 1));
      parameter.erase(std::remove_if(parameter.begin(), parameter.end(), [](char c) { return c == ' ' || c == '\t'; }),
                      parameter.end());
      if (parameter.rfind("q=", 0) == 0) {
        char* end = nullptr;
        q = std::strtod(parameter.c_str() + 2, &end);
        if (end == parameter.c_str() + 2 || *end != '\0' || !(q >= 0 && q <= 1)) q = 0;  // malformed: not acceptable
      }
    }
    best = rank;
    quality = q;
  }
  return quality;
}

bool valid_request_id(std::string_view id) {
  if (id.empty() || id.size() > 64) return false;
  for (char c : id) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::string generate_request_id() {
  thread_local std::mt19937_64 rng{std::random_device{}()};
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id(16, '0');
  auto bits = rng();
  for (auto& c : id) {
    c = kHex[bits & 15];
    bits >>= 4;
  }
  return id;
}

}  // namespace lienewton::service
