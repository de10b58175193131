// A minimal static-file HTTP/1.1 server for looking at story folders (the web viewer needs
// HTTP: browsers refuse ES modules and fetch() from file://). GET and HEAD only, one thread
// per connection (core/http.h, the one HTTP layer), files under the root only, loopback by
// default.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

namespace sims::io {

/// Serves the files under `root` until destroyed.
class StaticHttpServer {
 public:
  /// Binds `host`:`port` (port 0 = any free port) and starts serving in the background;
  /// throws sims::Error naming the address when it cannot bind.
  explicit StaticHttpServer(std::filesystem::path root, int port = 0,
                            const std::string& host = "127.0.0.1");
  /// Stops accepting, finishes open requests and joins the threads.
  ~StaticHttpServer();
  StaticHttpServer(const StaticHttpServer&) = delete;
  StaticHttpServer& operator=(const StaticHttpServer&) = delete;

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

/// Content type by file extension (text/javascript for .js, model/gltf-binary for .glb, ...).
std::string ContentTypeFor(const std::filesystem::path& path);

}  // namespace sims::io
