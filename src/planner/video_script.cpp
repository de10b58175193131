#include "sims/planner/video_script.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/planner/llm_client.h"
#include "sims/planner/prompt.h"
#include "sims/planner/text.h"

namespace sims::planner {

using nlohmann::json;

void VideoScriptOptions::Validate() const {
  if (!(timeout_s > 0))
    ThrowInputError("extract_script", "timeout", "a positive number of seconds");
  if (max_tokens <= 0) ThrowInputError("extract_script", "max_tokens", "a positive integer");
  if (temperature < 0) ThrowInputError("extract_script", "temperature", "a non-negative number");
}

std::string Base64Encode(const std::string& in) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8) | uint8_t(in[i + 2]);
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i + 1 == in.size()) {
    uint32_t v = uint8_t(in[i]) << 16;
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    uint32_t v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8);
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::filesystem::path FramesDirFor(const std::filesystem::path& script_path) {
  return script_path.parent_path() / (script_path.stem().string() + "_frames");
}

namespace {

std::string ReadBinary(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) ThrowInputError(p.string(), "", "a readable JPEG frame", "no such file");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string bytes = ss.str();
  if (bytes.size() < 3 || uint8_t(bytes[0]) != 0xFF || uint8_t(bytes[1]) != 0xD8)
    ThrowInputError(p.string(), "", "a JPEG image (starts with FF D8)", "other bytes");
  return bytes;
}

std::string FrameName(std::size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%03zu.jpg", i);
  return buf;
}

// Copies the frames into FramesDirFor(out) through a temporary folder, so the folder is either
// the old one or complete.
std::filesystem::path KeepFrames(const std::vector<ScriptFrame>& frames,
                                 const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  fs::path dir = FramesDirFor(out);
  if (dir.has_parent_path()) fs::create_directories(dir.parent_path());
  fs::path tmp = dir;
  tmp += ".tmp." + std::to_string(::getpid());
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp);
  try {
    for (std::size_t i = 0; i < frames.size(); ++i)
      fs::copy_file(frames[i].path, tmp / FrameName(i), fs::copy_options::overwrite_existing);
    fs::remove_all(dir);
    fs::rename(tmp, dir);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(tmp, ec);
    ThrowInputError(dir.string(), "", "a writable folder for the frames", e.what());
  }
  return dir;
}

std::string TimeList(const std::vector<ScriptFrame>& frames) {
  std::vector<std::string> t;
  for (const ScriptFrame& f : frames) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.1f", f.time_s);
    t.push_back(buf);
  }
  return Join(t, ", ");
}

json Provenance(const std::vector<ScriptFrame>& frames, const VideoScriptOptions& o,
                const std::filesystem::path& out, const std::vector<std::string>& notes) {
  json p;
  p["method"] = "video";
  p["video"] = o.video;
  p["endpoint"] = o.endpoint;
  p["model"] = o.model;
  json fr = json::array();
  std::string dir = FramesDirFor(out).filename().string();
  for (std::size_t i = 0; i < frames.size(); ++i)
    fr.push_back({{"file", dir + "/" + FrameName(i)}, {"time_s", frames[i].time_s}});
  p["frames"] = fr;
  p["notes"] = notes;
  return p;
}

}  // namespace

json BuildVideoScriptRequest(const std::vector<ScriptFrame>& frames,
                             const VideoScriptOptions& options, const Vocabulary& vocab) {
  options.Validate();
  if (frames.empty()) ThrowInputError("extract_script", "frames", "at least one frame", "none");
  std::map<std::string, std::string> values = VocabularyPromptValues(vocab);
  values["video"] = options.video.empty() ? "clip" : options.video;
  values["frame_count"] = std::to_string(frames.size());
  values["frame_times"] = TimeList(frames);
  ChatMessage user{"user", FillPrompt(ReadPromptTemplate(options.user_prompt), values), {}};
  for (const ScriptFrame& f : frames)
    user.image_urls.push_back("data:image/jpeg;base64," + Base64Encode(ReadBinary(f.path)));
  LlmConfig c;
  c.model = options.model;
  c.temperature = options.temperature;
  c.max_tokens = options.max_tokens;
  c.json_mode = options.json_mode;
  return ChatRequestJson(
      c, {{"system", FillPrompt(ReadPromptTemplate(options.system_prompt), values), {}}, user},
      options.seed);
}

VideoScriptResult ExtractVideoScript(const std::vector<ScriptFrame>& frames,
                                     const VideoScriptOptions& options,
                                     const std::filesystem::path& out, const Vocabulary& vocab) {
  if (options.endpoint.empty())
    ThrowInputError("extract_script", "--vlm-endpoint", "an http:// base URL (or --dry-run)",
                    "nothing");
  json request = BuildVideoScriptRequest(frames, options, vocab);
  std::string content;
  try {
    content = PostChatRequest(options.endpoint, options.api_key, request, options.timeout_s);
  } catch (const LlmError& e) {
    // The client's messages say what failed; the user also needs to know which endpoint.
    throw LlmError(e.kind(), "VLM endpoint " + options.endpoint + ": " + e.what());
  }
  VideoScriptResult r;
  r.script = ParseScriptAnswer(content, "VLM answer from " + options.endpoint, options.unknown,
                               &r.notes, vocab);
  r.script.id = out.stem().string();
  for (Keyframe& k : r.script.keyframes) k.script_id = r.script.id;
  for (const std::string& n : r.notes) spdlog::debug("{}: {}", out.string(), n);
  r.frames_dir = KeepFrames(frames, out);
  WriteShortScript(out, r.script, Provenance(frames, options, out, r.notes));
  r.script_path = out;
  return r;
}

VideoScriptResult WriteVideoScriptRequest(const std::vector<ScriptFrame>& frames,
                                          const VideoScriptOptions& options,
                                          const std::filesystem::path& out,
                                          const Vocabulary& vocab) {
  json request = BuildVideoScriptRequest(frames, options, vocab);
  VideoScriptResult r;
  r.frames_dir = KeepFrames(frames, out);
  WriteJsonFile(out, request);
  r.script_path = out;
  return r;
}

}  // namespace sims::planner
