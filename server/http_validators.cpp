#include "server/http_validators.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

namespace lienewton::service {
namespace {

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = 14695981039346656037ull) {
  for (const unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

// Weak (W/): the transport may gzip text bodies, and the gzipped and plain bodies share the tag.
std::string weak_tag(std::uint64_t value) {
  char text[21];
  std::snprintf(text, sizeof text, "W/\"%016llx\"", static_cast<unsigned long long>(value));
  return text;
}

// Drops a weak prefix and surrounding blanks: "W/\"x\"" and "\"x\"" compare equal under weak comparison.
std::string_view opaque_tag(std::string_view tag) {
  while (!tag.empty() && (tag.front() == ' ' || tag.front() == '\t')) tag.remove_prefix(1);
  while (!tag.empty() && (tag.back() == ' ' || tag.back() == '\t')) tag.remove_suffix(1);
  if (tag.substr(0, 2) == "W/") tag.remove_prefix(2);
  return tag;
}

}  // namespace

std::string content_etag(std::string_view bytes) { return weak_tag(fnv1a(bytes)); }

const std::string& build_id() {
  // Read in blocks: the sanitizer build's binary is ~100 MB, which a character-by-character read took 20 s over.
  static const std::string id = [] {
    std::ifstream in("/proc/self/exe", std::ios::binary);
    std::vector<char> block(1 << 20);
    std::uint64_t hash = fnv1a({});
    while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0)
      hash = fnv1a(std::string_view(block.data(), static_cast<std::size_t>(in.gcount())), hash);
    return hex(hash);
  }();
  return id;
}

bool none_match_fails(const HttpRequest& req, const std::string& etag, bool star_matches) {
  const std::string_view wanted = opaque_tag(etag);
  for (auto [it, end] = req.headers.equal_range("If-None-Match"); it != end; ++it) {
    std::string_view list = it->second;
    while (!list.empty()) {
      const auto comma = list.find(',');
      const std::string_view tag = opaque_tag(list.substr(0, comma));
      if (tag == wanted || (star_matches && tag == "*")) return true;
      if (comma == std::string_view::npos) break;
      list.remove_prefix(comma + 1);
    }
  }
  return false;
}

HttpResponse not_modified(const std::string& etag, const std::string& cache_control) {
  HttpResponse res;
  res.status = 304;
  res.set_header("ETag", etag);
  res.set_header("Cache-Control", cache_control);
  return res;
}

}  // namespace lienewton::service
