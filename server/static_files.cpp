#include "server/static_files.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "server/http_errors.hpp"
#include "server/http_validators.hpp"

namespace lienewton::service {
namespace {

constexpr std::uintmax_t kMaxFileSize = 32u << 20;
// Browsers keep the file but ask again each time; the ETag turns an unchanged file into a body-less 304.
constexpr const char* kStaticCacheControl = "no-cache";

// The dashboard runs only its own files: ES modules and style sheets from this origin, no inline script or
// style (it sets styles through the CSSOM, which CSP does not govern), rendered images as blob: URLs, the
// favicon as data:, requests only to this origin, and no page may frame it (clickjacking). The referrer goes
// to this origin only: a dashboard URL holds the request, a user's program included; and "no-referrer" would
// make browsers send "Origin: null" on the dashboard's POSTs, which the same-origin check refuses.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' blob: data:; connect-src 'self'; "
    "font-src 'self'; object-src 'none'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'";

void set_page_security_headers(HttpResponse& res) {
  res.set_header("Content-Security-Policy", kContentSecurityPolicy);
  res.set_header("X-Frame-Options", "DENY");
  res.set_header("Referrer-Policy", "same-origin");
}

std::string content_type(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".woff2") return "font/woff2";
  if (ext == ".txt" || ext == ".md") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

bool inside(const std::filesystem::path& root, const std::filesystem::path& file) {
  auto r = root.begin();
  auto f = file.begin();
  for (; r != root.end(); ++r, ++f) {
    if (f == file.end() || *r != *f) return false;
  }
  return true;
}

}  // namespace

std::string resolve_static_path(const std::string& web_root, const std::string& url_path) {
  namespace fs = std::filesystem;
  if (url_path.empty() || url_path[0] != '/' || url_path.find('\0') != std::string::npos ||
      url_path.find('\\') != std::string::npos) {
    return "";
  }
  fs::path relative;
  std::size_t start = 1;
  while (start <= url_path.size()) {
    const auto slash = url_path.find('/', start);
    const std::string segment = url_path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (segment == "..") return "";
    if (!segment.empty() && segment != ".") {
      if (segment[0] == '.') return "";  // no dotfiles (.git, .env, ...)
      relative /= segment;
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  std::error_code ec;
  const fs::path root = fs::canonical(web_root, ec);
  if (ec) return "";
  fs::path file = root / relative;
  if (fs::is_directory(file, ec)) file /= "index.html";
  // canonical() follows symlinks, so a link pointing out of the root is caught by the prefix check.
  const fs::path real = fs::canonical(file, ec);
  if (ec || !inside(root, real) || !fs::is_regular_file(real, ec)) return "";
  return real.string();
}

HttpResponse serve_static(const std::string& web_root, const HttpRequest& req) {
  namespace fs = std::filesystem;
  const std::string file = resolve_static_path(web_root, req.path);
  std::error_code ec;
  const auto size = file.empty() ? 0 : fs::file_size(file, ec);
  if (file.empty() || ec || size > kMaxFileSize) return error_response(404, "not_found", "", "no such route or file: " + req.path);
  std::ifstream in(file, std::ios::binary);
  std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return error_response(404, "not_found", "", "no such route or file: " + req.path);
  const std::string etag = content_etag(body);
  // If-None-Match is evaluated before Range (RFC 9110 13.2.2).
  if (none_match_fails(req, etag, true)) return not_modified(etag, kStaticCacheControl);
  HttpResponse res;
  set_page_security_headers(res);
  res.set_header("ETag", etag);
  if (req.ranges.size() == 1) {
    // The transport slices a 206 body to the single range; an unsatisfiable range is answered here.
    const auto [first, last] = req.ranges[0];
    const auto n = static_cast<long long>(body.size());
    const bool ok = first < 0 ? last > 0 : (first < n && (last < 0 || last >= first));
    if (!ok) {
      res = error_response(416, "range_not_satisfiable", "", "the requested byte range is outside the file");
      res.set_header("Content-Range", "bytes */" + std::to_string(body.size()));
      return res;
    }
    res.status = 206;
  }
  res.set_header("Cache-Control", kStaticCacheControl);
  res.content_type = content_type(file);
  res.body = std::move(body);
  return res;
}

}  // namespace lienewton::service
