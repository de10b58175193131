// The smallest real training config a test can run in milliseconds (shared by the learning and
// FSM tests): two envs, four steps per iteration, tiny networks, no AMP.
#pragma once

#include <string>

#include "sims/learning/train_run.h"

namespace sims::testing {

/// One iteration of `skill` on 2 envs × 4 steps with 16-unit networks and AMP off.
inline learning::TrainConfig TinyTrainConfig(const std::string& skill) {
  learning::TrainConfig c;
  c.env.num_envs = 2;
  c.env.threads = 1;
  c.skill.skill = skill;
  c.learner.amp.enabled = false;
  c.learner.network.actor_hidden = {16};
  c.learner.network.critic_hidden = {16};
  c.learner.network.heightmap_hidden = {8};
  c.learner.ppo.horizon = 4;
  c.learner.ppo.mini_epochs = 1;
  c.iterations = 1;
  return c;
}

}  // namespace sims::testing
