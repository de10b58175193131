// The settings users give through environment variables, read in one place. The library never
// calls getenv: apps read the process environment once at start-up (RunApp), install the path
// settings every module shares with InstallEnvironment, and pass the rest (LLM endpoint, model
// and keys) down as explicit option fields. Tests install what they need the same way.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace sims {

/// Values of the environment variables the project honours ("" / empty path = unset).
struct Environment {
  std::filesystem::path root;         ///< $SIMS_ROOT: another checkout's assets/ and configs/.
  std::filesystem::path data_dir;     ///< $SIMS_DATA_DIR: setup-time data (default data/).
  std::string log_level;              ///< $SIMS_LOG_LEVEL: used without --log-level.
  std::filesystem::path morse_dir;    ///< $SIMS_MORSE_DIR: morse-simulator-data's data folder.
  std::filesystem::path partnet_dir;  ///< $SIMS_PARTNET_DIR: PartNet objects for ScenePlans.
  std::filesystem::path future_dir;   ///< $SIMS_FUTURE_DIR: 3D-FUTURE models for 3D-FRONT.
  std::filesystem::path three_tgz;    ///< $SIMS_THREE_TGZ: the three.js npm tarball.
  std::string llm_endpoint;           ///< $SIMS_LLM_ENDPOINT: LLM base URL when none is given.
  std::string llm_model;              ///< $SIMS_LLM_MODEL: replaces the model name "default".
  /// Every variable of the process at start-up, for names a config file chooses
  /// (LlmConfig::api_key_env); the fields above are the ones the project itself defines.
  std::map<std::string, std::string> variables;

  /// variables[name], or "" when unset.
  std::string Variable(const std::string& name) const;
  /// The LLM API key: $<key_variable> if non-empty, else $OPENAI_API_KEY ("" = none).
  std::string LlmApiKey(const std::string& key_variable = "SIMS_LLM_API_KEY") const;
};

/// Reads the process environment: the one getenv/environ reader of the library (subprocess
/// copies environ into a child's environment, and looks programs up in the installed PATH).
Environment ReadEnvironment();

/// Installs the process-wide settings that paths.h, the scene loaders and the viewer use.
/// Not thread-safe: call it at start-up (RunApp, the test main) or from single-threaded tests.
void InstallEnvironment(Environment environment);

/// The installed settings (all unset until InstallEnvironment is called).
const Environment& InstalledEnvironment();

}  // namespace sims
