#include "sims/fsm/story_runner.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <omp.h>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/parallel.h"
#include "sims/core/progress.h"
#include "sims/core/rng.h"
#include "sims/core/skill_vocabulary.h"
#include "sims/humanoid/features.h"
#include "sims/learning/train_run.h"
#include "sims/learning/trainer.h"
#include "sims/scene/contact_targets.h"
#include "sims/sim/env.h"
#include "sims/sim/scene_physics.h"
#include "sims/task/skill.h"

namespace sims::fsm {

void StoryOptions::Validate() const {
  Require(success_hold_steps >= 1, "success_hold_steps", "at least 1 step");
  Require(walk_timeout_s > 0 && skill_timeout_s > 0, "skill_timeout_s", "positive time-outs (s)");
  Require(walk_seconds_per_m >= 0, "walk_seconds_per_m", "a non-negative time per metre (s/m)");
  Require(max_retries >= 0, "max_retries", "a non-negative count");
  Require(lookahead > 0, "lookahead", "a positive distance (m)");
  Require(walk_success_hold_steps >= 1, "walk_success_hold_steps", "at least 1 step");
  Require(walk_success_radius > 0, "walk_success_radius", "a positive distance (m)");
  Require(threads >= 0, "threads", "0 (all) or a positive count");
}

namespace {

// The env's task hook during a story: forwards to the skill of the current instruction. The
// skills' own episode logic (success-held truncation, force termination, new walk targets)
// is ignored: the FSM decides when an instruction ends, and the character is never reset.
// Skills observe in their own layouts (an object skill adds its object to walk's), so the row
// is as wide as the widest skill: the current skill fills its prefix, the rest stays zero, and
// each policy reads the prefix of its own width.
class StoryTask : public sim::TaskHook {
 public:
  StoryTask(std::shared_ptr<task::Skill> layout, int obs_dim)
      : layout_(std::move(layout)), obs_dim_(obs_dim) {}
  void set_current(task::Skill* s) { current_ = s; }
  task::Skill* current() const { return current_; }
  void set_start(const humanoid::HumanoidPose& p) { start_ = p; }
  const sim::TaskStepResult& last() const { return last_; }

  int obs_dim() const override { return obs_dim_; }
  std::vector<sim::ObsSegment> obs_segments() const override { return observer()->obs_segments(); }
  void SampleInitialState(int, Rng&, sim::InitialState* init) override { init->pose = start_; }
  void OnReset(const sim::EnvView&, Rng&) override {}
  sim::TaskStepResult Step(const sim::EnvView& view) override {
    if (!current_) return {};
    last_ = current_->Step(view);
    sim::TaskStepResult r = last_;
    r.terminate = r.truncate = false;
    return r;
  }
  void Observe(const sim::EnvView& view, float* out) const override {
    const task::Skill* s = observer();
    s->Observe(view, out);
    std::fill(out + s->obs_dim(), out + obs_dim_, 0.0f);
  }

 private:
  const task::Skill* observer() const { return current_ ? current_ : layout_.get(); }

  std::shared_ptr<task::Skill> layout_;
  int obs_dim_ = 0;
  task::Skill* current_ = nullptr;
  humanoid::HumanoidPose start_;
  sim::TaskStepResult last_;
};

struct LoadedPolicy {
  std::unique_ptr<learning::Policy> policy;
  task::SkillConfig skill_config;
  sim::EnvConfig env_config;
  bool trained_among_furniture = false;  // a walk trained in furnished rooms (walk_rooms > 0)
  double action_smoothing = 0;  // the set's for this skill, else the policy's own training's
};

LoadedPolicy LoadPolicy(const std::string& skill, const std::filesystem::path& file) {
  LoadedPolicy p;
  p.policy = std::make_unique<learning::Policy>(file);
  const auto stored = learning::ReadPolicyConfigs(*p.policy, file.string());
  p.skill_config = stored.skill;
  if (stored.env) p.env_config = *stored.env;
  const std::string trained = p.skill_config.skill;
  if (trained != skill)
    ThrowInputError(file.string(), "metadata.extra.skill.skill",
                    "a policy trained for '" + skill + "'", "'" + trained + "'");
  p.trained_among_furniture = p.skill_config.walk.rooms > 0;
  // A story never resamples targets or loads clips: the FSM sets every goal.
  p.skill_config.walk.resample_target_on_success = false;
  p.skill_config.walk.rooms = 0;  // the story places the character, in its own scene
  p.skill_config.motion.manifest.clear();
  // The story binds each instruction's object; the skill's own test (which parts it needs)
  // decides whether it can pursue it, not the categories it trained on (sit on a bed).
  p.skill_config.object.object_categories.clear();
  p.skill_config.skill = skill;
  return p;
}

// Keeps the OpenMP regions this thread opens to one thread while alive. The policies' networks
// open a region per layer to keep the BLAS single-threaded (learning/networks.cpp), but a
// story's rows fit one chunk, so there is nothing to share out, and on a busy machine each
// fork/join costs more than the layer: with 2 threads next to two training jobs, a character's
// control step took 5.3 ms instead of 0.4 ms. The actions do not depend on the thread count.
class SingleThreadedRegions {
 public:
  SingleThreadedRegions() : saved_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~SingleThreadedRegions() { omp_set_num_threads(saved_); }
  SingleThreadedRegions(const SingleThreadedRegions&) = delete;
  SingleThreadedRegions& operator=(const SingleThreadedRegions&) = delete;

 private:
  int saved_;
};

}  // namespace

struct StoryRunner::Impl {
  std::shared_ptr<const scene::Scene> scene;
  StoryOptions options;
  PolicySet policy_set;
  humanoid::StaticGeometry geometry;
  task::SkillContext context;
  std::map<std::string, LoadedPolicy> policies;
  std::map<std::string, std::shared_ptr<task::Skill>> skills;
  std::map<std::string, std::string> skill_errors;  // why a skill could not be built here
  std::unique_ptr<scene::FreeSpaceGrid> free_space;
  std::shared_ptr<StoryTask> task;
  std::unique_ptr<sim::BatchedEnv> env;
  std::vector<float> action;
  int step = 0;
  io::MotionRecordBuilder* recorder = nullptr;
  StoryRunner::ActionOverride override_fn;

  enum class Outcome { kSuccess, kTimeout, kFall };

  // One attempt of an instruction in progress (what used to be the locals of a loop that ran
  // the attempt to its end), so a driver can advance many characters one control step at a time.
  struct AttemptState {
    const Instruction* in = nullptr;
    task::Skill* skill = nullptr;
    double timeout = 0;
    task::InstructionTarget target;
    std::optional<scene::PathFollower> follower;
    bool last_stretch = true;  // success counts only once the carrot is the goal itself
    int hold_needed = 1;
    double start = 0;
    int held = 0;
  };

  // Where the character is in the story: the instruction, which attempt, and whether it runs the
  // instruction's skill, the get-up after a fall, or the get-up before a skill that starts
  // standing.
  enum class Phase { kPrepare, kAttempt, kRecover, kDone };
  struct RunState {
    const std::vector<Instruction>* instructions = nullptr;
    size_t k = 0;     // current instruction
    int attempt = 0;  // attempt of the current instruction
    Phase phase = Phase::kDone;
    AttemptState current;
    Instruction recovery;  // the get-up instruction while recovering
    Instruction prepare;   // the get-up instruction while preparing
    KeyframeOutcome out;   // outcome of the current instruction, being built
    StoryResult result;
    bool failed_before = false;
    double error_sum = 0;
    int error_count = 0;
    std::unique_ptr<ProgressReporter> progress;
    std::string log_prefix;  // names the story in a batch's interleaved log
  };
  RunState run;

  double Now() const { return step * env->control_dt(); }

  bool Fallen() const {
    const auto& b = env->bodies(0);
    return b.pos[humanoid::kHead].z() < options.fallen_head_height &&
           b.pos[humanoid::kPelvis].z() < options.fallen_pelvis_height;
  }

  sim::EnvView View() const { return env->View(0); }

  // The skill whose policy chooses the next action (valid while not done).
  const std::string& PendingSkill() const { return run.current.in->skill; }

  // The observation for the pending skill's policy, with the withheld inputs zeroed (in place,
  // as the policy sees it).
  const float* PolicyObservation() {
    options.ablation.Apply(env->task()->obs_segments(), 1, env->obs_dim(), env->observations());
    return env->observations();
  }

  // The action of this character alone (the override, else its own policy).
  void ActAlone() {
    if (override_fn)
      override_fn(PendingSkill(), env->observations(), action.data());
    else
      policies.at(PendingSkill()).policy->Act(PolicyObservation(), 1, action.data());
  }

  void ApplyAction() {
    // The running skill's smoothing blends with the targets held before, whichever skill set
    // them, so a smoothed skill takes over from the last one's pose targets.
    const auto it = policies.find(PendingSkill());
    env->set_action_smoothing(0, it == policies.end() ? 0.0 : it->second.action_smoothing);
    env->Step(action.data());
    ++step;
    if (recorder) recorder->AddFrame(env->pose(0));
  }

  // Error of the current goal: pelvis-to-target for walk-like skills, the skill's own measure
  // otherwise.
  double GoalError(const std::string& skill, const task::InstructionTarget& target) const {
    if (SkillTraitsOf(skill).navigates)
      return (env->pose(0).root_pos.head<2>() - target.point.head<2>()).norm();
    return skills.at(skill)->goal_error(View());
  }

  // Walks chase a carrot on the path: the walk policy was trained on targets metres away and
  // circles around ones it is about to pass, so it never gets a corner point as its target.
  bool Aim(AttemptState* a) {
    task::InstructionTarget t = a->target;
    if (a->follower) {
      const Eigen::Vector2d c =
          a->follower->Carrot(env->pose(0).root_pos.head<2>(), options.lookahead);
      t.point = {c.x(), c.y(), 0};
      a->last_stretch = a->follower->IsEnd(c);
    }
    const bool ok = a->skill->BeginInstruction(View(), t);
    // The observation of the last step was assembled for the previous goal (or skill).
    env->RefreshTaskObservation(0);
    return ok;
  }

  // Starts an attempt of an instruction (walks follow A* waypoints); false when the skill
  // cannot pursue the target (`note` says so). No control step is taken.
  bool BeginAttempt(const Instruction& in, AttemptState* a, std::string* note) {
    *a = AttemptState();
    a->in = &in;
    a->skill = skills.at(in.skill).get();
    const SkillTraits& traits = SkillTraitsOf(in.skill);
    const bool walk_timing = traits.timing == StoryTiming::kWalk;
    task->set_current(a->skill);
    a->skill->SetStyleVector(0, in.z);
    a->timeout = walk_timing ? options.walk_timeout_s : options.skill_timeout_s;
    std::vector<Eigen::Vector2d> waypoints;
    a->target = in.target;
    if (traits.navigates && a->target.has_point) {
      waypoints = free_space->Waypoints(env->pose(0).root_pos.head<2>(), a->target.point.head<2>());
      if (waypoints.empty()) waypoints = {a->target.point.head<2>()};  // no path: head straight
      // A detour around walls takes longer than a walk across the room.
      a->timeout +=
          options.walk_seconds_per_m *
          std::max(0.0, scene::PathLength(env->pose(0).root_pos.head<2>(), waypoints) - 5.0);
      std::string wp_text;
      for (const auto& w : waypoints) wp_text += fmt::format(" ({:.2f}, {:.2f})", w.x(), w.y());
      spdlog::debug("{}walk from ({:.2f}, {:.2f}) via{}", run.log_prefix, env->pose(0).root_pos.x(),
                    env->pose(0).root_pos.y(), wp_text);
    }
    if (!waypoints.empty()) a->follower.emplace(env->pose(0).root_pos.head<2>(), waypoints);
    if (!Aim(a)) {
      *note = "the " + in.skill + " skill cannot pursue this target";
      return false;
    }
    a->hold_needed = walk_timing ? options.walk_success_hold_steps : options.success_hold_steps;
    a->start = Now();
    a->held = 0;
    return true;
  }

  // After a control step of an attempt: its outcome if it ended (fall, success held long
  // enough, time-out), with the goal error and a note.
  std::optional<Outcome> CheckAttempt(AttemptState* a, double* error, std::string* note) {
    const std::string& skill = a->in->skill;
    // A get-up starts fallen (or lying, before a skill that starts standing): only its success
    // or time-out ends it.
    if (run.phase == Phase::kAttempt && Fallen()) {
      *error = GoalError(skill, a->target);
      return Outcome::kFall;
    }
    if (a->follower) Aim(a);
    a->held = a->last_stretch && env->successes()[0] ? a->held + 1 : 0;
    if (a->held >= a->hold_needed) {
      *error = GoalError(skill, a->target);
      return Outcome::kSuccess;
    }
    if (Now() - a->start < a->timeout) return std::nullopt;
    *error = GoalError(skill, a->target);
    spdlog::debug("{}time-out at ({:.2f}, {:.2f})", run.log_prefix, env->pose(0).root_pos.x(),
                  env->pose(0).root_pos.y());
    *note = "time-out after " + std::to_string(static_cast<int>(a->timeout)) + " s";
    return Outcome::kTimeout;
  }

  // The skill with a policy here that stands the character up (recovers_falls), or nullptr.
  const std::string* GetUpSkill() const {
    for (const auto& [name, skill] : skills)
      if (SkillTraitsOf(name).recovers_falls) return &name;
    return nullptr;
  }

  // After a fall: get up where the character lies (if a get-up policy exists). False when
  // there is none or it cannot start; true when the get-up attempt runs.
  bool BeginRecovery() {
    const std::string* up = GetUpSkill();
    if (!up) return false;
    run.recovery = Instruction();
    run.recovery.skill = *up;
    run.recovery.target.point = env->pose(0).root_pos;
    run.recovery.target.has_point = true;
    std::string note;
    return BeginAttempt(run.recovery, &run.current, &note);
  }

  // Without a working get-up the story cannot go on from the floor: the character is put
  // back on its feet at the nearest free spot, facing the way it was (the result says so).
  void ResetStanding() {
    const humanoid::HumanoidPose& now = env->pose(0);
    Eigen::Vector2d xy = now.root_pos.head<2>();
    if (auto f = free_space->NearestFree(xy, 2.0)) xy = *f;
    const Eigen::Vector3d forward = now.root_rot * Eigen::Vector3d::UnitX();
    humanoid::HumanoidPose pose;
    pose.root_pos = {xy.x(), xy.y(), humanoid::kDefaultRootHeight};
    pose.root_rot =
        Eigen::AngleAxisd(std::atan2(forward.y(), forward.x()), Eigen::Vector3d::UnitZ());
    task->set_start(pose);
    env->Reset();
    ++step;  // the reset takes one control step, so motion frames stay on the clock
    if (recorder) recorder->AddFrame(env->pose(0));
  }

  // The resumable story: Begin, then (while not done) an action for PendingSkill() and
  // Advance(), then Finish. Between control steps the character is always in an attempt
  // (kAttempt or kRecover) or done; everything that takes no control step (instructions that
  // cannot run, outcomes, starting the next attempt) happens inside Begin and Advance.
  void Begin(const std::vector<Instruction>& instructions, const Eigen::Vector3d& start,
             double start_heading, io::MotionRecordBuilder* rec, bool report_progress) {
    recorder = rec;
    step = 0;
    humanoid::HumanoidPose pose;
    pose.root_pos = {start.x(), start.y(), humanoid::kDefaultRootHeight};
    pose.root_rot = Eigen::AngleAxisd(start_heading, Eigen::Vector3d::UnitZ());
    task->set_start(pose);
    task->set_current(nullptr);
    env->Reset();
    if (recorder) recorder->AddFrame(env->pose(0));
    const std::string prefix = run.log_prefix;
    run = RunState();
    run.log_prefix = prefix;
    run.instructions = &instructions;
    if (report_progress)
      run.progress = std::make_unique<ProgressReporter>(
          "story", static_cast<int64_t>(instructions.size()), "keyframes", 5.0);
    StartInstruction();
  }

  bool Done() const { return run.phase == Phase::kDone; }

  // Steps the environment with `action` (already in `action`) and moves the FSM on.
  void Advance() {
    ApplyAction();
    double err = 0;
    std::string why;
    const auto o = CheckAttempt(&run.current, &err, &why);
    if (!o) return;
    if (run.phase == Phase::kRecover) {
      AfterRecovery(*o == Outcome::kSuccess);
    } else if (run.phase == Phase::kPrepare) {
      // Whatever the get-up did (a fall ends it too), the keyframe's attempt starts now.
      if (!StartAttempt()) StartInstruction();
    } else {
      AfterAttempt(*o, err, why);
    }
  }

  // Opens instructions in turn until one needs control steps or the story ends.
  void StartInstruction() {
    const auto& instructions = *run.instructions;
    while (run.k < instructions.size()) {
      const Instruction& in = instructions[run.k];
      KeyframeOutcome& out = run.out;
      out = KeyframeOutcome();
      out.keyframe = in.keyframe;
      out.skill = in.skill;
      out.caption = in.caption;
      out.emotion = in.emotion;
      out.object = in.object_name;
      out.start_time = Now();
      io::KeyframeAnnotation note;
      note.index = in.keyframe >= 0 ? in.keyframe : static_cast<int>(run.k);
      note.skill = in.skill;
      note.caption = in.caption;
      note.emotion = in.emotion;
      note.furniture = in.object_name;
      if (!in.placed || !skills.count(in.skill)) {
        out.note = !in.placed
                       ? "not placed: " + in.note
                       : "no usable policy for '" + in.skill + "'" +
                             (skill_errors.count(in.skill) ? ": " + skill_errors.at(in.skill) : "");
        if (recorder) recorder->AddKeyframe(note);
        EndInstruction();
        continue;
      }
      if (recorder) recorder->BeginKeyframe(note);
      run.attempt = 0;
      if (StartPreparation() || StartAttempt()) return;
    }
    Finish();
  }

  // A skill whose policy starts standing gets the character up first when it is not standing
  // (the get-up's goal does not hold: seated, lying, still down after a get-up that timed out),
  // aimed at the previous keyframe's target; the keyframe's own attempt and time-out begin
  // after it. False when there is nothing to run.
  bool StartPreparation() {
    const auto& instructions = *run.instructions;
    if (run.k == 0 || !SkillTraitsOf(instructions[run.k].skill).starts_standing) return false;
    const std::string* up = GetUpSkill();
    if (!up) return false;
    run.prepare = instructions[run.k - 1];
    run.prepare.skill = *up;
    run.prepare.keyframe = -1;
    std::string why;
    if (!BeginAttempt(run.prepare, &run.current, &why) || run.current.skill->Accomplished(View()))
      return false;
    spdlog::debug("{}{} before keyframe {}", run.log_prefix, run.prepare.skill, run.k);
    run.phase = Phase::kPrepare;
    return true;
  }

  // Starts attempt run.attempt of the current instruction; false when it ended at once (the
  // instruction is then closed).
  bool StartAttempt() {
    std::string why;
    if (BeginAttempt((*run.instructions)[run.k], &run.current, &why)) {
      // A script's get-up right after a walk, or after a sit that never sat, finds the
      // character standing: its goal holds before the policy acts.
      if (!run.current.skill->Accomplished(View())) {
        run.phase = Phase::kAttempt;
        return true;
      }
      run.out.success = true;
      run.out.contact_error = GoalError(run.current.in->skill, run.current.target);
      run.out.note = "accomplished at its start";
      CloseKeyframe();
      return false;
    }
    run.out.contact_error = 0;
    run.out.note = why;
    CloseKeyframe();
    return false;
  }

  void AfterAttempt(Outcome o, double err, const std::string& why) {
    KeyframeOutcome& out = run.out;
    out.contact_error = err;
    if (o == Outcome::kSuccess) {
      out.success = true;
    } else if (o == Outcome::kFall) {
      ++out.falls;
      if (BeginRecovery()) {
        run.phase = Phase::kRecover;
        return;
      }
      AfterRecovery(false);
      return;
    } else {
      out.note = why;
    }
    CloseKeyframe();
    StartInstruction();
  }

  void AfterRecovery(bool up) {
    KeyframeOutcome& out = run.out;
    if (up && run.attempt < options.max_retries) {
      ++out.retries;
      ++run.attempt;
      if (StartAttempt()) return;
      StartInstruction();
      return;
    }
    out.note = up ? "fell; retries exhausted" : "fell and could not get up";
    if (!up && options.reset_after_fall) {
      ResetStanding();
      out.note += "; reset standing";
    }
    CloseKeyframe();
    StartInstruction();
  }

  // Ends the current (attempted) instruction's keyframe annotation and records its outcome.
  void CloseKeyframe() {
    if (recorder) recorder->EndKeyframe(run.out.success, run.out.note);
    EndInstruction();
  }

  // Records the current instruction's outcome and moves to the next one.
  void EndInstruction() {
    const Instruction& in = (*run.instructions)[run.k];
    KeyframeOutcome& out = run.out;
    StoryResult& result = run.result;
    out.end_time = Now();
    const bool attempted = in.placed && skills.count(in.skill);
    if (attempted && (in.target.object >= 0 || SkillTraitsOf(in.skill).navigates)) {
      run.error_sum += out.contact_error;
      ++run.error_count;
    }
    if (!out.success) run.failed_before = true;
    if (!run.failed_before) ++result.success_steps;
    result.falls += out.falls;
    spdlog::info("{}keyframe {} {} '{}' {}: {} ({:.1f}-{:.1f} s, error {:.2f} m){}", run.log_prefix,
                 run.k, in.skill, in.caption, in.object_name, out.success ? "success" : "failed",
                 out.start_time, out.end_time, out.contact_error,
                 out.note.empty() ? "" : " — " + out.note);
    result.keyframes.push_back(out);
    ++run.k;
    if (run.progress) run.progress->Update(static_cast<int64_t>(run.k));
  }

  // The story's totals, once every instruction is closed.
  void Finish() {
    StoryResult& result = run.result;
    int ok = 0;
    for (const auto& o : result.keyframes) ok += o.success;
    result.success_rate =
        result.keyframes.empty() ? 0.0 : static_cast<double>(ok) / result.keyframes.size();
    result.mean_contact_error = run.error_count ? run.error_sum / run.error_count : 0.0;
    result.duration_s = Now();
    run.phase = Phase::kDone;
    recorder = nullptr;
  }
};

StoryRunner::StoryRunner(std::shared_ptr<const scene::Scene> scene, const PolicySet& policies,
                         const StoryOptions& options)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  ValidateConfig(options, "story options");
  m.scene = std::move(scene);
  m.options = options;
  m.policy_set = policies;
  m.geometry = sim::CompileSceneGeometry(*m.scene);
  m.context.humanoid = std::make_shared<const humanoid::Humanoid>(humanoid::BuildModel(m.geometry));
  m.context.scene = m.scene;
  m.context.ray_caster = std::make_shared<const scene::RayCaster>(*m.scene);
  m.context.height_grid = std::make_shared<const scene::SceneHeightGrid>(
      *m.scene, *m.context.ray_caster, scene::HeightGridConfig{});
  m.context.num_envs = 1;
  m.free_space =
      std::make_unique<scene::FreeSpaceGrid>(*m.scene, *m.context.height_grid, options.navigation);
  sim::EnvConfig env_config;
  std::shared_ptr<task::Skill> layout;
  std::string layout_file;
  int obs_dim = 0;
  // Each skill sees the heightmap of the kind of scene it was trained in: skills trained on an
  // empty floor (walk: obstacles are the navigation's job) get the flat floor's heightmap;
  // object skills and a walk trained among furniture get the story scene's.
  task::SkillContext flat = m.context;
  flat.height_grid = std::make_shared<const scene::SceneHeightGrid>(scene::Scene{});
  for (const auto& [skill, file] : policies.policies) {
    LoadedPolicy p = LoadPolicy(skill, file);
    p.skill_config.walk.success_radius = options.walk_success_radius;
    const auto smoothing = policies.action_smoothing.find(skill);
    p.action_smoothing = smoothing != policies.action_smoothing.end()
                             ? smoothing->second
                             : p.env_config.action_smoothing;
    try {
      const task::SkillInfo& info = task::FindSkill(skill);
      const bool flat_floor = info.traits.flat_scene && !p.trained_among_furniture;
      auto s = info.create(p.skill_config, flat_floor ? flat : m.context);
      const int width = humanoid::kSelfObsDim + s->obs_dim();
      if (p.policy->obs_dim() != width)
        ThrowInputError(
            file.string(), "obs_dim",
            "the width of the '" + skill + "' skill's observation (" + std::to_string(width) + ")",
            std::to_string(p.policy->obs_dim()));
      if (!layout) {
        env_config = p.env_config;
        layout = s;
        layout_file = file.string();
      }
      // One env computes every policy's self observation and steps at one control rate.
      const auto& e = p.env_config;
      if (e.substeps != env_config.substeps || e.root_height_obs != env_config.root_height_obs ||
          e.local_root_obs != env_config.local_root_obs)
        ThrowInputError(file.string(), "metadata env (substeps, root_height_obs, local_root_obs)",
                        "the settings of " + layout_file, "different ones");
      obs_dim = std::max(obs_dim, width);
      m.skills[skill] = s;
      m.policies[skill] = std::move(p);
    } catch (const Error& e) {
      if (std::string(e.what()).find(file.string()) != std::string::npos) throw;
      m.skill_errors[skill] = e.what();  // e.g. no bed in this scene: fatal only if needed
    }
  }
  if (!layout)
    ThrowInputError(policies.source.string(), "policies", "at least one usable policy", "none");
  env_config.num_envs = 1;
  env_config.early_termination = false;
  env_config.episode_length = 1 << 30;
  env_config.random_heading = false;
  env_config.spawn_radius = 0;
  env_config.threads = 1;
  env_config.seed = options.seed;
  m.task = std::make_shared<StoryTask>(layout, obs_dim - humanoid::kSelfObsDim);
  m.env = std::make_unique<sim::BatchedEnv>(m.context.humanoid, env_config, m.task);
  m.action.assign(humanoid::kNumDofs, 0.0f);
}

StoryRunner::~StoryRunner() = default;

void StoryRunner::SetActionOverride(ActionOverride fn) { impl_->override_fn = std::move(fn); }

const humanoid::StaticGeometry& StoryRunner::geometry() const { return impl_->geometry; }
std::shared_ptr<const humanoid::Humanoid> StoryRunner::humanoid() const {
  return impl_->context.humanoid;
}

void StoryRunner::CheckPolicies(const std::vector<Instruction>& instructions) const {
  const auto& m = *impl_;
  std::set<std::string> needed;
  for (const SkillTraits& t : SkillVocabulary())
    if (t.required) needed.insert(t.name);
  for (const auto& in : instructions)
    if (in.placed) needed.insert(in.skill);
  for (const auto& s : needed) {
    if (m.skills.count(s)) continue;
    const SkillTraits* traits = FindSkillTraits(s);  // a plan may name an unknown skill
    if (m.options.missing_policy_fails && !(traits && traits->required)) {
      spdlog::warn("no usable policy for '{}' in {}: its keyframes will be recorded as failed", s,
                   m.policy_set.source.string());
      continue;
    }
    if (m.skill_errors.count(s))
      ThrowInputError(m.policy_set.File(s).string(), "policies." + s,
                      "a skill that can run in this scene", m.skill_errors.at(s));
    m.policy_set.File(s);  // throws: no policy for this skill
  }
}

Eigen::Vector3d StoryRunner::DefaultStart(const std::vector<Instruction>& instructions) const {
  const auto& m = *impl_;
  // Start a few metres from the first object, on free floor with a path to it, so the story
  // opens with a real walk. Seed 0 tries the directions from +x; other seeds turn the first
  // direction tried, so repeated runs of one script start from different sides.
  const double phase = m.options.seed == 0 ? 0.0 : Rng(m.options.seed).Uniform(0.0, 2 * M_PI);
  for (const auto& in : instructions) {
    if (in.target.object < 0 && !in.target.has_point) continue;
    Eigen::Vector2d goal = in.target.point.head<2>();
    if (in.target.object >= 0) {
      const auto stands = scene::StandPoints(*m.scene, *m.context.ray_caster, in.target.object);
      if (stands.empty()) continue;
      goal = stands.front().head<2>();
    }
    for (double r : {3.0, 2.5, 3.5, 2.0, 4.0})
      for (int k = 0; k < 12; ++k) {
        const double a = phase + k * M_PI / 6;
        const Eigen::Vector2d p = goal + r * Eigen::Vector2d(std::cos(a), std::sin(a));
        if (!m.free_space->Free(p)) continue;
        // A short detour at most: a start behind a wall would open the story with a long walk.
        const auto path = m.free_space->Waypoints(p, goal);
        if (!path.empty() && scene::PathLength(p, path) < 1.5 * r) return {p.x(), p.y(), 0};
      }
    if (m.free_space->Free(goal)) return {goal.x(), goal.y(), 0};
  }
  const auto c = m.scene->Bounds().center();
  if (auto f = m.free_space->NearestFree(c.head<2>(), 20.0)) return {f->x(), f->y(), 0};
  return {0, 0, 0};
}

StoryResult StoryRunner::Run(const std::vector<Instruction>& instructions,
                             const Eigen::Vector3d& start, double start_heading,
                             io::MotionRecordBuilder* recorder) {
  return RunStoriesBatched({StoryJob{this, &instructions, start, start_heading, recorder}}, 1)
      .front();
}

std::vector<StoryResult> RunStoriesBatched(const std::vector<StoryJob>& jobs, int threads,
                                           std::vector<std::exception_ptr>* errors) {
  const int n = static_cast<int>(jobs.size());
  std::vector<StoryRunner::Impl*> m(n);
  for (int i = 0; i < n; ++i) {
    SIMS_CHECK_MSG(jobs[i].runner && jobs[i].instructions,
                   "a story job needs a runner and instructions");
    m[i] = jobs[i].runner->impl_.get();
    for (int j = 0; j < i; ++j) SIMS_CHECK_MSG(m[j] != m[i], "each story job needs its own runner");
  }
  std::vector<std::exception_ptr> failed(n);
  for (int i = 0; i < n; ++i) {
    try {
      jobs[i].runner->CheckPolicies(*jobs[i].instructions);
      m[i]->run.log_prefix = n > 1 ? fmt::format("story {}: ", i) : "";
      m[i]->Begin(*jobs[i].instructions, jobs[i].start, jobs[i].start_heading, jobs[i].recorder,
                  /*report_progress=*/n == 1);
    } catch (...) {
      failed[i] = std::current_exception();
    }
  }
  const int num_threads = threads > 0 ? threads : ThreadCount();
  std::unique_ptr<ProgressReporter> progress;
  if (n > 1) progress = std::make_unique<ProgressReporter>("stories", n, "stories", 5.0);
  std::vector<int> live;
  std::vector<float> obs_rows, act_rows;
  for (;;) {
    live.clear();
    for (int i = 0; i < n; ++i)
      if (!failed[i] && !m[i]->Done()) live.push_back(i);
    if (progress) progress->Update(n - static_cast<int64_t>(live.size()));
    if (live.empty()) break;
    // Actions: one policy call per policy file over every character whose current skill uses
    // it (rows in job order), on this thread: libtorch never runs inside the OpenMP loop below.
    {
      const SingleThreadedRegions single_threaded;
      std::map<std::string, std::vector<int>> groups;
      for (int i : live) {
        if (m[i]->override_fn)
          m[i]->ActAlone();
        else
          groups[m[i]->policy_set.policies.at(m[i]->PendingSkill()).string()].push_back(i);
      }
      for (const auto& [file, rows] : groups) {
        const int k = static_cast<int>(rows.size());
        if (k == 1) {
          m[rows[0]]->ActAlone();
          continue;
        }
        // The runners loaded the same file, so the first one's copy serves them all.
        const learning::Policy& policy =
            *m[rows[0]]->policies.at(m[rows[0]]->PendingSkill()).policy;
        const int obs_dim = policy.obs_dim(), act_dim = policy.action_dim();
        SIMS_CHECK(act_dim == humanoid::kNumDofs);
        obs_rows.resize(static_cast<size_t>(k) * obs_dim);
        act_rows.resize(static_cast<size_t>(k) * act_dim);
        for (int r = 0; r < k; ++r) {
          SIMS_CHECK(m[rows[r]]->env->obs_dim() >= obs_dim);
          std::memcpy(obs_rows.data() + static_cast<size_t>(r) * obs_dim,
                      m[rows[r]]->PolicyObservation(), sizeof(float) * obs_dim);
        }
        // Exactly what each row gets alone (a BLAS rounds a block of rows unlike a lone row).
        policy.ActRowExact(obs_rows.data(), k, act_rows.data());
        for (int r = 0; r < k; ++r)
          std::copy_n(act_rows.data() + static_cast<size_t>(r) * act_dim, act_dim,
                      m[rows[r]]->action.data());
      }
    }
    // Physics and FSM: each runner touches only its own model, data, skills and recorder, so
    // they step in parallel with the same results at any thread count.
    const int num_live = static_cast<int>(live.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(num_threads) if (num_live > 1)
    for (int j = 0; j < num_live; ++j) {
      const int i = live[j];
      try {
        m[i]->Advance();
      } catch (...) {
        failed[i] = std::current_exception();
      }
    }
  }
  std::vector<StoryResult> results(n);
  for (int i = 0; i < n; ++i) {
    m[i]->recorder = nullptr;
    m[i]->run.progress.reset();
    if (!failed[i]) results[i] = std::move(m[i]->run.result);
  }
  if (errors) {
    *errors = std::move(failed);
  } else {
    for (const auto& e : failed)
      if (e) std::rethrow_exception(e);
  }
  return results;
}

nlohmann::json StoryResultToJson(const StoryResult& r) {
  nlohmann::json ks = nlohmann::json::array();
  for (const auto& k : r.keyframes)
    ks.push_back({{"keyframe", k.keyframe},
                  {"skill", k.skill},
                  {"caption", k.caption},
                  {"emotion", k.emotion},
                  {"object", k.object},
                  {"start_time", k.start_time},
                  {"end_time", k.end_time},
                  {"success", k.success},
                  {"contact_error", k.contact_error},
                  {"falls", k.falls},
                  {"retries", k.retries},
                  {"note", k.note}});
  return {{"keyframes", ks},
          {"success_rate", r.success_rate},
          {"success_steps", r.success_steps},
          {"mean_contact_error", r.mean_contact_error},
          {"falls", r.falls},
          {"duration_s", r.duration_s}};
}

}  // namespace sims::fsm
