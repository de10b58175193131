#include "sims/fsm/policy_set.h"

#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/sim/env.h"
#include "sims/task/skill.h"

namespace sims::fsm {

std::filesystem::path DefaultPolicySetPath() { return AssetPath("policies/policies.json"); }

const std::filesystem::path& PolicySet::File(const std::string& skill) const {
  auto it = policies.find(skill);
  if (it != policies.end()) return it->second;
  std::string have;
  for (const auto& [k, v] : policies) have += (have.empty() ? "" : ", ") + k;
  ThrowInputError(source.string(), "policies." + skill,
                  "a policy for skill '" + skill + "' (the story needs it)",
                  have.empty() ? "no policies" : "only: " + have);
}

PolicySet LoadPolicySet(const std::filesystem::path& path) {
  const auto config = LoadConfig<PolicySetConfig>(path);
  PolicySet set;
  set.source = path;
  for (const auto& [skill, file] : config.policies) {
    task::FindSkill(skill);  // throws with the known names
    std::filesystem::path p = file;
    if (p.is_relative()) p = path.parent_path() / p;
    if (!std::filesystem::exists(p))
      ThrowInputError(path.string(), "policies." + skill, "an existing policy file",
                      "'" + p.string() + "' does not exist");
    set.policies[skill] = p;
  }
  for (const auto& [skill, alpha] : config.action_smoothing) {
    if (!config.policies.count(skill))
      ThrowInputError(path.string(), "action_smoothing." + skill, "a skill listed under 'policies'",
                      "no policy for '" + skill + "'");
    sim::CheckActionSmoothing(alpha, path.string(), "action_smoothing." + skill);
    set.action_smoothing[skill] = alpha;
  }
  return set;
}

}  // namespace sims::fsm
