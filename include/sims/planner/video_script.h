// Short scripts from video (SIMS §3.1: a vision-language model describes sampled frames and the
// answer becomes keyframes). The frames (JPEG files, e.g. from io::SampleVideoFrames) are sent
// as data URLs in OpenAI "image_url" content parts through the planner's one HTTP client
// (llm_client.h); the answer is validated by ParseScriptAnswer (script_answer.h). Outputs are
// written only when everything succeeded: the script atomically, its frames next to it.
//
//   VideoScriptOptions o;  o.endpoint = "http://127.0.0.1:8080/v1";  o.video = "clip.mp4";
//   VideoScriptResult r = ExtractVideoScript(frames, o, "scripts/clip.json");
//   // scripts/clip.json + scripts/clip_frames/000.jpg ...
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/planner/script_answer.h"

namespace sims::planner {

/// The vision-language endpoint and how its answer is treated. Nothing here reads the
/// environment: the caller passes endpoint, model and key explicitly.
struct VideoScriptOptions {
  std::string endpoint;           ///< OpenAI-compatible http:// base URL ("" only for dry runs).
  std::string model = "default";  ///< Model name sent in the request.
  std::string api_key;            ///< Bearer key ("" = no Authorization header).
  double timeout_s = 120.0;       ///< Whole-request time-out (connect + answer).
  int max_tokens = 1024;          ///< Answer length limit.
  double temperature = 0.0;       ///< Sampling temperature.
  bool json_mode = true;          ///< Ask for response_format {"type": "json_object"}.
  uint64_t seed = 0;              ///< Seed sent with the request.
  std::string system_prompt = "planner/vlm_system_prompt.txt";  ///< Under configs/.
  std::string user_prompt = "planner/vlm_user_prompt.txt";      ///< Under configs/.
  UnknownTerms unknown = UnknownTerms::kMap;  ///< Out-of-vocabulary furniture/skills.
  std::string video;                          ///< The video's name (prompt and provenance only).

  /// Throws sims::Error naming the option when a value is out of range.
  void Validate() const;
};

/// One frame handed to the model.
struct ScriptFrame {
  std::filesystem::path path;  ///< JPEG file.
  double time_s = 0.0;         ///< Time in the video (told to the model).
};

/// What an extraction produced.
struct VideoScriptResult {
  ShortScript script;                 ///< The validated script (id = output file stem).
  std::vector<std::string> notes;     ///< Mapped terms and inserted transitions.
  std::filesystem::path script_path;  ///< Written script (or request, for dry runs).
  std::filesystem::path frames_dir;   ///< Folder holding the frames used.
};

/// Where the frames of a script are kept: "dir/clip.json" → "dir/clip_frames".
std::filesystem::path FramesDirFor(const std::filesystem::path& script_path);

/// The chat-completions request: system prompt, then one user message with the text prompt and
/// every frame as a base64 JPEG data URL. Throws sims::Error naming an unreadable frame.
nlohmann::json BuildVideoScriptRequest(const std::vector<ScriptFrame>& frames,
                                       const VideoScriptOptions& options,
                                       const Vocabulary& vocab = Vocabulary::Default());

/// Sends the request, validates the answer, then writes `out` (the script, atomically, with a
/// "provenance" object) and copies the frames to FramesDirFor(out)/NNN.jpg. On a time-out, an
/// HTTP or protocol error or an invalid answer it throws (LlmError / sims::Error naming the
/// endpoint, the field and what was expected) and writes nothing.
VideoScriptResult ExtractVideoScript(const std::vector<ScriptFrame>& frames,
                                     const VideoScriptOptions& options,
                                     const std::filesystem::path& out,
                                     const Vocabulary& vocab = Vocabulary::Default());

/// Dry run: writes the request JSON that ExtractVideoScript would send to `out` (atomically)
/// and the frames next to it, without contacting any endpoint.
VideoScriptResult WriteVideoScriptRequest(const std::vector<ScriptFrame>& frames,
                                          const VideoScriptOptions& options,
                                          const std::filesystem::path& out,
                                          const Vocabulary& vocab = Vocabulary::Default());

/// Standard base64 (RFC 4648, with padding) of raw bytes.
std::string Base64Encode(const std::string& bytes);

}  // namespace sims::planner
