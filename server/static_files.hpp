#pragma once
// The dashboard's static files, served only from inside the web root (no "..", no symlinks leading out).
#include <string>

#include "server/http_exchange.hpp"

namespace lienewton::service {

// Answers req from web_root: 200 (or 206 for one valid byte range), 404 or 416. Never leaves the root.
HttpResponse serve_static(const std::string& web_root, const HttpRequest& req);

// The file a URL path maps to, or "" when the path is not allowed or not a regular file inside the root.
std::string resolve_static_path(const std::string& web_root, const std::string& url_path);

}  // namespace lienewton::service
