// A minimal OpenAI-compatible chat-completions client (llama.cpp server, vLLM, Ollama's /v1,
// any proxy) over the project's HTTP layer (core/http.h): no new dependency, no TLS. https
// endpoints are refused with a clear message (run a local server, or a plain-HTTP proxy in front of
// a remote one). Every failure is a sims::Error (LlmError) so the planner can fall back.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/core/config.h"
#include "sims/core/environment.h"
#include "sims/core/error.h"

namespace sims::planner {

/// LLM back-end settings (configs/planner/planner.json "llm"; flags override). The client uses
/// them verbatim; the apps fill the open ones from the environment with WithEnvironment.
struct LlmConfig {
  std::string endpoint;           ///< Base URL ("http://127.0.0.1:8080/v1"); "" = no LLM.
  std::string model = "default";  ///< Model name (the apps replace "default" by $SIMS_LLM_MODEL).
  std::string api_key;  ///< Key ("" = none; the apps use $<api_key_env>, $OPENAI_API_KEY).
  std::string api_key_env = "SIMS_LLM_API_KEY";  ///< Environment variable holding the key.
  double timeout_s = 60.0;                       ///< Whole-request time-out (connect + reply).
  double temperature = 0.0;  ///< Sampling temperature (0: as repeatable as possible).
  int max_tokens = 2048;     ///< Reply length limit.
  bool json_mode = true;     ///< Ask for response_format {"type": "json_object"}.
  std::string system_prompt = "planner/llm_system_prompt.txt";  ///< Under configs/.
  std::string user_prompt = "planner/llm_user_prompt.txt";      ///< Under configs/.
  int candidates = 24;  ///< Short scripts offered to the model.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(endpoint));
    a->Visit(SIMS_NVP(model));
    a->Visit(SIMS_NVP(api_key));
    a->Visit(SIMS_NVP(api_key_env));
    a->Visit(SIMS_NVP(timeout_s));
    a->Visit(SIMS_NVP(temperature));
    a->Visit(SIMS_NVP(max_tokens));
    a->Visit(SIMS_NVP(json_mode));
    a->Visit(SIMS_NVP(system_prompt));
    a->Visit(SIMS_NVP(user_prompt));
    a->Visit(SIMS_NVP(candidates));
  }
  /// Positive time-out and token limit, candidates ≥ 1.
  void Validate() const;
};

/// `config` with what it leaves open taken from `environment`: endpoint "" → $SIMS_LLM_ENDPOINT,
/// model "default" → $SIMS_LLM_MODEL (if set), api_key "" → $<api_key_env>, then
/// $OPENAI_API_KEY. The apps call it with the environment read at start-up; the library never
/// reads the environment itself, so a default Environment leaves `config` as it is.
LlmConfig WithEnvironment(LlmConfig config, const Environment& environment);

/// Why a request failed.
class LlmError : public Error {
 public:
  /// Failure kinds the caller may want to tell apart.
  enum class Kind { kConfig, kConnect, kTimeout, kHttp, kProtocol, kReply };
  /// `kind` classifies, `message` explains.
  LlmError(Kind kind, const std::string& message) : Error(message), kind_(kind) {}
  /// The kind.
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

/// The chat-completions URL for a base endpoint ("…/v1" → "…/v1/chat/completions"; a URL that
/// already ends in /chat/completions is kept; a bare host gets /v1/chat/completions).
std::string ChatCompletionsUrl(const std::string& endpoint);

/// One chat message.
struct ChatMessage {
  std::string role;                     ///< system, user or assistant.
  std::string content;                  ///< Text.
  std::vector<std::string> image_urls;  ///< Images (data: or http URLs) after the text, if any.
};

/// The chat-completions request body from `config` (model, sampling, json_mode). Messages with
/// images become OpenAI content-part arrays ({"type": "text"} then
/// {"type": "image_url", "image_url": {"url": ...}}).
nlohmann::json ChatRequestJson(const LlmConfig& config, const std::vector<ChatMessage>& messages,
                               uint64_t seed);

/// POSTs a request body to `endpoint`'s chat-completions URL (Bearer `api_key` unless empty)
/// and returns choices[0].message.content; every failure is an LlmError.
std::string PostChatRequest(const std::string& endpoint, const std::string& api_key,
                            const nlohmann::json& request, double timeout_s);

/// Sends a chat-completions request to config.endpoint (with config.api_key) and returns
/// choices[0].message.content; an empty endpoint is an LlmError(kConfig).
std::string ChatCompletion(const LlmConfig& config, const std::vector<ChatMessage>& messages,
                           uint64_t seed);

/// Removes a surrounding Markdown code fence (```json … ```) and text around a JSON object.
std::string StripToJson(const std::string& reply);

}  // namespace sims::planner
