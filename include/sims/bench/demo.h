// The standing demo behind apps/demo_env (the README's first command until run_story exists).
#pragma once

#include <filesystem>

#include "sims/sim/env.h"

namespace sims::bench {

/// Runs `steps` control steps of every env holding the default pose under Gaussian action
/// noise; writes `out_dir`/result.json (episode statistics, mean root height, rate) and
/// `out_dir`/config.json. Returns the result JSON.
nlohmann::json RunStandingDemo(const sim::EnvConfig& config, int steps, double noise,
                               const std::filesystem::path& out_dir);

}  // namespace sims::bench
