#include "sims/io/http_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "sims/core/error.h"
#include "sims/core/log.h"

namespace sims::io {

std::string ContentTypeFor(const std::filesystem::path& path) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".json", "application/json"},
      {".css", "text/css; charset=utf-8"},
      {".glb", "model/gltf-binary"},
      {".gltf", "model/gltf+json"},
      {".bin", "application/octet-stream"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".svg", "image/svg+xml"},
      {".mp4", "video/mp4"},
      {".bvh", "text/plain; charset=utf-8"},
      {".csv", "text/csv; charset=utf-8"},
      {".txt", "text/plain; charset=utf-8"},
  };
  auto it = types.find(path.extension().string());
  return it != types.end() ? it->second : "application/octet-stream";
}

namespace {

constexpr int kPollMs = 100;
constexpr int kIdleTimeoutMs = 10000;

std::string UrlDecode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(s[i + 1]) && std::isxdigit(s[i + 2])) {
      out.push_back(static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

bool SendAll(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = send(fd, data, n, MSG_NOSIGNAL);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

}  // namespace

struct StaticHttpServer::Impl {
  std::filesystem::path root;
  std::string host;
  int port = 0;
  int listen_fd = -1;
  std::atomic<bool> stop{false};
  std::atomic<int> requests{0};
  std::thread acceptor;
  std::mutex mu;
  struct Worker {
    std::thread thread;
    std::shared_ptr<std::atomic<bool>> done;
  };
  std::vector<Worker> workers;

  void AcceptLoop() {
    while (!stop) {
      pollfd p{listen_fd, POLLIN, 0};
      if (poll(&p, 1, kPollMs) <= 0) continue;
      const int fd = accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd < 0) continue;
      std::lock_guard<std::mutex> lock(mu);
      // Reap finished connections so a long viewing session does not pile up threads.
      for (auto it = workers.begin(); it != workers.end();) {
        if (it->done->load()) {
          it->thread.join();
          it = workers.erase(it);
        } else {
          ++it;
        }
      }
      auto done = std::make_shared<std::atomic<bool>>(false);
      workers.push_back({std::thread([this, fd, done] {
                           Serve(fd);
                           close(fd);
                           *done = true;
                         }),
                         done});
    }
  }

  // Reads one request head; false on timeout, stop or a closed connection.
  bool ReadHead(int fd, std::string* head) {
    int idle = 0;
    char buf[4096];
    while (head->find("\r\n\r\n") == std::string::npos) {
      if (stop || idle > kIdleTimeoutMs || head->size() > 65536) return false;
      pollfd p{fd, POLLIN, 0};
      const int r = poll(&p, 1, kPollMs);
      if (r == 0) {
        idle += kPollMs;
        continue;
      }
      const ssize_t n = recv(fd, buf, sizeof(buf), 0);
      if (n <= 0) return false;
      head->append(buf, static_cast<std::size_t>(n));
    }
    return true;
  }

  void Respond(int fd, int code, const std::string& reason, const std::string& type,
               const std::string& body, bool head_only, bool keep_alive) {
    std::ostringstream h;
    h << "HTTP/1.1 " << code << " " << reason << "\r\nContent-Type: " << type
      << "\r\nContent-Length: " << body.size()
      << "\r\nCache-Control: no-cache\r\nConnection: " << (keep_alive ? "keep-alive" : "close")
      << "\r\n\r\n";
    const std::string hs = h.str();
    if (SendAll(fd, hs.data(), hs.size()) && !head_only) SendAll(fd, body.data(), body.size());
    ++requests;
  }

  void Serve(int fd) {
    std::string pending;
    for (;;) {
      if (!ReadHead(fd, &pending)) return;
      const std::size_t end = pending.find("\r\n\r\n");
      const std::string head = pending.substr(0, end);
      pending.erase(0, end + 4);
      std::istringstream in(head);
      std::string method, target, version;
      in >> method >> target >> version;
      std::string lower = head;
      for (auto& c : lower) c = static_cast<char>(std::tolower(c));
      const bool keep_alive =
          version == "HTTP/1.1" && lower.find("connection: close") == std::string::npos;
      if (method != "GET" && method != "HEAD") {
        Respond(fd, 405, "Method Not Allowed", "text/plain", "GET or HEAD only\n", false, false);
        return;
      }
      const bool head_only = method == "HEAD";
      std::string path = UrlDecode(target.substr(0, target.find_first_of("?#")));
      if (path.empty() || path[0] != '/') path = "/" + path;
      if (path.back() == '/') path += "index.html";
      // Refuse anything that could leave the root.
      bool bad = path.find('\0') != std::string::npos;
      std::istringstream parts(path);
      for (std::string seg; std::getline(parts, seg, '/');) bad = bad || seg == "..";
      const std::filesystem::path file = root / path.substr(1);
      std::string body;
      if (!bad && std::filesystem::is_regular_file(file)) {
        std::ifstream f(file, std::ios::binary);
        body.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
        Respond(fd, 200, "OK", ContentTypeFor(file), body, head_only, keep_alive);
      } else {
        spdlog::debug("http: 404 {}", path);
        Respond(fd, 404, "Not Found", "text/plain", "not found: " + path + "\n", head_only,
                keep_alive);
      }
      if (!keep_alive) return;
    }
  }
};

StaticHttpServer::StaticHttpServer(std::filesystem::path root, int port, const std::string& host)
    : impl_(std::make_unique<Impl>()) {
  impl_->root = std::move(root);
  impl_->host = host;
  const std::string where = host + ":" + std::to_string(port);
  if (!std::filesystem::is_directory(impl_->root))
    ThrowInputError(impl_->root.string(), "", "a folder to serve", "no such folder");
  impl_->listen_fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (impl_->listen_fd < 0) ThrowInputError(where, "", "a TCP socket", std::strerror(errno));
  const int one = 1;
  setsockopt(impl_->listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  if (inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1) {
    close(impl_->listen_fd);
    ThrowInputError(where, "host", "an IPv4 address such as 127.0.0.1", host);
  }
  if (bind(impl_->listen_fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
      listen(impl_->listen_fd, 64) != 0) {
    const std::string err = std::strerror(errno);
    close(impl_->listen_fd);
    ThrowInputError(where, "", "a free address to listen on", err);
  }
  socklen_t len = sizeof(addr);
  getsockname(impl_->listen_fd, reinterpret_cast<sockaddr*>(&addr), &len);
  impl_->port = ntohs(addr.sin_port);
  impl_->acceptor = std::thread([this] { impl_->AcceptLoop(); });
}

StaticHttpServer::~StaticHttpServer() {
  impl_->stop = true;
  impl_->acceptor.join();
  close(impl_->listen_fd);
  std::vector<Impl::Worker> workers;
  {
    std::lock_guard<std::mutex> lock(impl_->mu);
    workers.swap(impl_->workers);
  }
  for (auto& w : workers) w.thread.join();
}

int StaticHttpServer::port() const { return impl_->port; }

std::string StaticHttpServer::url() const {
  return "http://" + impl_->host + ":" + std::to_string(impl_->port) + "/";
}

int StaticHttpServer::requests() const { return impl_->requests.load(); }

}  // namespace sims::io
