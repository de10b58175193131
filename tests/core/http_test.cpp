#include "sims/core/http.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

namespace sims::http {
namespace {

// The client against the server: a POST body arrives whole with its headers, the reply comes
// back; the handler sees the decoded path; a throwing handler gives a 500, not a dead server.
TEST(HttpTest, ClientAndServerRoundTrip) {
  Server server("127.0.0.1", 0, [](const Request& r) -> Reply {
    if (r.path == "/fail") throw Error("handler broke");
    const auto auth = r.headers.find("authorization");
    return {200, "OK", "application/json",
            r.method + " " + r.path + " " + r.body + " " +
                (auth == r.headers.end() ? "-" : auth->second)};
  });
  ASSERT_GT(server.port(), 0);
  const std::string big(100000, 'x');  // several TCP segments
  Response a = Post(server.url() + "a%20b?q=1", {{"Authorization", "Bearer k"}}, big, 5.0);
  EXPECT_EQ(a.status, 200);
  EXPECT_EQ(a.body, "POST /a b " + big + " Bearer k");
  Response b = Post(server.url() + "fail", {}, "{}", 5.0);
  EXPECT_EQ(b.status, 500);
  EXPECT_NE(b.body.find("handler broke"), std::string::npos);
  EXPECT_EQ(server.requests(), 2);
}

TEST(HttpTest, SlowServerTimesOutAndClosedPortRefuses) {
  int port = 0;
  {
    Server slow("127.0.0.1", 0, [](const Request&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(800));
      return Reply{};
    });
    port = slow.port();
    const auto start = std::chrono::steady_clock::now();
    try {
      Post(slow.url(), {}, "{}", 0.2);
      FAIL() << "no time-out";
    } catch (const HttpError& e) {
      EXPECT_EQ(e.kind(), HttpError::Kind::kTimeout);
      EXPECT_NE(std::string(e.what()).find("timed out"), std::string::npos);
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.7);
  }
  try {
    Post("http://127.0.0.1:" + std::to_string(port) + "/", {}, "{}", 2.0);
    FAIL() << "connected to a closed port";
  } catch (const HttpError& e) {
    EXPECT_EQ(e.kind(), HttpError::Kind::kConnect);
  }
}

TEST(HttpTest, UrlsAndBadAddresses) {
  const Url u = ParseUrl("http://localhost:8080/v1/x?y=1");
  EXPECT_EQ(u.host, "localhost");
  EXPECT_EQ(u.port, 8080);
  EXPECT_EQ(u.path, "/v1/x?y=1");
  EXPECT_EQ(ParseUrl("http://h").path, "/");
  EXPECT_EQ(ParseUrl("http://[::1]:9000/").host, "::1");
  for (const char* bad : {"https://h/", "ftp://h", "http://h:0/", "http://h:/", "http://[::1/"}) {
    try {
      ParseUrl(bad);
      FAIL() << bad;
    } catch (const HttpError& e) {
      EXPECT_EQ(e.kind(), HttpError::Kind::kConfig) << bad;
    }
  }
  EXPECT_EQ(UrlDecode("a%20b%2Fc%zz"), "a b/c%zz");
  EXPECT_THROW(Server("not-an-ip", 0, [](const Request&) { return Reply{}; }), Error);
}

}  // namespace
}  // namespace sims::http
