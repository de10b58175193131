#include "sims/planner/llm_client.h"

#include <nlohmann/json.hpp>

#include "sims/core/http.h"

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

namespace {

// The HTTP layer's failures as the planner's: the kind carries over, the message says "LLM".
[[noreturn]] void RethrowAsLlm(const http::HttpError& e) {
  LlmError::Kind kind = LlmError::Kind::kProtocol;
  switch (e.kind()) {
    case http::HttpError::Kind::kConfig:
      kind = LlmError::Kind::kConfig;
      break;
    case http::HttpError::Kind::kConnect:
      kind = LlmError::Kind::kConnect;
      break;
    case http::HttpError::Kind::kTimeout:
      kind = LlmError::Kind::kTimeout;
      break;
    case http::HttpError::Kind::kProtocol:
      kind = LlmError::Kind::kProtocol;
      break;
  }
  throw LlmError(kind, std::string("LLM endpoint: ") + e.what());
}

}  // namespace

std::string ChatCompletionsUrl(const std::string& endpoint) {
  std::string e = endpoint;
  while (!e.empty() && e.back() == '/') e.pop_back();
  const std::string suffix = "/chat/completions";
  if (e.size() >= suffix.size() && e.compare(e.size() - suffix.size(), suffix.size(), suffix) == 0)
    return e;
  http::Url u;
  try {
    u = http::ParseUrl(e);
  } catch (const http::HttpError& err) {
    RethrowAsLlm(err);
  }
  if (u.path == "/" || u.path.empty()) return e + "/v1" + suffix;
  return e + suffix;
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
  http::Response r;
  try {
    r = http::Post(ChatCompletionsUrl(endpoint), headers, request.dump(), timeout_s);
  } catch (const http::HttpError& e) {
    RethrowAsLlm(e);
  }
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
