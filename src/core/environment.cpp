#include "sims/core/environment.h"

#include <unistd.h>

#include <utility>

// Declared by <unistd.h> only under _GNU_SOURCE; POSIX defines it, so say so explicitly.
extern char** environ;

namespace sims {

std::string Environment::Variable(const std::string& name) const {
  const auto it = variables.find(name);
  return it == variables.end() ? std::string() : it->second;
}

std::string Environment::LlmApiKey(const std::string& key_variable) const {
  std::string key = key_variable.empty() ? std::string() : Variable(key_variable);
  return key.empty() ? Variable("OPENAI_API_KEY") : key;
}

Environment ReadEnvironment() {
  Environment e;
  // A snapshot of environ rather than getenv calls, so that nothing later depends on when (or
  // whether) a variable was read.
  for (char** p = environ; p && *p; ++p) {
    const std::string entry = *p;
    const std::size_t eq = entry.find('=');
    if (eq == std::string::npos) continue;
    e.variables.emplace(entry.substr(0, eq), entry.substr(eq + 1));
  }
  e.root = e.Variable("SIMS_ROOT");
  e.data_dir = e.Variable("SIMS_DATA_DIR");
  e.log_level = e.Variable("SIMS_LOG_LEVEL");
  e.morse_dir = e.Variable("SIMS_MORSE_DIR");
  e.partnet_dir = e.Variable("SIMS_PARTNET_DIR");
  e.future_dir = e.Variable("SIMS_FUTURE_DIR");
  e.three_tgz = e.Variable("SIMS_THREE_TGZ");
  e.llm_endpoint = e.Variable("SIMS_LLM_ENDPOINT");
  e.llm_model = e.Variable("SIMS_LLM_MODEL");
  return e;
}

namespace {
Environment& Installed() {
  static Environment environment;
  return environment;
}
}  // namespace

void InstallEnvironment(Environment environment) { Installed() = std::move(environment); }

const Environment& InstalledEnvironment() { return Installed(); }

}  // namespace sims
