#include "sims/eval/policy_eval.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <deque>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/eval/motion_metrics.h"
#include "sims/humanoid/features.h"
#include "sims/humanoid/state.h"
#include "sims/io/gltf_export.h"
#include "sims/io/motion_record.h"
#include "sims/language/embedding_bank.h"
#include "sims/language/motion_text.h"
#include "sims/learning/text_styles.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"
#include "sims/scene/loaders.h"
#include "sims/task/handoff.h"
#include "sims/task/object_skill.h"
#include "sims/task/unified/unified.h"

namespace sims::eval {

namespace {

// Forwards everything to the skill and records its per-env metrics right after each Step,
// before the environment resets a finished env (which overwrites the skill's state).
class RecordingHook : public sim::TaskHook {
 public:
  RecordingHook(std::shared_ptr<task::Skill> skill, int n)
      : skill_(std::move(skill)),
        error_(n, 0.0),
        offset_(n, Eigen::Vector3d::Zero()),
        completed_(n, 0),
        num_steps_(n, 1) {
    unified_ = dynamic_cast<task::UnifiedSkill*>(skill_.get());
  }
  int obs_dim() const override { return skill_->obs_dim(); }
  std::vector<sim::ObsSegment> obs_segments() const override { return skill_->obs_segments(); }
  void SampleInitialState(int i, Rng& rng, sim::InitialState* init) override {
    skill_->SampleInitialState(i, rng, init);
  }
  void OnReset(const sim::EnvView& v, Rng& rng) override { skill_->OnReset(v, rng); }
  void Observe(const sim::EnvView& v, float* out) const override { skill_->Observe(v, out); }
  uint32_t contact_body_mask() const override { return skill_->contact_body_mask(); }
  int style_id(int i) const override { return skill_->style_id(i); }
  std::vector<double> SaveEnvState(int i) const override { return skill_->SaveEnvState(i); }
  void LoadEnvState(int i, const std::vector<double>& s) override { skill_->LoadEnvState(i, s); }

  sim::TaskStepResult Step(const sim::EnvView& v) override {
    const sim::TaskStepResult r = skill_->Step(v);
    const int i = v.env_id;
    error_[i] = skill_->goal_error(v);
    offset_[i] = GoalOffset(v);
    if (unified_) {  // a chain of contacts: progress through its steps
      completed_[i] = unified_->steps_completed(i);
      num_steps_[i] = static_cast<int>(unified_->steps(i).size());
    }
    return r;
  }

  double error(int i) const { return error_[i]; }
  const Eigen::Vector3d& offset(int i) const { return offset_[i]; }
  int completed(int i) const { return completed_[i]; }
  int num_steps(int i) const { return num_steps_[i]; }
  bool multi_step() const { return unified_ != nullptr; }

 private:
  // The first active contact joint's offset from its goal in the heading frame (x forward,
  // y left, z up): a seated pelvis's offset tells a target-placement bias from aiming noise.
  Eigen::Vector3d GoalOffset(const sim::EnvView& v) const {
    const uint32_t mask = skill_->goal_mask(v.env_id);
    for (int j = 0; j < humanoid::kNumContactJoints; ++j) {
      if (!(mask & (1u << j))) continue;
      const Eigen::Vector3d p_WJ = humanoid::ContactJointPosition(*v.bodies, j);
      return humanoid::HeadingInverse(v.pose->root_rot) * (p_WJ - skill_->goal(v.env_id, j));
    }
    return Eigen::Vector3d::Zero();
  }

  std::shared_ptr<task::Skill> skill_;
  task::UnifiedSkill* unified_ = nullptr;
  std::vector<double> error_;
  std::vector<Eigen::Vector3d> offset_;
  std::vector<int> completed_, num_steps_;
};

struct ResolvedConfig {
  task::SkillConfig skill;
  sim::EnvConfig env;
};

ResolvedConfig ResolveConfig(const PolicyEvalOptions& o, const learning::Policy& policy) {
  ResolvedConfig rc;
  const std::string src = o.checkpoint.string();
  if (!o.config.empty()) {
    const auto tc = LoadConfig<learning::TrainConfig>(o.config);
    rc.skill = tc.skill;
    rc.env = tc.env;
  } else {
    auto stored = learning::ReadPolicyConfigs(policy, src);
    if (!stored.env)
      ThrowInputError(src, "metadata.extra.env",
                      "the env config train_policy stores with a policy (or --config)", "none");
    rc.skill = std::move(stored.skill);
    rc.env = *stored.env;
  }
  if (!o.skill.empty() && o.skill != rc.skill.skill)
    ThrowInputError(src, "extra.skill.skill", "a '" + o.skill + "' policy (--skill)",
                    "a '" + rc.skill.skill + "' policy");
  return rc;
}

// What --style-eval needs: the classifier, and per emotion the held-out captions' z.
struct StyleTrials {
  std::unique_ptr<StyleClassifier> classifier;
  Eigen::MatrixXd reference;               // pose features of the skill's clips (SIMS Tab. 3)
  std::vector<Eigen::MatrixXd> generated;  // ... of each trial's motion
  std::vector<std::string> emotions;
  std::map<std::string, std::vector<std::pair<std::string, Eigen::VectorXf>>> captions;
  StyleEvalReport report;
};

StyleTrials PrepareStyleTrials(const PolicyEvalOptions& o, const task::SkillConfig& sc,
                               const motion::MotionLibrary* lib) {
  if (!lib)
    ThrowInputError(o.checkpoint.string(), "extra.skill.motion.manifest",
                    "a motion manifest (the classifier learns styles from its clips) for "
                    "--style-eval",
                    "none");
  StyleTrials st;
  std::vector<const motion::MotionClip*> train, heldout;
  for (int i = 0; i < lib->num_clips(); ++i) {
    const motion::MotionClip& c = lib->clip(i);
    if (c.meta().skill != sc.skill) continue;
    (IsClipVariant(c.meta()) ? heldout : train).push_back(&c);
  }
  if (train.empty())
    ThrowInputError(sc.motion.manifest, "clips", "clips of skill '" + sc.skill + "'", "none");
  st.classifier = std::make_unique<StyleClassifier>(StyleClassifier::Train(train));
  std::vector<Eigen::MatrixXd> parts;
  for (const auto* list : {&train, &heldout})
    for (const motion::MotionClip* c : *list)
      parts.push_back(PoseFeatures(io::RecordFromClip(*c, 30.0), 3));
  st.reference = StackRows(parts);
  st.report.classifier_heldout = st.classifier->Score(heldout, /*segment_frames=*/90);
  st.report.chance = 1.0 / static_cast<double>(st.classifier->labels().size());

  const std::filesystem::path captions =
      o.style_captions.empty() ? ConfigPath("language/test_paraphrases.json") : o.style_captions;
  const std::filesystem::path model = !o.style_model.empty() ? o.style_model
                                      : !sc.style_model.empty()
                                          ? std::filesystem::path(sc.style_model)
                                          : language::DefaultStyleModelDir();
  st.report.captions = captions.string();
  st.report.model = model.string();
  const auto embedder = language::StyleEmbedder::Load(model);
  const nlohmann::json j = ReadJsonFile(captions);
  if (!j.contains("queries") || !j["queries"].is_array())
    ThrowInputError(captions.string(), "queries", "an array of {caption, clip}",
                    j.dump().substr(0, 80));
  for (const auto& q : j["queries"]) {
    if (!q.contains("caption") || !q["caption"].is_string() || !q.contains("clip") ||
        !q["clip"].is_string())
      ThrowInputError(captions.string(), "queries[]", "{\"caption\": text, \"clip\": name}",
                      q.dump());
    const std::string clip = q["clip"];
    for (int i = 0; i < lib->num_clips(); ++i) {
      const motion::MotionMeta& m = lib->clip(i).meta();
      if (m.name != clip || m.mirrored || m.skill != sc.skill) continue;
      if (st.classifier->LabelIndex(m.emotion) < 0) break;
      const std::string caption = q["caption"];
      st.captions[m.emotion].emplace_back(caption, embedder.Embed(caption));
      break;
    }
  }
  for (const auto& [emotion, list] : st.captions) st.emotions.push_back(emotion);
  if (st.emotions.size() < 2)
    ThrowInputError(captions.string(), "queries",
                    "captions of at least two emotions of '" + sc.skill + "' clips",
                    std::to_string(st.emotions.size()));
  st.report.emotions = st.emotions;
  return st;
}

}  // namespace

nlohmann::json PolicyEvalReport::ToJson() const {
  nlohmann::json per = nlohmann::json::array();
  for (const auto& t : results) {
    per.push_back({{"success", t.success},
                   {"fell", t.fell},
                   {"force_end", t.force_end},
                   {"success_step", t.success_step},
                   {"contact_error", t.contact_error},
                   {"min_contact_error", t.min_contact_error},
                   {"goal_offset", {t.goal_offset.x(), t.goal_offset.y(), t.goal_offset.z()}},
                   {"steps_completed", t.steps_completed},
                   {"num_steps", t.num_steps},
                   {"length", t.length}});
    if (!t.start.empty()) per.back()["start"] = t.start;
    per.back()["touching"] = t.touching;
    if (!t.object.empty()) {
      per.back()["object"] = t.object;
      per.back()["object_extent"] = {t.object_extent.x(), t.object_extent.y(), t.object_extent.z()};
      per.back()["start_distance"] = t.start_distance;
    }
    if (style) {
      per.back()["caption"] = t.caption;
      per.back()["emotion"] = t.emotion;
      per.back()["style"] = t.style;
    }
  }
  nlohmann::json out = {
      {"skill", skill},
      {"checkpoint", checkpoint},
      {"scene", scene},
      {"trials", trials},
      {"seed", seed},
      {"success_rate", success_rate},
      {"fall_rate", fall_rate},
      {"force_end_rate", force_end_rate},
      {"contact_error", contact_error},
      {"min_contact_error", min_contact_error},
      {"success_steps", success_steps},
      {"mean_num_steps", mean_num_steps},
      {"time_to_success_s", time_to_success},
      {"mean_length", mean_length},
      {"foot_sliding_m_per_s", foot_sliding},
      {"foot_sliding_ratio", foot_sliding_ratio},
      {"action_rate_rms", action_rate_rms},
      {"control_dt", control_dt},
      {"ablation", {{"no_text", ablation.no_text}, {"no_heightmap", ablation.no_heightmap}}},
      {"reference_starts", reference_starts},
      {"clutter", clutter},
      {"action_smoothing", action_smoothing},
      {"results", per}};
  if (!by_start.empty()) {
    nlohmann::json groups = nlohmann::json::object();
    for (const auto& [label, g] : by_start)
      groups[label] = {{"trials", g.trials},
                       {"success_rate", g.success_rate},
                       {"fall_rate", g.fall_rate},
                       {"time_to_success_s", g.time_to_success}};
    out["by_start"] = groups;
  }
  if (style) {
    const StyleAccuracy& h = style->classifier_heldout;
    out["style_accuracy"] = style->accuracy;
    out["style_per_emotion"] = style->per_emotion;
    out["style_chance"] = style->chance;
    out["style_emotions"] = style->emotions;
    out["style_captions"] = style->captions;
    out["style_model"] = style->model;
    out["fid"] = style->fid;
    out["apd"] = style->apd;
    out["reference_apd"] = style->reference_apd;
    out["style_classifier_heldout"] = {{"accuracy", h.accuracy},
                                       {"per_label", h.per_label},
                                       {"segments", h.motions},
                                       {"total", h.total}};
  }
  return out;
}

PolicyEvalReport EvaluatePolicy(const PolicyEvalOptions& o) {
  if (o.trials <= 0)
    ThrowInputError("--trials", "trials", "a positive count", std::to_string(o.trials));
  const learning::Policy policy(o.checkpoint);
  ResolvedConfig rc = ResolveConfig(o, policy);
  task::SkillConfig& sc = rc.skill;
  const int n_env = o.num_envs > 0 ? o.num_envs : std::min(o.trials, 16);

  // Evaluation settings: standing starts, held-out objects, and the skill's own (walk: fixed
  // targets 3–5 m away).
  const task::SkillInfo& info = task::FindSkill(sc.skill);
  sc.object.held_out_objects = o.held_out;
  if (o.num_objects < 0)
    ThrowInputError("--objects", "num_objects", "a non-negative count (0 = the policy's)",
                    std::to_string(o.num_objects));
  if (o.num_objects > 0) sc.object.num_objects = o.num_objects;
  sc.object.spawn_curriculum = false;  // the full spawn-distance range
  // Standing starts unless asked for the training's clip starts (a diagnostic: can the policy
  // finish a motion it is placed in?).
  if (!(o.reference_starts >= 0 && o.reference_starts <= 1))
    ThrowInputError("--reference-starts", "reference_starts", "a share in [0, 1]",
                    std::to_string(o.reference_starts));
  sc.reference_init_prob = o.reference_starts;
  if (!(o.clutter >= 0 && o.clutter <= 1))
    ThrowInputError("--clutter", "clutter", "a share in [0, 1]", std::to_string(o.clutter));
  sc.object.clutter_share = o.clutter;
  if (!sc.style_conditioned && o.reference_starts == 0 && !o.style_eval) sc.motion.manifest.clear();
  if (info.configure_eval && !o.training_starts) info.configure_eval(&sc);
  sim::EnvConfig ec = rc.env;
  ec.num_envs = n_env;
  ec.seed = o.seed;
  ec.threads = o.threads;
  ec.early_termination = true;
  if (o.action_smoothing >= 0) {
    sim::CheckActionSmoothing(o.action_smoothing, "--action-smoothing", "action_smoothing");
    ec.action_smoothing = o.action_smoothing;
  }

  std::shared_ptr<const scene::Scene> scene;
  task::ContactPlan plan;
  if (!o.scene_plan.empty()) {
    if (!info.traits.contact_steps)
      ThrowInputError(o.checkpoint.string(), "extra.skill.skill",
                      "a policy of a chain-of-contacts skill (" +
                          SkillNames([](const SkillTraits& t) { return t.contact_steps; }) +
                          ") to run a ScenePlan (--scene-plan)",
                      "a '" + sc.skill + "' policy");
    auto loaded = task::LoadScenePlanRef(o.scene_plan, o.partnet_root);
    scene = loaded.scene;
    plan = std::move(loaded.plan);
    // UniHSI: a plan of n steps must finish within n × 10 s.
    ec.episode_length = static_cast<int>(plan.steps.size()) * 300;
  }

  task::SkillSetup setup = task::CreateSkill(sc, n_env, o.seed, scene, &ec);
  learning::ApplyStyleModel(sc, &setup);
  if (scene) dynamic_cast<task::UnifiedSkill&>(*setup.skill).SetPlan(plan.steps);
  auto hook = std::make_shared<RecordingHook>(setup.skill, n_env);
  sim::BatchedEnv env(setup.context.humanoid, ec, hook);
  if (env.obs_dim() != policy.obs_dim())
    ThrowInputError(o.checkpoint.string(), "obs_dim",
                    std::to_string(env.obs_dim()) + " values, what the '" + sc.skill +
                        "' environment built from the policy's metadata observes",
                    std::to_string(policy.obs_dim()) +
                        " (the policy was trained with another layout, e.g. heightmap size)");
  if (env.action_dim() != policy.action_dim())
    ThrowInputError(o.checkpoint.string(), "action_dim", std::to_string(env.action_dim()),
                    std::to_string(policy.action_dim()));

  PolicyEvalReport rep;
  rep.skill = sc.skill;
  rep.checkpoint = o.checkpoint.string();
  rep.scene =
      scene ? scene->name + (plan.id.empty() ? "" : " plan " + plan.id) : setup.context.scene->name;
  rep.trials = o.trials;
  rep.seed = o.seed;
  rep.control_dt = env.control_dt();
  rep.ablation = o.ablation;
  rep.reference_starts = o.reference_starts;
  rep.clutter = o.clutter;
  rep.action_smoothing = ec.action_smoothing;
  rep.results.resize(o.trials);
  // Each env runs trial after trial; env i's k-th trial is a fixed trial index.
  std::vector<int> trial(n_env, -1);
  int next = 0;
  StyleTrials st;
  if (o.style_eval) st = PrepareStyleTrials(o, sc, setup.context.motions.get());
  // Style evaluation: trial k pursues emotion k mod E with that emotion's (k / E)-th caption;
  // its motion (one frame per control step) is labelled when it ends.
  std::vector<std::vector<motion::MotionFrame>> motion(n_env);
  // --record: the first record_trials trials' frames, written when each trial ends.
  const int record_trials = o.record_dir.empty() ? 0 : o.record_trials;
  if (record_trials > 0) std::filesystem::create_directories(o.record_dir);
  std::vector<std::unique_ptr<io::MotionRecordBuilder>> recording(n_env);
  // Foot sliding over every trial's steps; a pair across a reset is not a move.
  FootSlidingMeter sliding;
  auto feet = [&](int i) {
    const humanoid::BodyStates& b = env.bodies(i);
    return std::array<Eigen::Vector3d, 2>{b.pos[humanoid::kLeftFoot], b.pos[humanoid::kRightFoot]};
  };
  std::vector<std::array<Eigen::Vector3d, 2>> feet_before(n_env);
  for (int i = 0; i < n_env; ++i) feet_before[i] = feet(i);
  // Chatter: the policy's PD targets against its previous step's in the same trial.
  std::vector<std::array<double, humanoid::kNumDofs>> targets_before(n_env);
  std::vector<char> has_targets(n_env, 0);
  ActionRateMeter action_rate;
  // --end-states: each env's last state before a reset and the object it was on (a reset may
  // pick another object).
  const auto* object_skill = dynamic_cast<const task::ObjectSkill*>(setup.skill.get());
  const bool keep_ends = !o.end_states.empty() && object_skill;
  std::vector<humanoid::HumanoidPose> last_pose(n_env);
  std::vector<const task::ObjectGeometry*> last_object(n_env, nullptr);
  std::vector<task::HandoffState> end_states;
  auto keep_last = [&](int i) {
    last_pose[i] = env.pose(i);
    last_object[i] = &object_skill->geometry(i);
  };
  if (keep_ends)
    for (int i = 0; i < n_env; ++i) keep_last(i);
  // What touched the scene besides feet on the floor in each env's last second of steps (the
  // step that ends a trial has already reset the env): a brush now and then is enough to break
  // a success that must hold, so the last step alone showed nothing in the recorded bed trials.
  const int touch_window = std::max(1, static_cast<int>(std::lround(1.0 / rep.control_dt)));
  std::vector<std::deque<uint32_t>> touching(n_env);
  auto keep_touching = [&](int i) {
    touching[i].push_back(task::OffFloorContacts(*setup.context.humanoid, env.data(i)));
    if (static_cast<int>(touching[i].size()) > touch_window) touching[i].pop_front();
  };
  auto begin_trial = [&](int i) {
    if (trial[i] < 0) return;
    rep.results[trial[i]].start = setup.skill->start_label(i);
    if (object_skill && setup.context.scene) {
      TrialResult& t = rep.results[trial[i]];
      const task::ObjectGeometry& g = object_skill->geometry(i);
      t.object = setup.context.scene->objects[g.object].instance;
      t.object_extent = g.local.max - g.local.min;
      t.start_distance = (env.pose(i).root_pos.head<2>() - g.center).norm();
    }
    if (trial[i] < record_trials) {
      recording[i] =
          std::make_unique<io::MotionRecordBuilder>(setup.context.humanoid, 1.0 / rep.control_dt);
      recording[i]->SetTitle(fmt::format("{} trial {}", sc.skill, trial[i]));
      recording[i]->SetScene({setup.context.scene ? setup.context.scene->name : "", ""});
      io::KeyframeAnnotation a;
      a.skill = sc.skill;
      a.caption = rep.results[trial[i]].start;
      recording[i]->BeginKeyframe(a);
      recording[i]->AddFrame(env.pose(i));
    }
    if (!o.style_eval) return;
    const int k = trial[i], e = static_cast<int>(st.emotions.size());
    const auto& list = st.captions.at(st.emotions[k % e]);
    const auto& [caption, z] = list[(k / e) % list.size()];
    rep.results[k].caption = caption;
    rep.results[k].emotion = st.emotions[k % e];
    setup.skill->SetStyleVector(i, z);
    env.RefreshTaskObservation(i);
    motion[i].clear();
  };

  for (int i = 0; i < n_env && next < o.trials; ++i) trial[i] = next++;
  for (int i = 0; i < n_env; ++i) begin_trial(i);
  int finished = 0;
  const std::vector<sim::ObsSegment> segments = setup.skill->obs_segments();
  std::vector<float> actions(static_cast<size_t>(n_env) * env.action_dim());
  while (finished < o.trials) {
    o.ablation.Apply(segments, n_env, env.obs_dim(), env.observations());
    policy.Act(env.observations(), n_env, actions.data());
    for (int i = 0; i < n_env; ++i) {
      if (trial[i] < 0) continue;
      std::array<double, humanoid::kNumDofs> now;
      setup.context.humanoid->ActionToTargets(actions.data() + i * env.action_dim(), now.data());
      if (has_targets[i]) action_rate.Add(targets_before[i].data(), now.data(), humanoid::kNumDofs);
      targets_before[i] = now;
      has_targets[i] = 1;
    }
    env.Step(actions.data());
    for (int i = 0; i < n_env; ++i) {
      const std::array<Eigen::Vector3d, 2> now = feet(i);
      if (trial[i] >= 0 && !env.dones()[i])
        for (int k = 0; k < 2; ++k) sliding.Add(feet_before[i][k], now[k], rep.control_dt);
      feet_before[i] = now;
    }
    for (int i = 0; i < n_env; ++i) {
      if (trial[i] < 0) continue;
      TrialResult& t = rep.results[trial[i]];
      t.min_contact_error =
          t.length == 0 ? hook->error(i) : std::min(t.min_contact_error, hook->error(i));
      ++t.length;
      // Success counts once the task reports itself accomplished (held as long as required).
      if (env.completions()[i] && t.success_step < 0) t.success_step = t.length;
      if (!env.dones()[i] && recording[i]) recording[i]->AddFrame(env.pose(i));
      if (!env.dones()[i] && keep_ends) keep_last(i);
      if (!env.dones()[i]) {
        keep_touching(i);
        if (o.style_eval) {
          const humanoid::HumanoidPose& p = env.pose(i);
          motion::MotionFrame f;
          f.root_pos = p.root_pos;
          f.root_rot = p.root_rot;
          f.dof_pos = p.dof_pos;
          motion[i].push_back(f);
        }
        continue;
      }
      if (o.style_eval) {
        const int label = st.classifier->Classify(motion[i]);
        t.style = label >= 0 ? st.classifier->labels()[label] : "";
        io::MotionRecordBuilder record(setup.context.humanoid);
        for (const motion::MotionFrame& f : motion[i]) {
          humanoid::HumanoidPose p;
          p.root_pos = f.root_pos;
          p.root_rot = f.root_rot;
          p.dof_pos = f.dof_pos;
          record.AddFrame(p);
        }
        if (!motion[i].empty()) st.generated.push_back(PoseFeatures(record.Finish(), 3));
      }
      has_targets[i] = 0;
      t.fell = env.end_reasons()[i] == sim::EndReason::kFall ||
               env.end_reasons()[i] == sim::EndReason::kUnstable;
      t.force_end = env.end_reasons()[i] == sim::EndReason::kTaskTerminate;
      t.contact_error = hook->error(i);
      t.goal_offset = hook->offset(i);
      uint32_t touched = 0;
      for (const uint32_t m : touching[i]) touched |= m;
      touching[i].clear();
      for (int b = 0; b < humanoid::kNumBodies; ++b)
        if (touched & (1u << b)) t.touching.push_back(humanoid::BodyNames()[b]);
      if (hook->multi_step()) {
        t.steps_completed = hook->completed(i);
        t.num_steps = hook->num_steps(i);
        t.success = !t.fell && !t.force_end && t.steps_completed == t.num_steps;
      } else {
        t.success = !t.fell && !t.force_end && t.success_step >= 0;
        t.steps_completed = t.success ? 1 : 0;
      }
      if (keep_ends && !t.fell && !t.force_end) {
        const std::string part = object_skill->support_part(*last_object[i]);
        if (!part.empty())
          end_states.push_back(
              task::MakeHandoffState(sc.skill, part, *last_object[i], last_pose[i], t.success));
      }
      if (recording[i]) {
        recording[i]->EndKeyframe(t.success,
                                  fmt::format("{}; {} steps; goal error {:.3f} m (least {:.3f} m)",
                                              t.fell        ? "fell"
                                              : t.force_end ? "ended by the task"
                                              : t.success   ? "succeeded"
                                                            : "timed out",
                                              t.length, t.contact_error, t.min_contact_error));
        const io::MotionRecord r = recording[i]->Finish();
        const std::string stem = "trial_" + std::to_string(trial[i]);
        io::SaveMotionRecord(r, o.record_dir / (stem + ".json"));
        io::ExportGltf(r, setup.context.scene.get(), o.record_dir / (stem + ".glb"));
        recording[i].reset();
      }
      ++finished;
      trial[i] = next < o.trials ? next++ : -1;
      begin_trial(i);
    }
  }

  if (!o.end_states.empty()) {
    if (end_states.empty())
      ThrowInputError(o.checkpoint.string(), "extra.skill.skill",
                      "a policy of a skill that rests the character on a furniture part (e.g. "
                      "sit, lie) with at least one trial that did not fall, for --end-states",
                      "'" + sc.skill + "' with no such trial");
    task::SaveHandoffStates(end_states, o.end_states);
    spdlog::info("wrote {} end states to {}", end_states.size(), o.end_states.string());
  }
  int successes = 0;
  rep.mean_num_steps = 0;
  for (const auto& t : rep.results) {
    successes += t.success;
    rep.fall_rate += t.fell;
    rep.force_end_rate += t.force_end;
    rep.contact_error += t.contact_error;
    rep.min_contact_error += t.min_contact_error;
    rep.success_steps += t.steps_completed;
    rep.mean_num_steps += t.num_steps;
    rep.mean_length += t.length;
    if (t.success) rep.time_to_success += t.success_step * rep.control_dt;
  }
  const double n = o.trials;
  rep.success_rate = successes / n;
  rep.fall_rate /= n;
  rep.force_end_rate /= n;
  rep.contact_error /= n;
  rep.min_contact_error /= n;
  rep.success_steps /= n;
  rep.mean_num_steps /= n;
  rep.mean_length /= n;
  const FootSliding slid = sliding.Result();
  rep.foot_sliding = slid.mean_speed;
  rep.foot_sliding_ratio = slid.sliding_ratio;
  rep.action_rate_rms = action_rate.Rms();
  rep.time_to_success = successes ? rep.time_to_success / successes : 0.0;
  for (const auto& t : rep.results) {
    if (t.start.empty()) continue;
    PolicyEvalReport::StartGroup& g = rep.by_start[t.start];
    ++g.trials;
    g.success_rate += t.success;
    g.fall_rate += t.fell;
    if (t.success) g.time_to_success += t.success_step * rep.control_dt;
  }
  for (auto& [label, g] : rep.by_start) {
    g.time_to_success = g.success_rate > 0 ? g.time_to_success / g.success_rate : 0.0;
    g.success_rate /= g.trials;
    g.fall_rate /= g.trials;
  }
  if (o.style_eval) {
    std::map<std::string, int> right, count;
    int correct = 0;
    for (const auto& t : rep.results) {
      ++count[t.emotion];
      right[t.emotion] += t.style == t.emotion;
      correct += t.style == t.emotion;
    }
    for (const auto& [emotion, c] : count)
      st.report.per_emotion[emotion] = static_cast<double>(right[emotion]) / c;
    st.report.accuracy = correct / n;
    const Eigen::MatrixXd gen = StackRows(st.generated);
    if (gen.rows() > 1 && st.reference.rows() > 1) {
      st.report.fid = FrechetDistance(gen, st.reference);
      st.report.apd = AveragePairwiseDistance(gen);
      st.report.reference_apd = AveragePairwiseDistance(st.reference);
    }
    spdlog::info(
        "style: accuracy {:.3f} over {} emotions (chance {:.3f}); classifier {:.3f} on "
        "its held-out clips",
        st.report.accuracy, st.emotions.size(), st.report.chance,
        st.report.classifier_heldout.accuracy);
    rep.style = st.report;
  }
  spdlog::info("eval {}: {} trials, success {:.3f}, falls {:.3f}, contact error {:.3f} m",
               rep.skill, rep.trials, rep.success_rate, rep.fall_rate, rep.contact_error);
  return rep;
}

}  // namespace sims::eval
