// Retrieval accuracy of a trained motion–text model: for held-out paraphrases, is the nearest
// clip by z the expected one? (issue: report the figure, target ≥ 80%).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sims/language/embedding_bank.h"

namespace sims::language {

/// The clip style a bank clip name stands for: "_v<k>" variants and the mirror suffix removed,
/// and left/right swapped for mirrored clips (a mirrored left reach is a right reach).
std::string ClipStyleOf(const std::string& clip_name);

/// Evaluates {"queries": [{"caption", "clip"}]} from `path`; returns {"accuracy", "correct",
/// "total", "queries": [{"caption", "expected", "retrieved", "cosine", "correct"}]}.
nlohmann::json EvaluateRetrieval(const StyleEmbedder& embedder, const std::filesystem::path& path);

}  // namespace sims::language
