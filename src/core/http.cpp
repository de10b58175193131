#include "sims/core/http.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <sstream>
#include <thread>

namespace sims::http {

namespace {

using Clock = std::chrono::steady_clock;

std::string Lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

class Socket {
 public:
  explicit Socket(int fd) : fd_(fd) {}
  ~Socket() {
    if (fd_ >= 0) ::close(fd_);
  }
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

int RemainingMs(Clock::time_point deadline) {
  auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return ms <= 0 ? 0 : static_cast<int>(std::min<long long>(ms, 1 << 30));
}

// Waits for `events` on fd until the deadline; throws a time-out error when it passes.
void Wait(int fd, short events, Clock::time_point deadline, const std::string& what) {
  for (;;) {
    const int ms = RemainingMs(deadline);
    if (ms == 0) throw HttpError(HttpError::Kind::kTimeout, "request timed out while " + what);
    pollfd p{fd, events, 0};
    const int r = ::poll(&p, 1, ms);
    if (r > 0) return;
    if (r == 0) throw HttpError(HttpError::Kind::kTimeout, "request timed out while " + what);
    if (errno != EINTR)
      throw HttpError(HttpError::Kind::kConnect,
                      std::string("poll failed: ") + std::strerror(errno));
  }
}

int Connect(const Url& u, Clock::time_point deadline) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  const std::string port = std::to_string(u.port);
  const int rc = ::getaddrinfo(u.host.c_str(), port.c_str(), &hints, &res);
  if (rc != 0)
    throw HttpError(HttpError::Kind::kConnect,
                    "cannot resolve host '" + u.host + "': " + ::gai_strerror(rc));
  std::string last_error = "no address";
  for (addrinfo* a = res; a; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL, 0) | O_NONBLOCK);
    if (::connect(fd, a->ai_addr, a->ai_addrlen) == 0) {
      ::freeaddrinfo(res);
      return fd;
    }
    if (errno == EINPROGRESS) {
      try {
        Wait(fd, POLLOUT, deadline, "connecting to " + u.host + ":" + port);
      } catch (...) {
        ::close(fd);
        ::freeaddrinfo(res);
        throw;
      }
      int err = 0;
      socklen_t len = sizeof(err);
      ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len);
      if (err == 0) {
        ::freeaddrinfo(res);
        return fd;
      }
      last_error = std::strerror(err);
    } else {
      last_error = std::strerror(errno);
    }
    ::close(fd);
  }
  ::freeaddrinfo(res);
  throw HttpError(HttpError::Kind::kConnect,
                  "cannot connect to " + u.host + ":" + port + ": " + last_error);
}

// Decodes a chunked body; false while the terminating zero-size chunk has not arrived.
bool DecodeChunked(const std::string& body, std::string* out) {
  out->clear();
  std::size_t pos = 0;
  for (;;) {
    const std::size_t eol = body.find("\r\n", pos);
    if (eol == std::string::npos) return false;
    char* end = nullptr;
    const std::string size_text = body.substr(pos, eol - pos);
    const unsigned long size = std::strtoul(size_text.c_str(), &end, 16);
    if (end == size_text.c_str())
      throw HttpError(HttpError::Kind::kProtocol,
                      "bad chunk size '" + size_text.substr(0, 20) + "'");
    pos = eol + 2;
    if (size == 0) return true;
    if (pos + size + 2 > body.size()) return false;
    out->append(body, pos, size);
    pos += size + 2;
  }
}

// True when `raw` holds a complete response; fills status and body then.
bool ParseResponse(const std::string& raw, bool eof, Response* out) {
  const std::size_t end = raw.find("\r\n\r\n");
  if (end == std::string::npos) {
    if (eof)
      throw HttpError(HttpError::Kind::kProtocol,
                      "connection closed before the HTTP headers ended");
    return false;
  }
  const std::string head = raw.substr(0, end);
  const std::string body = raw.substr(end + 4);
  const std::size_t sp = head.find(' ');
  if (head.rfind("HTTP/", 0) != 0 || sp == std::string::npos)
    throw HttpError(HttpError::Kind::kProtocol,
                    "not an HTTP response: '" + head.substr(0, 40) + "'");
  const int status = std::atoi(head.c_str() + sp + 1);
  const std::string lower = Lower(head);
  const bool chunked = lower.find("\r\ntransfer-encoding: chunked") != std::string::npos;
  long long length = -1;
  const std::size_t cl = lower.find("\r\ncontent-length:");
  if (cl != std::string::npos) length = std::atoll(lower.c_str() + cl + 17);
  if (chunked) {
    if (!DecodeChunked(body, &out->body)) {
      if (eof)
        throw HttpError(HttpError::Kind::kProtocol, "connection closed inside a chunked body");
      return false;
    }
  } else if (length >= 0) {
    if (static_cast<long long>(body.size()) < length) {
      if (eof)
        throw HttpError(HttpError::Kind::kProtocol, "connection closed before the body ended");
      return false;
    }
    out->body = body.substr(0, static_cast<std::size_t>(length));
  } else {
    if (!eof) return false;  // the body runs to the end of the connection
    out->body = body;
  }
  out->status = status;
  return true;
}

bool SendAll(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::send(fd, data, n, MSG_NOSIGNAL);
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

Url ParseUrl(const std::string& url) {
  const std::string scheme = "http://";
  if (url.rfind("https://", 0) == 0)
    throw HttpError(HttpError::Kind::kConfig,
                    "'" + url +
                        "': https is not supported by the built-in client (plain HTTP/1.1 "
                        "only); use a local server (llama.cpp, vLLM) or a plain-HTTP proxy");
  if (url.rfind(scheme, 0) != 0)
    throw HttpError(HttpError::Kind::kConfig,
                    "'" + url + "': expected an http://host[:port]/path URL");
  Url u;
  const std::string rest = url.substr(scheme.size());
  const std::size_t slash = rest.find('/');
  const std::string authority = rest.substr(0, slash);
  u.path = slash == std::string::npos ? "/" : rest.substr(slash);
  std::string port;
  if (!authority.empty() && authority.front() == '[') {  // [IPv6]:port
    const std::size_t close = authority.find(']');
    if (close == std::string::npos)
      throw HttpError(HttpError::Kind::kConfig, "'" + url + "': unterminated [address]");
    u.host = authority.substr(1, close - 1);
    if (close + 1 < authority.size() && authority[close + 1] == ':')
      port = authority.substr(close + 2);
    else if (close + 1 < authority.size())
      throw HttpError(HttpError::Kind::kConfig, "'" + url + "': bad authority");
  } else {
    const std::size_t colon = authority.rfind(':');
    u.host = authority.substr(0, colon);
    if (colon != std::string::npos) port = authority.substr(colon + 1);
    if (colon != std::string::npos && port.empty())
      throw HttpError(HttpError::Kind::kConfig, "'" + url + "': empty port");
  }
  if (!port.empty()) {
    char* end = nullptr;
    const long p = std::strtol(port.c_str(), &end, 10);
    if (*end != '\0' || p <= 0 || p > 65535)
      throw HttpError(HttpError::Kind::kConfig, "'" + url + "': bad port '" + port + "'");
    u.port = static_cast<int>(p);
  }
  if (u.host.empty()) throw HttpError(HttpError::Kind::kConfig, "'" + url + "': no host");
  return u;
}

Response Post(const std::string& url,
              const std::vector<std::pair<std::string, std::string>>& headers,
              const std::string& body, double timeout_s) {
  const Url u = ParseUrl(url);
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<long long>(timeout_s * 1000));
  Socket sock(Connect(u, deadline));
  std::string request = "POST " + u.path + " HTTP/1.1\r\nHost: " + u.host + ":" +
                        std::to_string(u.port) +
                        "\r\nContent-Type: application/json\r\nAccept: application/json\r\n"
                        "Connection: close\r\nContent-Length: " +
                        std::to_string(body.size()) + "\r\n";
  for (const auto& [k, v] : headers) request += k + ": " + v + "\r\n";
  request += "\r\n" + body;
  std::size_t sent = 0;
  while (sent < request.size()) {
    Wait(sock.fd(), POLLOUT, deadline, "sending the request");
    const ssize_t n = ::send(sock.fd(), request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      throw HttpError(HttpError::Kind::kConnect,
                      std::string("send failed: ") + std::strerror(errno));
    }
    sent += static_cast<std::size_t>(n);
  }
  std::string raw;
  Response resp;
  char buf[16384];
  for (;;) {
    Wait(sock.fd(), POLLIN, deadline, "waiting for the reply");
    const ssize_t n = ::recv(sock.fd(), buf, sizeof(buf), 0);
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      throw HttpError(HttpError::Kind::kConnect,
                      std::string("recv failed: ") + std::strerror(errno));
    }
    if (n == 0) {
      ParseResponse(raw, true, &resp);
      return resp;
    }
    raw.append(buf, static_cast<std::size_t>(n));
    if (ParseResponse(raw, false, &resp)) return resp;
  }
}

std::string UrlDecode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out.push_back(static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

// ---- server ---------------------------------------------------------------------------------

namespace {
constexpr int kPollMs = 100;
constexpr int kIdleTimeoutMs = 10000;
constexpr std::size_t kMaxHead = 65536;
constexpr std::size_t kMaxBody = 16 << 20;
}  // namespace

struct Server::Impl {
  std::string host;
  int port = 0;
  int listen_fd = -1;
  Handler handler;
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
      if (::poll(&p, 1, kPollMs) <= 0) continue;
      const int fd = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd < 0) continue;
      std::lock_guard<std::mutex> lock(mu);
      // Reap finished connections so a long session does not pile up threads.
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
                           ::close(fd);
                           *done = true;
                         }),
                         done});
    }
  }

  // Reads until `pending` holds `want` bytes (or a head end when want == 0); false on time-out,
  // stop, a closed connection or an oversized head.
  bool ReadMore(int fd, std::string* pending, std::size_t want) {
    int idle = 0;
    char buf[16384];
    auto enough = [&] {
      return want > 0 ? pending->size() >= want : pending->find("\r\n\r\n") != std::string::npos;
    };
    while (!enough()) {
      if (stop || idle > kIdleTimeoutMs || (want == 0 && pending->size() > kMaxHead)) return false;
      pollfd p{fd, POLLIN, 0};
      const int r = ::poll(&p, 1, kPollMs);
      if (r == 0) {
        idle += kPollMs;
        continue;
      }
      const ssize_t n = ::recv(fd, buf, sizeof(buf), 0);
      if (n <= 0) return false;
      pending->append(buf, static_cast<std::size_t>(n));
    }
    return true;
  }

  void Respond(int fd, const Reply& r, bool head_only, bool keep_alive) {
    std::ostringstream h;
    h << "HTTP/1.1 " << r.status << " " << r.reason << "\r\nContent-Type: " << r.content_type
      << "\r\nContent-Length: " << r.body.size()
      << "\r\nCache-Control: no-cache\r\nConnection: " << (keep_alive ? "keep-alive" : "close")
      << "\r\n\r\n";
    const std::string hs = h.str();
    ++requests;  // before sending: a client that has its reply sees it counted
    if (SendAll(fd, hs.data(), hs.size()) && !head_only) SendAll(fd, r.body.data(), r.body.size());
  }

  void Serve(int fd) {
    std::string pending;
    for (;;) {
      if (!ReadMore(fd, &pending, 0)) return;
      const std::size_t end = pending.find("\r\n\r\n");
      const std::string head = pending.substr(0, end);
      pending.erase(0, end + 4);
      Request req;
      std::istringstream lines(head);
      std::string line, version;
      std::getline(lines, line);
      std::istringstream first(line);
      first >> req.method >> req.target >> version;
      while (std::getline(lines, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        std::string value = line.substr(colon + 1);
        value.erase(0, value.find_first_not_of(" \t"));
        req.headers[Lower(line.substr(0, colon))] = value;
      }
      const auto conn = req.headers.find("connection");
      const bool keep_alive =
          version == "HTTP/1.1" && !(conn != req.headers.end() && Lower(conn->second) == "close");
      const auto cl = req.headers.find("content-length");
      if (cl != req.headers.end()) {
        char* stop_at = nullptr;
        const unsigned long long n = std::strtoull(cl->second.c_str(), &stop_at, 10);
        if (stop_at == cl->second.c_str() || n > kMaxBody) {
          Respond(fd, {413, "Payload Too Large", "text/plain", "body too large\n"}, false, false);
          return;
        }
        if (!ReadMore(fd, &pending, static_cast<std::size_t>(n))) return;
        req.body = pending.substr(0, static_cast<std::size_t>(n));
        pending.erase(0, static_cast<std::size_t>(n));
      }
      req.path = UrlDecode(req.target.substr(0, req.target.find_first_of("?#")));
      Reply reply;
      try {
        reply = handler(req);
      } catch (const std::exception& e) {
        reply = {500, "Internal Server Error", "text/plain", std::string(e.what()) + "\n"};
      }
      Respond(fd, reply, req.method == "HEAD", keep_alive);
      if (!keep_alive) return;
    }
  }
};

Server::Server(const std::string& host, int port, Handler handler)
    : impl_(std::make_unique<Impl>()) {
  impl_->host = host;
  impl_->handler = std::move(handler);
  const std::string where = host + ":" + std::to_string(port);
  impl_->listen_fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (impl_->listen_fd < 0) ThrowInputError(where, "", "a TCP socket", std::strerror(errno));
  const int one = 1;
  ::setsockopt(impl_->listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1) {
    ::close(impl_->listen_fd);
    ThrowInputError(where, "host", "an IPv4 address such as 127.0.0.1", host);
  }
  if (::bind(impl_->listen_fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
      ::listen(impl_->listen_fd, 64) != 0) {
    const std::string err = std::strerror(errno);
    ::close(impl_->listen_fd);
    ThrowInputError(where, "", "a free address to listen on", err);
  }
  socklen_t len = sizeof(addr);
  ::getsockname(impl_->listen_fd, reinterpret_cast<sockaddr*>(&addr), &len);
  impl_->port = ntohs(addr.sin_port);
  impl_->acceptor = std::thread([this] { impl_->AcceptLoop(); });
}

Server::~Server() {
  impl_->stop = true;
  impl_->acceptor.join();
  ::close(impl_->listen_fd);
  std::vector<Impl::Worker> workers;
  {
    std::lock_guard<std::mutex> lock(impl_->mu);
    workers.swap(impl_->workers);
  }
  for (auto& w : workers) w.thread.join();
}

int Server::port() const { return impl_->port; }

std::string Server::url() const {
  return "http://" + impl_->host + ":" + std::to_string(impl_->port) + "/";
}

int Server::requests() const { return impl_->requests.load(); }

}  // namespace sims::http
