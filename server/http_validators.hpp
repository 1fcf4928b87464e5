#pragma once
// HTTP validators (RFC 9110 8.8.3, 13.1.2): ETags from a content hash, and the If-None-Match check that
// turns a repeated GET into 304 Not Modified.
#include <string>
#include <string_view>

#include "server/http_exchange.hpp"

namespace lienewton::service {

// A weak entity tag W/"<16 hex digits>" of the bytes' 64-bit FNV-1a hash: equal bytes give equal tags in any
// build. Weak because the transport may send the same body gzipped (RFC 9110 8.8.3.3); If-None-Match compares
// weakly anyway.
std::string content_etag(std::string_view bytes);

// A hash of the running server binary, read once: a render's tag mixes it in, so a new build never answers 304
// for a picture an older build drew.
const std::string& build_id();

// True when the request's If-None-Match lists etag (weak comparison, as RFC 9110 13.1.2 asks for GET), or is "*"
// and star_matches (the representation is known to exist, e.g. a file; a render is not known until it is drawn).
bool none_match_fails(const HttpRequest& req, const std::string& etag, bool star_matches);

// 304 with the validator and caching headers a 200 would carry, and no body.
HttpResponse not_modified(const std::string& etag, const std::string& cache_control);

}  // namespace lienewton::service
