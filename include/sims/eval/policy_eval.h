// Policy evaluation (eval_policy): runs N trials of an exported skill policy and reports
// success rate, contact error, success steps, time to success and falls.
//
// The policy file's metadata ("extra": the skill and env configs train_policy wrote) gives the
// observation layout; the environment is rebuilt from it with evaluation settings:
//   walk:    a target 3–5 m away, kept after success; success = the pelvis within
//            walk_success_radius (0.5 m) of it at some step, without falling in the episode.
//   objects: held-out procedural objects (dimensions outside the training ranges), default
//            (standing) starts; success = the skill's success test held at some step without
//            a fall.
//   unified: random chains on held-out objects, or the steps of a UniHSI ScenePlan
//            (n steps within n × 10 s); success = every step passed.
// With style_eval, each trial's z comes from a held-out caption (cycling over emotions) and
// the trial's motion is labelled by a StyleClassifier trained on the skill's clips (generator
// variants held out and scored as its own accuracy); style accuracy = label == emotion.
// Trials run on parallel environments; each env runs trial after trial (deterministic for a
// seed). Metrics per trial are taken at the step that ends it (before the env resets).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/eval/style_classifier.h"
#include "sims/sim/task_hook.h"

#include <nlohmann/json.hpp>

namespace sims::eval {

/// What to evaluate and how.
struct PolicyEvalOptions {
  std::filesystem::path checkpoint;    ///< Policy file written by train_policy (policy.pt).
  std::string skill;                   ///< Expected skill ("" = the policy's).
  int trials = 100;                    ///< Number of trials.
  uint64_t seed = 0;                   ///< Environment seed.
  std::filesystem::path config;        ///< Optional TrainConfig JSON replacing the metadata.
  std::string scene_plan;              ///< UniHSI ScenePlan "plan.json" or "plan.json#id".
  std::filesystem::path partnet_root;  ///< PartNet folder ("" = $SIMS_PARTNET_DIR, data/partnet).
  int num_envs = 0;                    ///< Parallel environments (0 = min(trials, 16)).
  int threads = 0;                     ///< Env threads (0 = the process setting).
  bool held_out = true;                ///< Held-out object dimensions.
  /// Pieces in the evaluation ground, whatever the training's num_objects, so a run trained
  /// on more pieces is tested on the same set (0 = the policy's config).
  int num_objects = 16;
  sim::ObsAblation ablation;    ///< Inputs withheld from the policy (--no-text, ...).
  double reference_starts = 0;  ///< Share of trials started from motion clips (0–1).
  /// Share of the evaluation pieces with a table in front (ObjectParams::clutter_share), 0 =
  /// lone pieces whatever the training used, so every policy meets the same test set.
  double clutter = 0;
  /// Action smoothing α the trials run with (sim::EnvConfig::action_smoothing), to measure
  /// what a policy set's action_smoothing does; negative = the one the policy trained with.
  double action_smoothing = -1;
  /// Keeps the skill's training start settings instead of its evaluation ones (SkillInfo::
  /// configure_eval): get-up's reach into the rise or its backplay window (levels from 0), a
  /// diagnostic of what the policy trains on.
  bool training_starts = false;
  /// Style evaluation (--style-eval): trial k walks with the z of a caption the motion–text
  /// model never trained on, cycling over the emotions, and its motion is classified.
  bool style_eval = false;
  std::filesystem::path style_captions;  ///< {"queries": [{caption, clip}]} ("" = test set).
  std::filesystem::path style_model;     ///< Motion–text model ("" = the policy's or default).
  /// When set, the first record_trials trials are written to this folder as trial_<k>.json
  /// (io::MotionRecord, one frame per control step, the outcome as its keyframe) and
  /// trial_<k>.glb (the scene and the animated character), to watch what a policy does.
  std::filesystem::path record_dir;
  int record_trials = 0;  ///< How many trials --record keeps (from trial 0).
  /// When set, the state each trial of an object skill with a support part (sit, lie) ends in
  /// (the last step before the reset; falls and force-ended trials left out) is written here
  /// as hand-off states (task/handoff.h), relative to the trial's object part.
  std::filesystem::path end_states;
};

/// One trial.
struct TrialResult {
  bool success = false;          ///< Goal reached (all steps) without a fall.
  bool fell = false;             ///< Ended by a fall or a simulation blow-up.
  bool force_end = false;        ///< Ended by the task's excessive-contact-force termination.
  int success_step = -1;         ///< First control step at which the task completed (−1: never).
  double contact_error = 0;      ///< Skill goal error at the end of the trial (m).
  double min_contact_error = 0;  ///< Smallest skill goal error during the trial (m).
  /// At the end: the first active contact joint minus its goal (m), in the heading frame
  /// (x forward, y left, z up).
  Eigen::Vector3d goal_offset = Eigen::Vector3d::Zero();
  int steps_completed = 0;  ///< Plan steps passed (single-step skills: 1 on success).
  int num_steps = 1;        ///< Plan steps of the trial.
  int length = 0;           ///< Control steps the trial ran.
  std::string start;        ///< How the trial started (Skill::start_label; "" = no kinds).
  /// Object skills: the piece of the trial (instance id), its object-frame extent (m) and the
  /// pelvis's horizontal distance from the piece's centre at the start (m), so failures can be
  /// grouped by size and approach length ("" / zeros for other skills).
  std::string object;
  Eigen::Vector3d object_extent = Eigen::Vector3d::Zero();
  double start_distance = 0;  ///< ...
  /// Bodies that touched the scene other than a foot on the floor in the trial's last second
  /// (why a get-up that stands does not count: a shin brushing the bed frame).
  std::vector<std::string> touching;
  std::string caption;  ///< Style evaluation: the caption whose z the policy saw.
  std::string emotion;  ///< ... its emotion.
  std::string style;    ///< ... the classifier's label of the motion ("" = too short).
};

/// Style evaluation results (PolicyEvalOptions::style_eval).
struct StyleEvalReport {
  std::string captions;                       ///< Caption file used.
  std::string model;                          ///< Motion–text model folder.
  std::vector<std::string> emotions;          ///< Emotions with captions, in trial order.
  double accuracy = 0;                        ///< Trials classified as their emotion.
  std::map<std::string, double> per_emotion;  ///< Emotion → accuracy.
  double chance = 0;                          ///< 1 / classifier labels.
  StyleAccuracy classifier_heldout;           ///< The classifier on its held-out clips.
  double fid = 0;            ///< FID of the trials' pose features against the skill's clips.
  double apd = 0;            ///< APD of the trials' pose features (diversity).
  double reference_apd = 0;  ///< APD of the clips' pose features.
};

/// Aggregated results.
struct PolicyEvalReport {
  std::string skill;               ///< Evaluated skill.
  std::string checkpoint;          ///< Policy file.
  std::string scene;               ///< Scene name (training ground or plan).
  int trials = 0;                  ///< Trials run.
  uint64_t seed = 0;               ///< Seed.
  double control_dt = 1.0 / 30.0;  ///< Seconds per control step.
  double success_rate = 0;         ///< Fraction of successful trials.
  double fall_rate = 0;            ///< Fraction of trials that ended by a fall.
  double force_end_rate = 0;       ///< Fraction ended by excessive contact force.
  double contact_error = 0;        ///< Mean final goal error (m).
  double min_contact_error = 0;    ///< Mean over trials of the smallest goal error (m).
  double success_steps = 0;        ///< Mean plan steps passed per trial.
  double mean_num_steps = 1;       ///< Mean plan steps per trial.
  double time_to_success = 0;      ///< Mean seconds to first success (successful trials).
  double mean_length = 0;          ///< Mean trial length (control steps).
  /// Mean horizontal foot speed while a foot is down, over all trials (eval::FootSliding).
  double foot_sliding = 0;
  double foot_sliding_ratio = 0;  ///< Share of those foot moves faster than 0.1 m/s.
  /// RMS change of the policy's PD targets from one control step to the next within a trial
  /// (rad, over joints and steps): chatter, which the feet show as sliding.
  double action_rate_rms = 0;
  sim::ObsAblation ablation;    ///< Inputs that were withheld.
  double reference_starts = 0;  ///< Share of trials asked to start from motion clips.
  double clutter = 0;           ///< Share of the pieces with a table in front.
  double action_smoothing = 0;  ///< The action smoothing α the trials ran with.
  /// Per start kind (skills with start labels, e.g. get-up's seat/bed/floor/fall).
  struct StartGroup {
    int trials = 0;              ///< Trials that started this way.
    double success_rate = 0;     ///< Their success rate.
    double fall_rate = 0;        ///< Their fall rate.
    double time_to_success = 0;  ///< Mean seconds to success (successful ones).
  };
  std::map<std::string, StartGroup> by_start;  ///< Start label → results (empty: no labels).
  std::optional<StyleEvalReport> style;        ///< Present with --style-eval.
  std::vector<TrialResult> results;            ///< Per trial.

  /// JSON with the aggregates and the per-trial results.
  nlohmann::json ToJson() const;
};

/// Runs the evaluation; throws sims::Error naming the file and field on bad input (missing
/// policy, metadata without configs, skill or observation-size mismatch, bad plan).
PolicyEvalReport EvaluatePolicy(const PolicyEvalOptions& options);

}  // namespace sims::eval
