#include "sims/io/http_server.h"

#include <fstream>
#include <map>
#include <sstream>

#include "sims/core/error.h"
#include "sims/core/http.h"
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

struct StaticHttpServer::Impl {
  std::filesystem::path root;
  std::unique_ptr<http::Server> server;

  http::Reply Serve(const http::Request& req) const {
    if (req.method != "GET" && req.method != "HEAD")
      return {405, "Method Not Allowed", "text/plain", "GET or HEAD only\n"};
    std::string path = req.path;
    if (path.empty() || path[0] != '/') path = "/" + path;
    if (path.back() == '/') path += "index.html";
    // Refuse anything that could leave the root.
    bool bad = path.find('\0') != std::string::npos;
    std::istringstream parts(path);
    for (std::string seg; std::getline(parts, seg, '/');) bad = bad || seg == "..";
    const std::filesystem::path file = root / path.substr(1);
    if (!bad && std::filesystem::is_regular_file(file)) {
      std::ifstream f(file, std::ios::binary);
      return {200, "OK", ContentTypeFor(file),
              std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>())};
    }
    spdlog::debug("http: 404 {}", path);
    return {404, "Not Found", "text/plain", "not found: " + path + "\n"};
  }
};

StaticHttpServer::StaticHttpServer(std::filesystem::path root, int port, const std::string& host)
    : impl_(std::make_unique<Impl>()) {
  impl_->root = std::move(root);
  if (!std::filesystem::is_directory(impl_->root))
    ThrowInputError(impl_->root.string(), "", "a folder to serve", "no such folder");
  impl_->server = std::make_unique<http::Server>(
      host, port, [impl = impl_.get()](const http::Request& r) { return impl->Serve(r); });
}

StaticHttpServer::~StaticHttpServer() = default;

int StaticHttpServer::port() const { return impl_->server->port(); }

std::string StaticHttpServer::url() const { return impl_->server->url(); }

int StaticHttpServer::requests() const { return impl_->server->requests(); }

}  // namespace sims::io
