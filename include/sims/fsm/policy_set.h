// The per-skill policies a story runs with: a JSON file (assets/policies/policies.json)
// mapping skill names to ExportPolicy() files, relative to the JSON file's folder, and
// optionally the action smoothing a skill's policy runs with (sim::EnvConfig::action_smoothing;
// without an entry, the one the policy trained with).
//   {"description": "...", "policies": {"walk": "walk/policy.pt", "sit": "sit/policy.pt"},
//    "action_smoothing": {"walk": 0.3}}
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "sims/core/config.h"

namespace sims::fsm {

/// A policy-set file.
struct PolicySetConfig {
  std::string description;                         ///< Free text.
  std::map<std::string, std::string> policies;     ///< skill → policy file.
  std::map<std::string, double> action_smoothing;  ///< skill → α (absent: its training's).

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(description));
    a->Visit(SIMS_NVP(policies));
    a->Visit(SIMS_NVP(action_smoothing));
  }
};

/// A loaded policy set with resolved paths.
struct PolicySet {
  std::filesystem::path source;                           ///< The JSON file.
  std::map<std::string, std::filesystem::path> policies;  ///< skill → absolute policy file.
  std::map<std::string, double> action_smoothing;         ///< skill → α overriding its own.

  /// True when the set has a policy for `skill`.
  bool Has(const std::string& skill) const { return policies.count(skill) > 0; }
  /// The file for `skill`; throws sims::Error naming the set file, the field and the skills
  /// it does have.
  const std::filesystem::path& File(const std::string& skill) const;
};

/// Loads and checks a policy set: known skill names, files that exist, smoothing only for
/// skills with a policy and within [0, sim::kMaxActionSmoothing].
PolicySet LoadPolicySet(const std::filesystem::path& path);

/// assets/policies/policies.json.
std::filesystem::path DefaultPolicySetPath();

}  // namespace sims::fsm
