#include "sims/planner/llm_client.h"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include <fcntl.h>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>

#include <nlohmann/json.hpp>

#include "sims/planner/text.h"

namespace sims::planner {

void LlmConfig::Validate() const {
  Require(timeout_s > 0, "timeout_s", "a positive number of seconds");
  Require(max_tokens > 0, "max_tokens", "a positive integer");
  Require(candidates >= 1, "candidates", "an integer ≥ 1");
  Require(temperature >= 0, "temperature", "a non-negative number");
}

LlmConfig WithEnvironment(LlmConfig config, const Environment& environment) {
  if (config.endpoint.empty()) config.endpoint = environment.llm_endpoint;
  if (config.model == "default" && !environment.llm_model.empty())
    config.model = environment.llm_model;
  if (config.api_key.empty()) config.api_key = environment.LlmApiKey(config.api_key_env);
  return config;
}

HttpUrl ParseHttpUrl(const std::string& url) {
  const std::string scheme = "http://";
  if (url.rfind("https://", 0) == 0)
    throw LlmError(LlmError::Kind::kConfig,
                   "LLM endpoint '" + url +
                       "': https is not supported by the built-in client (plain HTTP/1.1 only); "
                       "use a local server (llama.cpp, vLLM) or a plain-HTTP proxy");
  if (url.rfind(scheme, 0) != 0)
    throw LlmError(LlmError::Kind::kConfig,
                   "LLM endpoint '" + url + "': expected an http://host[:port]/path URL");
  HttpUrl u;
  std::string rest = url.substr(scheme.size());
  std::size_t slash = rest.find('/');
  std::string authority = rest.substr(0, slash);
  u.path = slash == std::string::npos ? "/" : rest.substr(slash);
  std::string port;
  if (!authority.empty() && authority.front() == '[') {  // [IPv6]:port
    std::size_t close = authority.find(']');
    if (close == std::string::npos)
      throw LlmError(LlmError::Kind::kConfig, "LLM endpoint '" + url + "': unterminated [address]");
    u.host = authority.substr(1, close - 1);
    if (close + 1 < authority.size() && authority[close + 1] == ':')
      port = authority.substr(close + 2);
    else if (close + 1 < authority.size())
      throw LlmError(LlmError::Kind::kConfig, "LLM endpoint '" + url + "': bad authority");
  } else {
    std::size_t colon = authority.rfind(':');
    u.host = authority.substr(0, colon);
    if (colon != std::string::npos) port = authority.substr(colon + 1);
    if (colon != std::string::npos && port.empty())
      throw LlmError(LlmError::Kind::kConfig, "LLM endpoint '" + url + "': empty port");
  }
  if (!port.empty()) {
    char* end = nullptr;
    long p = std::strtol(port.c_str(), &end, 10);
    if (*end != '\0' || p <= 0 || p > 65535)
      throw LlmError(LlmError::Kind::kConfig,
                     "LLM endpoint '" + url + "': bad port '" + port + "'");
    u.port = static_cast<int>(p);
  }
  if (u.host.empty())
    throw LlmError(LlmError::Kind::kConfig, "LLM endpoint '" + url + "': no host");
  return u;
}

std::string ChatCompletionsUrl(const std::string& endpoint) {
  std::string e = endpoint;
  while (!e.empty() && e.back() == '/') e.pop_back();
  const std::string suffix = "/chat/completions";
  if (e.size() >= suffix.size() && e.compare(e.size() - suffix.size(), suffix.size(), suffix) == 0)
    return e;
  HttpUrl u = ParseHttpUrl(e);
  if (u.path == "/" || u.path.empty()) return e + "/v1" + suffix;
  return e + suffix;
}

namespace {

using Clock = std::chrono::steady_clock;

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
    int ms = RemainingMs(deadline);
    if (ms == 0) throw LlmError(LlmError::Kind::kTimeout, "LLM request timed out while " + what);
    pollfd p{fd, events, 0};
    int r = ::poll(&p, 1, ms);
    if (r > 0) return;
    if (r == 0) throw LlmError(LlmError::Kind::kTimeout, "LLM request timed out while " + what);
    if (errno != EINTR)
      throw LlmError(LlmError::Kind::kConnect, std::string("poll failed: ") + std::strerror(errno));
  }
}

int Connect(const HttpUrl& u, Clock::time_point deadline) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  std::string port = std::to_string(u.port);
  int rc = ::getaddrinfo(u.host.c_str(), port.c_str(), &hints, &res);
  if (rc != 0)
    throw LlmError(LlmError::Kind::kConnect,
                   "cannot resolve LLM host '" + u.host + "': " + ::gai_strerror(rc));
  std::string last_error = "no address";
  for (addrinfo* a = res; a; a = a->ai_next) {
    int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
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
  throw LlmError(LlmError::Kind::kConnect,
                 "cannot connect to LLM endpoint " + u.host + ":" + port + ": " + last_error);
}

// Decodes a chunked body; false while the terminating zero-size chunk has not arrived.
bool DecodeChunked(const std::string& body, std::string* out) {
  out->clear();
  std::size_t pos = 0;
  for (;;) {
    std::size_t eol = body.find("\r\n", pos);
    if (eol == std::string::npos) return false;
    char* end = nullptr;
    std::string size_text = body.substr(pos, eol - pos);
    unsigned long size = std::strtoul(size_text.c_str(), &end, 16);
    if (end == size_text.c_str())
      throw LlmError(LlmError::Kind::kProtocol, "bad chunk size '" + size_text.substr(0, 20) + "'");
    pos = eol + 2;
    if (size == 0) return true;
    if (pos + size + 2 > body.size()) return false;
    out->append(body, pos, size);
    pos += size + 2;
  }
}

// True when `raw` holds a complete response; fills status and body then.
bool ParseResponse(const std::string& raw, bool eof, HttpResponse* out) {
  std::size_t end = raw.find("\r\n\r\n");
  if (end == std::string::npos) {
    if (eof)
      throw LlmError(LlmError::Kind::kProtocol, "connection closed before the HTTP headers ended");
    return false;
  }
  std::string head = raw.substr(0, end);
  std::string body = raw.substr(end + 4);
  std::size_t sp = head.find(' ');
  if (head.rfind("HTTP/", 0) != 0 || sp == std::string::npos)
    throw LlmError(LlmError::Kind::kProtocol, "not an HTTP response: '" + head.substr(0, 40) + "'");
  int status = std::atoi(head.c_str() + sp + 1);
  std::string lower = ToLower(head);
  bool chunked = lower.find("\r\ntransfer-encoding: chunked") != std::string::npos;
  long long length = -1;
  std::size_t cl = lower.find("\r\ncontent-length:");
  if (cl != std::string::npos) length = std::atoll(lower.c_str() + cl + 17);
  if (chunked) {
    if (!DecodeChunked(body, &out->body)) {
      if (eof) throw LlmError(LlmError::Kind::kProtocol, "connection closed inside a chunked body");
      return false;
    }
  } else if (length >= 0) {
    if (static_cast<long long>(body.size()) < length) {
      if (eof) throw LlmError(LlmError::Kind::kProtocol, "connection closed before the body ended");
      return false;
    }
    out->body = body.substr(0, static_cast<std::size_t>(length));
  } else {
    if (!eof) return false;  // body runs to the end of the connection
    out->body = body;
  }
  out->status = status;
  return true;
}

}  // namespace

HttpResponse HttpPost(const std::string& url,
                      const std::vector<std::pair<std::string, std::string>>& headers,
                      const std::string& body, double timeout_s) {
  HttpUrl u = ParseHttpUrl(url);
  auto deadline =
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
    ssize_t n = ::send(sock.fd(), request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      throw LlmError(LlmError::Kind::kConnect, std::string("send failed: ") + std::strerror(errno));
    }
    sent += static_cast<std::size_t>(n);
  }
  std::string raw;
  HttpResponse resp;
  char buf[16384];
  for (;;) {
    Wait(sock.fd(), POLLIN, deadline, "waiting for the reply");
    ssize_t n = ::recv(sock.fd(), buf, sizeof(buf), 0);
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      throw LlmError(LlmError::Kind::kConnect, std::string("recv failed: ") + std::strerror(errno));
    }
    if (n == 0) {
      ParseResponse(raw, true, &resp);
      return resp;
    }
    raw.append(buf, static_cast<std::size_t>(n));
    if (ParseResponse(raw, false, &resp)) return resp;
  }
}

nlohmann::json ChatRequestJson(const LlmConfig& config, const std::vector<ChatMessage>& messages,
                               uint64_t seed) {
  nlohmann::json req;
  req["model"] = config.model;
  req["temperature"] = config.temperature;
  req["max_tokens"] = config.max_tokens;
  req["seed"] = seed;
  if (config.json_mode) req["response_format"] = {{"type", "json_object"}};
  req["messages"] = nlohmann::json::array();
  for (const ChatMessage& m : messages) {
    if (m.image_urls.empty()) {
      req["messages"].push_back({{"role", m.role}, {"content", m.content}});
      continue;
    }
    nlohmann::json parts = nlohmann::json::array();
    parts.push_back({{"type", "text"}, {"text", m.content}});
    for (const std::string& url : m.image_urls)
      parts.push_back({{"type", "image_url"}, {"image_url", {{"url", url}}}});
    req["messages"].push_back({{"role", m.role}, {"content", parts}});
  }
  return req;
}

std::string PostChatRequest(const std::string& endpoint, const std::string& api_key,
                            const nlohmann::json& request, double timeout_s) {
  if (endpoint.empty()) throw LlmError(LlmError::Kind::kConfig, "no LLM endpoint configured");
  std::vector<std::pair<std::string, std::string>> headers;
  if (!api_key.empty()) headers.emplace_back("Authorization", "Bearer " + api_key);
  HttpResponse r = HttpPost(ChatCompletionsUrl(endpoint), headers, request.dump(), timeout_s);
  if (r.status != 200)
    throw LlmError(LlmError::Kind::kHttp, "LLM endpoint answered HTTP " + std::to_string(r.status) +
                                              ": " + r.body.substr(0, 200));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(r.body);
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for a huge number
    throw LlmError(LlmError::Kind::kProtocol, std::string("LLM reply is not JSON: ") + e.what());
  }
  const nlohmann::json* content = nullptr;
  if (j.is_object() && j.contains("choices") && j["choices"].is_array() && !j["choices"].empty()) {
    const nlohmann::json& c = j["choices"][0];
    if (c.is_object() && c.contains("message") && c["message"].is_object() &&
        c["message"].contains("content") && c["message"]["content"].is_string())
      content = &c["message"]["content"];
  }
  if (!content)
    throw LlmError(LlmError::Kind::kProtocol,
                   "LLM reply lacks choices[0].message.content: " + r.body.substr(0, 200));
  return content->get<std::string>();
}

std::string ChatCompletion(const LlmConfig& config, const std::vector<ChatMessage>& messages,
                           uint64_t seed) {
  if (config.endpoint.empty())
    throw LlmError(LlmError::Kind::kConfig, "no LLM endpoint configured");
  return PostChatRequest(config.endpoint, config.api_key, ChatRequestJson(config, messages, seed),
                         config.timeout_s);
}

std::string StripToJson(const std::string& reply) {
  std::string s = Trim(reply);
  std::size_t fence = s.find("```");
  if (fence != std::string::npos) {
    std::size_t start = s.find('\n', fence);
    std::size_t end = s.find("```", fence + 3);
    if (start != std::string::npos && end != std::string::npos && end > start)
      s = Trim(s.substr(start + 1, end - start - 1));
  }
  std::size_t open = s.find('{'), close = s.rfind('}');
  if (open != std::string::npos && close != std::string::npos && close > open)
    s = s.substr(open, close - open + 1);
  return s;
}

}  // namespace sims::planner
