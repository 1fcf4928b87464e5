#include "server/request_limits.hpp"

#include <gtest/gtest.h>

namespace lienewton::service {
namespace {

HttpRequest request(std::initializer_list<std::pair<const char*, const char*>> headers) {
  HttpRequest r;
  r.method = "POST";
  for (const auto& [k, v] : headers) r.headers.emplace(k, v);
  return r;
}

int status_of(const HttpRequest& r, BodyKind kind = BodyKind::json, std::size_t max_body = 100) {
  auto rejection = check_body_rules(r, kind, max_body);
  return rejection ? rejection->status : 0;
}

TEST(RequestLimits, BodyRules) {
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}, {"Content-Type", "application/json"}})), 0);
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}})), 0);
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}, {"Content-Type", "application/x-www-form-urlencoded"}})), 0);
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}, {"Content-Type", "Application/JSON; charset=utf-8"}})), 0);
  EXPECT_EQ(status_of(request({})), 411);
  EXPECT_EQ(status_of(request({{"Transfer-Encoding", "chunked"}})), 411);
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}, {"Content-Encoding", "gzip"}})), 415);
  EXPECT_EQ(status_of(request({{"Content-Length", "101"}})), 413);
  EXPECT_EQ(status_of(request({{"Content-Length", "99999999999999999999999"}})), 400);
  EXPECT_EQ(status_of(request({{"Content-Length", "-1"}})), 400);
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}, {"Content-Type", "text/xml"}})), 415);
  EXPECT_EQ(status_of(request({{"Content-Length", "10"}, {"Content-Type", "multipart/form-data; boundary=x"}})), 415);
  EXPECT_EQ(status_of(request({{"Content-Length", "5"}}), BodyKind::none), 400);
  auto ranged = request({});
  ranged.ranges = {{0, 1}, {5, 9}};
  EXPECT_EQ(status_of(ranged, BodyKind::none), 416);
}

TEST(RequestLimits, RequestIds) {
  EXPECT_TRUE(valid_request_id("abc-DEF_1.2"));
  EXPECT_TRUE(valid_request_id(std::string(64, 'a')));
  EXPECT_FALSE(valid_request_id(std::string(65, 'a')));
  EXPECT_FALSE(valid_request_id(""));
  EXPECT_FALSE(valid_request_id("a b"));
  EXPECT_FALSE(valid_request_id("a\"b"));
  EXPECT_FALSE(valid_request_id("a\nb"));
  const std::string id = generate_request_id();
  EXPECT_TRUE(valid_request_id(id));
  EXPECT_NE(id, generate_request_id());
}

}  // namespace
}  // namespace lienewton::service
