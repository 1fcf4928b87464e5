#pragma once
// The dashboard's static files, served only from inside the web root (no "..", no symlinks leading out).
#include <string>

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace lienewton::service {

// Answers req from web_root: 200 (or 206 for one valid byte range), 404 or 416. Never leaves the root.
void serve_static(const std::string& web_root, const httplib::Request& req, httplib::Response& res);

// The file a URL path maps to, or "" when the path is not allowed or not a regular file inside the root.
std::string resolve_static_path(const std::string& web_root, const std::string& url_path);

}  // namespace lienewton::service
