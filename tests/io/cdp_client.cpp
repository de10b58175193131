#include "io/cdp_client.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "sims/core/error.h"

namespace sims::io::testing {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::string ChromiumPath() {
  if (const char* env = std::getenv("SIMS_CHROMIUM"); env && *env)
    return ProgramAvailable(env) ? env : "";
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (ProgramAvailable(p)) return p;
  return "";
}

CdpBrowser::CdpBrowser(const std::filesystem::path& profile_dir, int width, int height) {
  const std::string exe = ChromiumPath();
  if (exe.empty()) ThrowInputError("chromium", "", "Chromium installed (cmake/setup.sh)", "absent");
  std::filesystem::create_directories(profile_dir);
  log_path_ = profile_dir / "chromium.log";
  SubprocessOptions opt;
  opt.parent_writes_fds = {3};
  opt.parent_reads_fds = {4};
  opt.stdout_file = log_path_;
  opt.stderr_file = profile_dir / "chromium.err.log";
  log_path_ = opt.stderr_file;
  proc_ = std::make_unique<Subprocess>(
      std::vector<std::string>{
          exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
          "--disable-background-networking", "--disable-component-update", "--disable-sync",
          "--disable-default-apps", "--mute-audio", "--user-data-dir=" + profile_dir.string(),
          "--window-size=" + std::to_string(width) + "," + std::to_string(height),
          "--remote-debugging-pipe", "about:blank"},
      opt);
  const json targets = Call("Target.getTargets", json::object(), 30, true);
  std::string page;
  for (const auto& t : targets["targetInfos"])
    if (t["type"] == "page") page = t["targetId"];
  if (page.empty()) {
    const json created = Call("Target.createTarget", {{"url", "about:blank"}}, 20, true);
    page = created["targetId"];
  }
  session_ =
      Call("Target.attachToTarget", {{"targetId", page}, {"flatten", true}}, 20, true)["sessionId"];
  Call("Runtime.enable");
  Call("Log.enable");
  Call("Page.enable");
}

CdpBrowser::~CdpBrowser() {
  if (!proc_) return;
  try {
    Send({{"id", next_id_++}, {"method", "Browser.close"}});
  } catch (...) {
  }
  int code;
  if (!proc_->WaitFor(3000, &code)) proc_->Kill();
}

std::string CdpBrowser::Log() const {
  std::ifstream in(log_path_);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return s.size() > 3000 ? s.substr(s.size() - 3000) : s;
}

void CdpBrowser::Send(const json& msg) {
  const std::string text = msg.dump() + std::string(1, '\0');
  if (!proc_->WriteAll(text.data(), text.size(), 3))
    ThrowInputError("chromium", "", "a running browser", "the DevTools pipe closed: " + Log());
}

void CdpBrowser::OnEvent(const json& msg) {
  const std::string method = msg.value("method", "");
  const json& p = msg.contains("params") ? msg["params"] : json::object();
  if (method == "Runtime.consoleAPICalled" &&
      (p.value("type", "") == "error" || p.value("type", "") == "assert")) {
    std::string text = "console." + p.value("type", "") + ":";
    for (const auto& a : p["args"])
      text += " " + (a.contains("value") ? a["value"].dump() : a.value("description", "?"));
    errors_.push_back(text);
  } else if (method == "Runtime.exceptionThrown") {
    const json& d = p["exceptionDetails"];
    std::string text = "exception: " + d.value("text", "");
    if (d.contains("exception")) text += " " + d["exception"].value("description", "");
    errors_.push_back(text);
  } else if (method == "Log.entryAdded" && p["entry"].value("level", "") == "error") {
    errors_.push_back("log: " + p["entry"].value("text", "") + " " + p["entry"].value("url", ""));
  } else if (method == "Page.loadEventFired") {
    loaded_ = true;
  }
}

void CdpBrowser::Pump(double timeout_s) {
  char buf[65536];
  const long n = proc_->ReadSome(buf, sizeof(buf), 4, static_cast<int>(timeout_s * 1000));
  if (n == 0) ThrowInputError("chromium", "", "a running browser", "it exited: " + Log());
  if (n < 0) return;
  buffer_.append(buf, static_cast<std::size_t>(n));
  std::size_t end;
  while ((end = buffer_.find('\0')) != std::string::npos) {
    const json msg = json::parse(buffer_.substr(0, end));
    buffer_.erase(0, end + 1);
    if (msg.contains("id"))
      responses_.push_back(msg);
    else
      OnEvent(msg);
  }
}

json CdpBrowser::Call(const std::string& method, const json& params, double timeout_s,
                      bool browser) {
  const int id = next_id_++;
  json msg = {{"id", id}, {"method", method}, {"params", params}};
  if (!browser) msg["sessionId"] = session_;
  Send(msg);
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    for (auto it = responses_.begin(); it != responses_.end(); ++it) {
      if ((*it)["id"] != id) continue;
      const json r = *it;
      responses_.erase(it);
      if (r.contains("error"))
        ThrowInputError("chromium", method, "a DevTools result", r["error"].dump());
      return r.value("result", json::object());
    }
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0) ThrowInputError("chromium", method, "an answer within the time-out", "none");
    Pump(std::min(left, 0.5));
  }
}

json CdpBrowser::Eval(const std::string& expression, double timeout_s) {
  const json r = Call("Runtime.evaluate",
                      {{"expression", expression}, {"awaitPromise", true}, {"returnByValue", true}},
                      timeout_s);
  if (r.contains("exceptionDetails"))
    ThrowInputError("page", expression, "an expression that evaluates",
                    r["exceptionDetails"].dump().substr(0, 500));
  return r["result"].value("value", json());
}

bool CdpBrowser::WaitFor(const std::string& expression, double timeout_s) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (Clock::now() < deadline) {
    if (Eval("!!(" + expression + ")") == true) return true;
    Pump(0.1);
  }
  return false;
}

void CdpBrowser::Navigate(const std::string& url) {
  loaded_ = false;
  Call("Page.navigate", {{"url", url}});
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (!loaded_ && Clock::now() < deadline) Pump(0.2);
  if (!loaded_) ThrowInputError(url, "", "a page that loads within 30 s", "no load event");
}

void CdpBrowser::Click(double x, double y) {
  for (const char* type : {"mouseMoved", "mousePressed", "mouseReleased"})
    Call("Input.dispatchMouseEvent",
         {{"type", type}, {"x", x}, {"y", y}, {"button", "left"}, {"clickCount", 1}});
}

std::string CdpBrowser::Screenshot() {
  return Call("Page.captureScreenshot", {{"format", "png"}}, 30)["data"];
}

}  // namespace sims::io::testing
