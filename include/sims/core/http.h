// The project's one HTTP/1.1 layer (plain http://, POSIX sockets): a client for the planner's
// and the video extractor's OpenAI-compatible endpoints and a small threaded server the web
// viewer is served from. No TLS: endpoints are local servers (llama.cpp, vLLM) or plain-HTTP
// proxies.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sims/core/error.h"

namespace sims::http {

/// Why an HTTP exchange failed.
class HttpError : public Error {
 public:
  /// Failure kinds a caller may want to tell apart.
  enum class Kind { kConfig, kConnect, kTimeout, kProtocol };
  /// `kind` classifies, `message` explains.
  HttpError(Kind kind, const std::string& message) : Error(message), kind_(kind) {}
  /// The kind.
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

/// Parts of an http:// URL.
struct Url {
  std::string host;        ///< Host name or address (IPv6 without brackets).
  int port = 80;           ///< Port.
  std::string path = "/";  ///< Path (with query).
};

/// Parses "http://host[:port][/path]"; https and other schemes throw HttpError(kConfig).
Url ParseUrl(const std::string& url);

/// An HTTP response as the client received it.
struct Response {
  int status = 0;    ///< Status code.
  std::string body;  ///< Body (chunked transfer decoded).
};

/// POSTs `body` (application/json) with extra `headers` and waits at most `timeout_s` for the
/// whole exchange; throws HttpError (connect, time-out, protocol).
Response Post(const std::string& url,
              const std::vector<std::pair<std::string, std::string>>& headers,
              const std::string& body, double timeout_s);

/// A request as the server received it.
struct Request {
  std::string method;                          ///< GET, HEAD, POST, ...
  std::string target;                          ///< Request target as sent.
  std::string path;                            ///< Target without query, %-decoded.
  std::map<std::string, std::string> headers;  ///< Lower-case names.
  std::string body;                            ///< Content-Length bytes (empty otherwise).
};

/// What a handler answers.
struct Reply {
  int status = 200;                                        ///< Status code.
  std::string reason = "OK";                               ///< Reason phrase.
  std::string content_type = "text/plain; charset=utf-8";  ///< Content-Type.
  std::string body;  ///< Body (HEAD requests get only its length).
};

/// Answers one request; runs on the connection's thread.
using Handler = std::function<Reply(const Request&)>;

/// A threaded HTTP/1.1 server (a thread per connection, keep-alive, bodies by Content-Length)
/// that stops and joins its threads when destroyed.
class Server {
 public:
  /// Binds `host`:`port` (IPv4; port 0 = any free port) and serves in the background; throws
  /// sims::Error naming the address when it cannot bind.
  Server(const std::string& host, int port, Handler handler);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// The bound port.
  int port() const;
  /// "http://host:port/".
  std::string url() const;
  /// Requests answered so far.
  int requests() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// %XX-decodes a URL path.
std::string UrlDecode(const std::string& s);

}  // namespace sims::http
