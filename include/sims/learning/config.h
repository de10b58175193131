// Hyper-parameters of PPO + (conditional) AMP training, bound to JSON (configs/skills/*.json).
// Defaults follow ASE/UniHSI (their humanoid AMP configs) except where a 2-core CPU needs smaller
// networks and batches; the GPU values are noted beside each field.
#pragma once

#include <string>
#include <vector>

#include "sims/core/config.h"

namespace sims::learning {

/// Network sizes (GPU: [1024, 1024, 512]; ≈260 MFLOP/sample, far too slow on a CPU).
struct NetworkConfig {
  std::vector<int> actor_hidden{256, 256};     ///< Actor MLP hidden sizes.
  std::vector<int> critic_hidden{256, 256};    ///< Critic MLP hidden sizes.
  std::vector<int> disc_hidden{256, 128};      ///< Discriminator MLP hidden sizes.
  std::vector<int> heightmap_hidden{128, 64};  ///< Heightmap encoder MLP (output = last).
  std::string activation = "relu";             ///< relu | elu | tanh.
  double action_log_std = -2.9;                ///< Fixed Gaussian log σ.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(actor_hidden));
    a->Visit(SIMS_NVP(critic_hidden));
    a->Visit(SIMS_NVP(disc_hidden));
    a->Visit(SIMS_NVP(heightmap_hidden));
    a->Visit(SIMS_NVP(activation));
    a->Visit(SIMS_NVP(action_log_std));
  }
  /// Checks sizes and names.
  void Validate() const;
};

/// PPO settings.
struct PpoConfig {
  double gamma = 0.99;          ///< Discount.
  double lambda = 0.95;         ///< GAE λ.
  double clip = 0.2;            ///< Ratio clip ε.
  int horizon = 32;             ///< Steps per env per iteration.
  int mini_epochs = 6;          ///< Passes over each batch.
  int minibatch_size = 1024;    ///< Samples per gradient step (GPU: 16384).
  double learning_rate = 1e-4;  ///< Adam lr (GPU: 2e-5 with 131k-sample batches).
  double critic_coef = 5.0;     ///< Value loss weight.
  double bounds_coef = 10.0;    ///< Action-mean bounds loss weight.
  /// Weight of the temporal smoothness loss on the action mean (CAPS, Mysore et al. 2021):
  /// mean over action dims of (μ(s_t) − μ(s_t+1))² for consecutive states of an episode in the
  /// rollout. Why: the trained policies chatter (PD targets jumping 0.2–0.5 rad rms per step);
  /// a reward for steady actions pays through noisy returns, this shapes the mean directly.
  /// 0 = off (the loss is still measured and logged).
  double smooth_coef = 0.0;
  double entropy_coef = 0.0;        ///< Entropy bonus (σ is fixed, so 0).
  double grad_norm = 1.0;           ///< Gradient-norm clip (0 = off).
  bool normalize_advantage = true;  ///< (A − μ)/(σ + 1e-8) batch-wide.
  bool normalize_value = true;      ///< Critic predicts normalised returns.
  double obs_clip = 5.0;            ///< Normalised observations are clamped to ±obs_clip.
  /// After --init-policy, the imported observation normaliser counts as this many samples, so
  /// the new task's statistics take over within a few iterations (walk's ≈5 M would freeze
  /// them); inputs constant in the source task restart at mean 0, variance 1.
  double warm_start_obs_count = 4096;
  /// Warm start across layouts: task inputs with a source variance below this start silent.
  double warm_start_quiet_var = 1e-2;
  /// The actor does not learn in the first K iterations (the critic catches up with a
  /// warm-started actor; 0 = off).
  int actor_warmup_iterations = 0;
  /// "constant" or "adaptive" (rl_games): after every minibatch the learning rate shrinks by
  /// 1.5 when the policy's KL divergence exceeded 2·kl_threshold and grows by 1.5 when it
  /// stayed under kl_threshold / 2 (within [1e-6, 1e-2]). With σ = 0.055 a constant rate
  /// overshoots: clip fractions of 0.3–0.7 per update.
  std::string lr_schedule = "constant";
  double kl_threshold = 0.008;  ///< Target KL per minibatch of the adaptive schedule.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(gamma));
    a->Visit(SIMS_NVP(lambda));
    a->Visit(SIMS_NVP(clip));
    a->Visit(SIMS_NVP(horizon));
    a->Visit(SIMS_NVP(mini_epochs));
    a->Visit(SIMS_NVP(minibatch_size));
    a->Visit(SIMS_NVP(learning_rate));
    a->Visit(SIMS_NVP(critic_coef));
    a->Visit(SIMS_NVP(bounds_coef));
    a->Visit(SIMS_NVP(smooth_coef));
    a->Visit(SIMS_NVP(entropy_coef));
    a->Visit(SIMS_NVP(grad_norm));
    a->Visit(SIMS_NVP(normalize_advantage));
    a->Visit(SIMS_NVP(normalize_value));
    a->Visit(SIMS_NVP(obs_clip));
    a->Visit(SIMS_NVP(warm_start_obs_count));
    a->Visit(SIMS_NVP(warm_start_quiet_var));
    a->Visit(SIMS_NVP(actor_warmup_iterations));
    a->Visit(SIMS_NVP(lr_schedule));
    a->Visit(SIMS_NVP(kl_threshold));
  }
  /// Checks ranges.
  void Validate() const;
};

/// Adversarial motion prior settings.
struct AmpConfig {
  bool enabled = true;             ///< Train a discriminator and use the style reward.
  bool conditional = false;        ///< SIMS: D(s, s', z) with the clip's embedding z.
  std::string loss = "bce";        ///< bce | lsgan.
  double task_weight = 0.5;        ///< w_task.
  double style_weight = 0.5;       ///< w_style.
  double reward_scale = 2.0;       ///< r_style = −log(max(1 − D, 1e-4)) · scale.
  double disc_coef = 5.0;          ///< Discriminator loss weight in the joint loss.
  double grad_penalty = 5.0;       ///< Weight of mean ‖∇ₓ D(demo)‖².
  double logit_reg = 0.01;         ///< Weight of ‖w_logit‖².
  double weight_decay = 1e-4;      ///< Weight of Σ‖W‖² (weights only).
  int replay_size = 32768;         ///< Replay buffer capacity (GPU: 200k).
  double replay_keep_prob = 0.01;  ///< Insert probability once the buffer is full.
  int demo_pool_size = 32768;      ///< Demo windows precomputed from the motion library.
  /// Demo windows redrawn per iteration, cycling through the pool, so a long run does not
  /// re-see one fixed sample hundreds of times (0 = a fixed pool).
  int demo_refresh = 0;
  double grad_norm = 1.0;  ///< Discriminator gradient-norm clip, apart from the policy's (0 = off).
  int batch_size = 512;    ///< Demo samples per discriminator step (half replay negatives).
  /// Mini-epochs per iteration in which the discriminator trains (0 = all of them). ASE takes
  /// one discriminator step per ~2700 samples; with 2048 samples and 6 epochs of 2 minibatches
  /// every epoch gives one per ~170, which saturates it and costs half the update.
  int disc_epochs = 0;
  double mismatch_fraction =
      0.25;  ///< Conditional: demo windows paired with a wrong z as negatives.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(enabled));
    a->Visit(SIMS_NVP(conditional));
    a->Visit(SIMS_NVP(loss));
    a->Visit(SIMS_NVP(task_weight));
    a->Visit(SIMS_NVP(style_weight));
    a->Visit(SIMS_NVP(reward_scale));
    a->Visit(SIMS_NVP(disc_coef));
    a->Visit(SIMS_NVP(grad_penalty));
    a->Visit(SIMS_NVP(logit_reg));
    a->Visit(SIMS_NVP(weight_decay));
    a->Visit(SIMS_NVP(replay_size));
    a->Visit(SIMS_NVP(replay_keep_prob));
    a->Visit(SIMS_NVP(demo_pool_size));
    a->Visit(SIMS_NVP(demo_refresh));
    a->Visit(SIMS_NVP(grad_norm));
    a->Visit(SIMS_NVP(batch_size));
    a->Visit(SIMS_NVP(disc_epochs));
    a->Visit(SIMS_NVP(mismatch_fraction));
  }
  /// Checks ranges and names.
  void Validate() const;
};

/// Everything the learner needs besides the environment.
struct LearnerConfig {
  NetworkConfig network;  ///< Network sizes.
  PpoConfig ppo;          ///< PPO.
  AmpConfig amp;          ///< AMP.
  uint64_t seed = 0;      ///< Network init, sampling noise, minibatch order.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(network));
    a->Visit(SIMS_NVP(ppo));
    a->Visit(SIMS_NVP(amp));
    a->Visit(SIMS_NVP(seed));
  }
};

}  // namespace sims::learning
