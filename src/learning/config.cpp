#include "sims/learning/config.h"

namespace sims::learning {

void NetworkConfig::Validate() const {
  for (int h : actor_hidden) Require(h > 0, "actor_hidden", "positive layer sizes");
  for (int h : critic_hidden) Require(h > 0, "critic_hidden", "positive layer sizes");
  Require(!disc_hidden.empty(), "disc_hidden", "at least one hidden layer");
  for (int h : disc_hidden) Require(h > 0, "disc_hidden", "positive layer sizes");
  Require(!heightmap_hidden.empty(), "heightmap_hidden", "at least one hidden layer");
  for (int h : heightmap_hidden) Require(h > 0, "heightmap_hidden", "positive layer sizes");
  Require(activation == "relu" || activation == "elu" || activation == "tanh", "activation",
          "one of relu, elu, tanh");
  Require(action_log_std > -10 && action_log_std < 2, "action_log_std", "a log σ in (−10, 2)");
}

void PpoConfig::Validate() const {
  Require(gamma > 0 && gamma <= 1, "gamma", "a discount in (0, 1]");
  Require(lambda >= 0 && lambda <= 1, "lambda", "a GAE λ in [0, 1]");
  Require(clip > 0 && clip < 1, "clip", "a ratio clip in (0, 1)");
  Require(horizon > 0, "horizon", "a positive number of steps");
  Require(mini_epochs > 0, "mini_epochs", "a positive count");
  Require(minibatch_size > 0, "minibatch_size", "a positive count");
  Require(learning_rate > 0 && learning_rate < 1, "learning_rate", "a rate in (0, 1)");
  Require(critic_coef >= 0, "critic_coef", "a non-negative weight");
  Require(bounds_coef >= 0, "bounds_coef", "a non-negative weight");
  Require(smooth_coef >= 0, "smooth_coef", "a non-negative weight");
  Require(grad_norm >= 0, "grad_norm", "a non-negative norm (0 = no clipping)");
  Require(obs_clip > 0, "obs_clip", "a positive clip");
  Require(warm_start_obs_count > 0, "warm_start_obs_count", "a positive sample count");
  Require(warm_start_quiet_var >= 0, "warm_start_quiet_var", "a non-negative variance");
  Require(actor_warmup_iterations >= 0, "actor_warmup_iterations", "a non-negative count");
  Require(lr_schedule == "constant" || lr_schedule == "adaptive", "lr_schedule",
          "\"constant\" or \"adaptive\"");
  Require(kl_threshold > 0, "kl_threshold", "a positive KL divergence");
}

void AmpConfig::Validate() const {
  Require(loss == "bce" || loss == "lsgan", "loss", "bce or lsgan");
  Require(task_weight >= 0 && style_weight >= 0, "task_weight", "non-negative reward weights");
  Require(reward_scale > 0, "reward_scale", "a positive scale");
  Require(replay_size > 0, "replay_size", "a positive capacity");
  Require(replay_keep_prob >= 0 && replay_keep_prob <= 1, "replay_keep_prob", "a probability");
  Require(demo_pool_size > 0, "demo_pool_size", "a positive count");
  Require(batch_size > 0, "batch_size", "a positive count");
  Require(disc_epochs >= 0, "disc_epochs", "a mini-epoch count ≥ 0 (0 = every mini-epoch)");
  Require(demo_refresh >= 0 && demo_refresh <= demo_pool_size, "demo_refresh",
          "a count in [0, demo_pool_size]");
  Require(grad_norm >= 0, "grad_norm", "a non-negative norm (0 = no clipping)");
  Require(mismatch_fraction >= 0 && mismatch_fraction < 1, "mismatch_fraction",
          "a fraction in [0, 1)");
}

}  // namespace sims::learning
