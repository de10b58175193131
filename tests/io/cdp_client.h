// A headless Chromium driven over the DevTools protocol through --remote-debugging-pipe
// (NUL-terminated JSON on fds 3/4): no WebSocket, no Node, no npm package needed.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/io/subprocess.h"

namespace sims::io::testing {

/// The Chromium executable: $SIMS_CHROMIUM, else /usr/bin/chromium; "" when absent.
std::string ChromiumPath();

/// One browser with one page (a session attached to its first tab).
class CdpBrowser {
 public:
  /// Launches Chromium headless with a fresh profile in `profile_dir` and a `width`×`height`
  /// window; throws sims::Error when it does not answer.
  CdpBrowser(const std::filesystem::path& profile_dir, int width = 1000, int height = 700);
  ~CdpBrowser();

  /// Sends a command (to the page session, or to the browser when `browser` is true) and
  /// returns its result; throws sims::Error on a protocol error or after `timeout_s`.
  nlohmann::json Call(const std::string& method,
                      const nlohmann::json& params = nlohmann::json::object(),
                      double timeout_s = 20, bool browser = false);
  /// Evaluates a JS expression in the page (promises awaited) and returns its value.
  nlohmann::json Eval(const std::string& expression, double timeout_s = 20);
  /// Polls Eval(expression) until it is true; false after `timeout_s`.
  bool WaitFor(const std::string& expression, double timeout_s);
  /// Navigates and waits for the load event.
  void Navigate(const std::string& url);
  /// A mouse click at page coordinates (CSS pixels).
  void Click(double x, double y);
  /// Base64 PNG of the page.
  std::string Screenshot();
  /// Console errors, uncaught exceptions and failed loads seen so far.
  const std::vector<std::string>& errors() const { return errors_; }
  /// Chromium's stderr (for failure messages).
  std::string Log() const;

 private:
  void Send(const nlohmann::json& msg);
  void Pump(double timeout_s);  // reads and dispatches messages for up to timeout_s
  void OnEvent(const nlohmann::json& msg);

  std::filesystem::path log_path_;
  std::unique_ptr<Subprocess> proc_;
  std::string buffer_;
  int next_id_ = 1;
  std::string session_;
  std::vector<nlohmann::json> responses_;
  std::vector<std::string> errors_;
  bool loaded_ = false;
};

}  // namespace sims::io::testing
