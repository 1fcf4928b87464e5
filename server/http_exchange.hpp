#pragma once
// What a handler sees of HTTP and what it gives back: a small request value in, a response value (or a record
// stream) out. Only the transport (http_server.cpp) translates these to and from cpp-httplib.
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lienewton::service {

// Header names compare without regard to case (RFC 9110 5.1).
struct CaseInsensitiveLess {
  bool operator()(const std::string& a, const std::string& b) const;
};
using HeaderMap = std::multimap<std::string, std::string, CaseInsensitiveLess>;

struct HttpRequest {
  std::string method;
  std::string path;
  std::multimap<std::string, std::string> params;  // query parameters
  HeaderMap headers;
  std::vector<std::pair<long long, long long>> ranges;  // parsed Range header; -1 marks an open end
  std::string body;
  // The client's address: the TCP peer, or the X-Real-IP a trusted front forwarded (long-work slots per client).
  std::string client;
  // The connection's socket on long-work routes (-1 elsewhere): watched for a client that leaves mid-work.
  int socket = -1;

  bool has_header(const std::string& name) const { return headers.count(name) > 0; }
  std::size_t header_count(const std::string& name) const { return headers.count(name); }
  // The first value of the header, "" when absent.
  std::string header(const std::string& name) const;
};

// Writes one chunk of a streamed body; false once the client has gone.
using ChunkSink = std::function<bool(std::string_view chunk)>;
// Produces a streamed body through the sink, on the connection's own worker; returns false to abort the
// connection (the client went away), true when the body is complete.
using BodyStream = std::function<bool(const ChunkSink& sink)>;

struct HttpResponse {
  int status = 200;  // 206: the transport slices the body to the request's single byte range
  std::string content_type;
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
  BodyStream stream;  // when set, the body is sent chunked from it and `body` is unused

  void set_header(std::string name, std::string value) { headers.emplace_back(std::move(name), std::move(value)); }
};

}  // namespace lienewton::service
