// serve_viewer: serves a story folder (run_story's output: index.html, motion.json, scene.glb)
// on 127.0.0.1 so the web viewer can be opened in a browser; Ctrl-C stops it.
#include <csignal>
#include <iostream>
#include <thread>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/io/http_server.h"

namespace {
volatile std::sig_atomic_t g_stop = 0;
}

int main(int argc, char** argv) {
  CLI::App app{"Serve a story folder for the web viewer (http://127.0.0.1:PORT/)"};
  std::string dir, host = "127.0.0.1";
  int port = 8000;
  sims::AppFlags flags;
  app.add_option("dir", dir, "folder with index.html (run_story output)")->required();
  app.add_option("--port", port, "port (0 = any free port)");
  app.add_option("--host", host, "address to bind (127.0.0.1 keeps it local)");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  return sims::RunApp(flags, [&] {
    sims::io::StaticHttpServer server(dir, port, host);
    std::signal(SIGINT, [](int) { g_stop = 1; });
    std::signal(SIGTERM, [](int) { g_stop = 1; });
    std::cout << "serving " << dir << " at " << server.url() << " (Ctrl-C to stop)" << std::endl;
    while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    return 0;
  });
}
