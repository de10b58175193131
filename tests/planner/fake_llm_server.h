// A tiny HTTP server on 127.0.0.1 for the planner's endpoint tests (LLM planner, video VLM,
// imitation): it replays canned responses, one per connection, optionally after a delay, and
// records the requests it received.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace sims::planner::test_support {

/// A complete "200 OK" response with a JSON body.
inline std::string HttpOk(const std::string& body) {
  return "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: " +
         std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body;
}

/// A chat-completions response whose choices[0].message.content is `content`.
inline std::string ChatOk(const std::string& content) {
  nlohmann::json body = {
      {"choices", {{{"index", 0}, {"message", {{"role", "assistant"}, {"content", content}}}}}}};
  return HttpOk(body.dump());
}

/// Serves one canned response per connection, in order, from a thread.
class FakeServer {
 public:
  struct Reply {
    std::string raw;   // full HTTP response
    int delay_ms = 0;  // wait before answering (the client may give up first)
  };
  explicit FakeServer(std::vector<Reply> replies) : replies_(std::move(replies)) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    int one = 1;
    ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    EXPECT_EQ(::listen(fd_, 4), 0);
    socklen_t len = sizeof(addr);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] { Serve(); });
  }
  ~FakeServer() {
    stop_ = true;
    thread_.join();
    ::close(fd_);
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }
  std::vector<std::string> requests() const {
    std::lock_guard<std::mutex> lock(mu_);
    return requests_;
  }

 private:
  void Serve() {
    for (const Reply& r : replies_) {
      int client = -1;
      while (!stop_ && client < 0) {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, 20) > 0) client = ::accept(fd_, nullptr, nullptr);
      }
      if (client < 0) return;
      std::string req = ReadRequest(client);
      {
        std::lock_guard<std::mutex> lock(mu_);
        requests_.push_back(req);
      }
      auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(r.delay_ms);
      while (!stop_ && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      std::size_t sent = 0;
      while (sent < r.raw.size()) {
        ssize_t n = ::send(client, r.raw.data() + sent, r.raw.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) break;
        sent += static_cast<std::size_t>(n);
      }
      ::close(client);
    }
  }
  static std::string ReadRequest(int fd) {
    std::string raw;
    char buf[4096];
    for (;;) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 2000) <= 0) break;
      ssize_t n = ::recv(fd, buf, sizeof(buf), 0);
      if (n <= 0) break;
      raw.append(buf, static_cast<std::size_t>(n));
      std::size_t end = raw.find("\r\n\r\n");
      if (end == std::string::npos) continue;
      std::size_t cl = raw.find("Content-Length: ");
      std::size_t length = cl == std::string::npos ? 0 : std::stoul(raw.substr(cl + 16));
      if (raw.size() >= end + 4 + length) break;
    }
    return raw;
  }
  std::vector<Reply> replies_;
  int fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex mu_;
  std::vector<std::string> requests_;
};

}  // namespace sims::planner::test_support
