#include "sims/sim/env.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <omp.h>

#include "sims/core/error.h"
#include "sims/core/parallel.h"

namespace sims::sim {

uint32_t TaskHook::contact_body_mask() const { return FeetContactMask(); }

std::vector<ObsSegment> TaskHook::obs_segments() const {
  ObsSegment s;
  s.name = "task";
  s.size = obs_dim();
  return {s};
}

void ObsAblation::Apply(const std::vector<ObsSegment>& segments, int n, int obs_dim,
                        float* obs) const {
  if (!any()) return;
  for (const ObsSegment& s : segments) {
    const bool withheld = (no_text && s.kind == ObsSegment::Kind::kStyle) ||
                          (no_heightmap && s.kind == ObsSegment::Kind::kHeightmap);
    if (!withheld) continue;
    SIMS_CHECK(humanoid::kSelfObsDim + s.offset + s.size <= obs_dim);
    for (int i = 0; i < n; ++i)
      std::fill_n(obs + static_cast<size_t>(i) * obs_dim + humanoid::kSelfObsDim + s.offset, s.size,
                  0.f);
  }
}

uint32_t FeetContactMask() { return (1u << humanoid::kRightFoot) | (1u << humanoid::kLeftFoot); }

namespace {
std::string SmoothingRange() {
  return fmt::format("a smoothing factor in [0, {}]", kMaxActionSmoothing);
}
}  // namespace

void EnvConfig::Validate() const {
  Require(num_envs > 0, "num_envs", "a positive integer");
  Require(substeps > 0, "substeps", "a positive integer");
  Require(episode_length > 1, "episode_length", "an integer > 1");
  Require(termination_height >= 0, "termination_height", "a non-negative height (m)");
  Require(spawn_radius >= 0, "spawn_radius", "a non-negative radius (m)");
  Require(max_velocity > 0, "max_velocity", "a positive number");
  Require(amp_history >= 1, "amp_history", "at least 1 step");
  Require(threads >= 0, "threads", "0 (all hardware threads) or a positive count");
  Require(recovery_episode_prob >= 0 && recovery_episode_prob <= 1, "recovery_episode_prob",
          "a probability in [0, 1]");
  Require(recovery_steps >= 1, "recovery_steps", "at least 1 step");
  Require(action_smoothing >= 0 && action_smoothing <= kMaxActionSmoothing, "action_smoothing",
          SmoothingRange());
  Require(action_rate_weight >= 0 && action_rate_weight <= 1, "action_rate_weight",
          "a share in [0, 1]");
  Require(action_rate_scale > 0, "action_rate_scale", "a positive scale (1/rad²)");
}

void CheckActionSmoothing(double alpha, std::string_view source, std::string_view field) {
  if (!(alpha >= 0 && alpha <= kMaxActionSmoothing))
    ThrowInputError(source, field, SmoothingRange(), fmt::format("{}", alpha));
}

namespace {
constexpr EndReason kNone = EndReason::kNone, kFall = EndReason::kFall,
                    kTimeout = EndReason::kTimeout, kTaskTerminate = EndReason::kTaskTerminate,
                    kTaskTruncate = EndReason::kTaskTruncate, kUnstable = EndReason::kUnstable;
constexpr int kWatchedWarnings[] = {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC, mjWARN_BADCTRL};
}  // namespace

// MuJoCo's kinematics normalises the free-joint quaternion in qpos in place and then derives
// xquat by normalising again; mju_normalize4 can alternate between two neighbouring values, so
// the state after mj_step1 depends on the quaternion *before* the pass, not the one left in
// qpos. Each env keeps that pre-pass quaternion so a snapshot can replay the pass exactly.
namespace {
void RememberRootQuaternion(const humanoid::Humanoid& h, const mjData* d, double* out4) {
  std::memcpy(out4, d->qpos + h.root_qpos_adr() + 3, 4 * sizeof(double));
}
}  // namespace

struct BatchedEnv::Slot {
  humanoid::MjDataPtr data;
  Rng rng;
  humanoid::HumanoidPose pose;
  humanoid::BodyStates bodies;
  std::vector<float> amp_hist;  // [amp_history, 125], slot 0 = current step
  int progress = 0;
  int grace = 0;
  bool reference = false;  // the episode began from a motion-clip state
  int warnings_seen = 0;
  double targets[humanoid::kNumDofs];
  double root_quat_before_pass[4];  // see RememberRootQuaternion
};

BatchedEnv::BatchedEnv(std::shared_ptr<const humanoid::Humanoid> humanoid, const EnvConfig& config,
                       std::shared_ptr<TaskHook> task)
    : humanoid_(std::move(humanoid)), config_(config), task_(std::move(task)) {
  SIMS_CHECK(humanoid_ != nullptr);
  ValidateConfig(config_, "EnvConfig");
  obs_dim_ = humanoid::kSelfObsDim + (task_ ? task_->obs_dim() : 0);
  threads_ = config_.threads > 0 ? config_.threads : ThreadCount();
  obs_options_.root_height = config_.root_height_obs;
  obs_options_.local_root_rot = config_.local_root_obs;
  contact_mask_ = task_ ? task_->contact_body_mask() : FeetContactMask();
  const int n = config_.num_envs;
  obs_.assign(static_cast<size_t>(n) * obs_dim_, 0.0f);
  terminal_obs_.assign(obs_.size(), 0.0f);
  rewards_.assign(n, 0.0f);
  amp_obs_.assign(static_cast<size_t>(n) * amp_obs_dim(), 0.0f);
  dones_.assign(n, 0);
  action_smoothing_.assign(n, config_.action_smoothing);
  terminated_.assign(n, 0);
  successes_.assign(n, 0);
  completions_.assign(n, 0);
  episode_reference_.assign(n, 0);
  end_reason_.assign(n, kNone);
  recovered_.assign(n, 0);
  slots_.resize(n);
  for (int i = 0; i < n; ++i) {
    slots_[i] = std::make_unique<Slot>();
    slots_[i]->data = humanoid::MakeData(humanoid_->model());
    slots_[i]->rng = Rng::ForEnv(config_.seed, i);
    slots_[i]->amp_hist.assign(static_cast<size_t>(amp_obs_dim()), 0.0f);
  }
  Reset();
}

BatchedEnv::~BatchedEnv() = default;

double BatchedEnv::control_dt() const {
  return humanoid_->model()->opt.timestep * config_.substeps;
}

mjData* BatchedEnv::data(int env_id) { return slots_.at(env_id)->data.get(); }
const humanoid::HumanoidPose& BatchedEnv::pose(int env_id) const { return slots_.at(env_id)->pose; }
const humanoid::BodyStates& BatchedEnv::bodies(int env_id) const {
  return slots_.at(env_id)->bodies;
}
int BatchedEnv::progress(int env_id) const { return slots_.at(env_id)->progress; }

EnvView BatchedEnv::View(int i) const {
  const Slot& s = *slots_[i];
  EnvView v;
  v.env_id = i;
  v.humanoid = humanoid_.get();
  v.data = s.data.get();
  v.pose = &s.pose;
  v.bodies = &s.bodies;
  v.progress = s.progress;
  v.control_dt = control_dt();
  return v;
}

void BatchedEnv::Reset() {
#pragma omp parallel for schedule(static) num_threads(threads_)
  for (int i = 0; i < config_.num_envs; ++i) ResetSlot(i);
}

void BatchedEnv::ResetEnv(int env_id) {
  SIMS_CHECK(env_id >= 0 && env_id < config_.num_envs);
  ResetSlot(env_id);
}

void BatchedEnv::set_action_smoothing(int env_id, double alpha) {
  SIMS_CHECK(env_id >= 0 && env_id < config_.num_envs);
  CheckActionSmoothing(alpha, "BatchedEnv", "action_smoothing");
  action_smoothing_[env_id] = alpha;
}

void BatchedEnv::ResetSlot(int i) {
  Slot& s = *slots_[i];
  const mjModel* m = humanoid_->model();
  mjData* d = s.data.get();
  InitialState init;
  // Default state: AMP default pose with random heading and position.
  if (config_.random_heading) {
    const double yaw = s.rng.Uniform(-M_PI, M_PI);
    init.pose.root_rot = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  }
  if (config_.spawn_radius > 0) {
    const double r = config_.spawn_radius * std::sqrt(s.rng.Uniform());
    const double a = s.rng.Uniform(0, 2 * M_PI);
    init.pose.root_pos.x() = r * std::cos(a);
    init.pose.root_pos.y() = r * std::sin(a);
  }
  if (task_) task_->SampleInitialState(i, s.rng, &init);

  mj_resetData(m, d);
  s.progress = 0;
  s.grace = init.termination_grace_steps;
  s.reference = init.reference;
  const int hist = config_.amp_history;
  // AMP history of a reference init: poses at t − k·dt evaluated with this env's data as scratch.
  const bool has_history = static_cast<int>(init.history.size()) >= hist - 1 && hist > 1;
  if (has_history) {
    for (int k = 1; k < hist; ++k) {
      humanoid::ForwardKinematics(*humanoid_, init.history[k - 1], d, &s.bodies);
      humanoid::ComputeAmpObservation(
          init.history[k - 1], s.bodies, obs_options_,
          s.amp_hist.data() + static_cast<size_t>(k) * humanoid::kAmpObsStepDim);
    }
  }
  humanoid::WritePose(*humanoid_, init.pose, d);
  // Hold the initial joint angles as PD targets until the first action arrives.
  for (int j = 0; j < humanoid::kNumDofs; ++j)
    d->ctrl[humanoid_->actuator_id(j)] = init.pose.dof_pos[j];
  RememberRootQuaternion(*humanoid_, d, s.root_quat_before_pass);
  mj_forward(m, d);
  s.warnings_seen = 0;
  for (int w : kWatchedWarnings) s.warnings_seen += d->warning[w].number;
  if (task_) {
    humanoid::ReadPose(*humanoid_, d, &s.pose);
    humanoid::ReadBodyStates(*humanoid_, d, &s.bodies);
    task_->OnReset(View(i), s.rng);
  }
  RefreshObservation(i, !has_history);
}

void BatchedEnv::RefreshTaskObservation(int env_id) {
  SIMS_CHECK(env_id >= 0 && env_id < config_.num_envs);
  RefreshObservation(env_id, false);
}

void BatchedEnv::RefreshObservation(int i, bool fill_history) {
  Slot& s = *slots_[i];
  const mjData* d = s.data.get();
  humanoid::ReadPose(*humanoid_, d, &s.pose);
  humanoid::ReadBodyStates(*humanoid_, d, &s.bodies);
  float* row = obs_.data() + static_cast<size_t>(i) * obs_dim_;
  humanoid::ComputeSelfObservation(s.bodies, obs_options_, row);
  if (task_) task_->Observe(View(i), row + humanoid::kSelfObsDim);
  humanoid::ComputeAmpObservation(s.pose, s.bodies, obs_options_, s.amp_hist.data());
  if (fill_history) {
    // Default/fall resets have no past: repeat the current observation (ASE).
    for (int k = 1; k < config_.amp_history; ++k)
      std::memcpy(s.amp_hist.data() + static_cast<size_t>(k) * humanoid::kAmpObsStepDim,
                  s.amp_hist.data(), sizeof(float) * humanoid::kAmpObsStepDim);
  }
}

bool BatchedEnv::Unstable(int i) const {
  const Slot& s = *slots_[i];
  const mjModel* m = humanoid_->model();
  const mjData* d = s.data.get();
  int warnings = 0;
  for (int w : kWatchedWarnings) warnings += d->warning[w].number;
  if (warnings != s.warnings_seen) return true;  // MuJoCo already caught a bad number
  for (int k = 0; k < m->nq; ++k)
    if (!std::isfinite(d->qpos[k])) return true;
  for (int k = 0; k < m->nv; ++k)
    if (!std::isfinite(d->qvel[k]) || std::abs(d->qvel[k]) > config_.max_velocity) return true;
  return false;
}

bool BatchedEnv::Fallen(int i) const {
  const Slot& s = *slots_[i];
  const mjData* d = s.data.get();
  // ASE: some non-contact body touches something outside the humanoid AND some non-contact
  // body is below the termination height.
  bool touching = false;
  for (int c = 0; c < d->ncon && !touching; ++c) {
    const int b1 = humanoid_->geom_body(d->contact[c].geom1);
    const int b2 = humanoid_->geom_body(d->contact[c].geom2);
    if ((b1 >= 0) == (b2 >= 0)) continue;  // self-contact or scene-scene
    const int b = b1 >= 0 ? b1 : b2;
    if (!(contact_mask_ & (1u << b))) touching = true;
  }
  if (!touching) return false;
  for (int b = 0; b < humanoid::kNumBodies; ++b) {
    if (contact_mask_ & (1u << b)) continue;
    const double h = b == humanoid::kHead
                         ? std::max(config_.head_termination_height, config_.termination_height)
                         : config_.termination_height;
    if (s.bodies.pos[b].z() < h) return true;
  }
  return false;
}

void BatchedEnv::StepEnv(int i, const float* action) {
  Slot& s = *slots_[i];
  const mjModel* m = humanoid_->model();
  mjData* d = s.data.get();
  humanoid_->ActionToTargets(action, s.targets);
  const double alpha = action_smoothing_[i];
  const double w_rate = config_.action_rate_weight;
  double rate_sq = 0;
  for (int j = 0; j < humanoid::kNumDofs; ++j) {
    double& held = d->ctrl[humanoid_->actuator_id(j)];
    if (w_rate > 0) rate_sq += (s.targets[j] - held) * (s.targets[j] - held);
    held = alpha > 0 ? alpha * held + (1 - alpha) * s.targets[j] : s.targets[j];
  }
  // The position/velocity stage of the state we start from is already computed (by mj_forward
  // after a reset or mj_step1 at the end of the last control step), so finish that step with
  // mj_step2, then run full steps, and end with mj_step1 so observations see the final state.
  mj_step2(m, d);
  for (int k = 1; k < config_.substeps; ++k) mj_step(m, d);
  RememberRootQuaternion(*humanoid_, d, s.root_quat_before_pass);
  mj_step1(m, d);
  s.progress += 1;

  EndReason reason = kNone;
  TaskStepResult tr;
  recovered_[i] = 0;
  if (Unstable(i)) {
    reason = kUnstable;
  } else {
    humanoid::ReadPose(*humanoid_, d, &s.pose);
    humanoid::ReadBodyStates(*humanoid_, d, &s.bodies);
    if (task_) tr = task_->Step(View(i));
    if (s.grace > 0) --s.grace;
    bool fell = config_.early_termination && s.grace == 0 && s.progress > 1 && Fallen(i);
    // A recovery episode goes on instead; the draw only happens when they are on, so every
    // other random stream stays as it was.
    if (fell && config_.recovery_episode_prob > 0 &&
        s.rng.Bernoulli(config_.recovery_episode_prob)) {
      s.grace = config_.recovery_steps;
      recovered_[i] = 1;
      fell = false;
    }
    if (fell) {
      reason = kFall;
    } else if (tr.terminate) {
      reason = kTaskTerminate;
    } else if (tr.truncate) {
      reason = kTaskTruncate;
    } else if (s.progress >= config_.episode_length - 1) {
      reason = kTimeout;
    }
  }

  if (w_rate > 0)
    tr.reward = static_cast<float>(
        (1 - w_rate) * tr.reward +
        w_rate * std::exp(-config_.action_rate_scale * rate_sq / humanoid::kNumDofs));
  rewards_[i] = reason == kUnstable ? 0.0f : tr.reward;
  successes_[i] = tr.success ? 1 : 0;
  completions_[i] = reason != kUnstable && tr.completed ? 1 : 0;
  episode_reference_[i] = s.reference ? 1 : 0;
  float* row = obs_.data() + static_cast<size_t>(i) * obs_dim_;
  float* amp_row = amp_obs_.data() + static_cast<size_t>(i) * amp_obs_dim();
  if (reason != kUnstable) {
    // Shift the AMP history one step back and compute slot 0 (the observation of now).
    std::memmove(s.amp_hist.data() + humanoid::kAmpObsStepDim, s.amp_hist.data(),
                 sizeof(float) * humanoid::kAmpObsStepDim * (config_.amp_history - 1));
    humanoid::ComputeAmpObservation(s.pose, s.bodies, obs_options_, s.amp_hist.data());
    humanoid::ComputeSelfObservation(s.bodies, obs_options_, row);
    if (task_) task_->Observe(View(i), row + humanoid::kSelfObsDim);
  }
  // A blown-up transition keeps the previous (finite) AMP history so no NaN reaches a learner.
  std::memcpy(amp_row, s.amp_hist.data(), sizeof(float) * amp_obs_dim());

  end_reason_[i] = reason;
  dones_[i] = reason != kNone;
  terminated_[i] = reason == kFall || reason == kTaskTerminate || reason == kUnstable;
  if (reason != kNone) {
    std::memcpy(terminal_obs_.data() + static_cast<size_t>(i) * obs_dim_, row,
                sizeof(float) * obs_dim_);
    ResetSlot(i);
  }
}

void BatchedEnv::Step(const float* actions) {
  const int n = config_.num_envs;
#pragma omp parallel for schedule(static) num_threads(threads_)
  for (int i = 0; i < n; ++i) StepEnv(i, actions + static_cast<size_t>(i) * humanoid::kNumDofs);
  stats_.steps += n;
  for (int i = 0; i < n; ++i) {
    stats_.recoveries += recovered_[i];
    switch (end_reason_[i]) {
      case kFall:
        ++stats_.falls;
        break;
      case kTimeout:
        ++stats_.timeouts;
        break;
      case kTaskTerminate:
      case kTaskTruncate:
        ++stats_.task_ends;
        break;
      case kUnstable:
        ++stats_.instabilities;
        break;
      default:
        continue;
    }
    ++stats_.episodes;
  }
}

namespace {
class ByteWriter {
 public:
  template <typename T>
  void Put(const T* p, size_t n) {
    const char* c = reinterpret_cast<const char*>(p);
    out_.append(c, c + sizeof(T) * n);
  }
  template <typename T>
  void Put(const T& v) {
    Put(&v, 1);
  }
  std::string& str() { return out_; }

 private:
  std::string out_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& in) : in_(in) {}
  template <typename T>
  void Get(T* p, size_t n) {
    const size_t bytes = sizeof(T) * n;
    if (pos_ + bytes > in_.size())
      ThrowInputError("environment state", "", "a snapshot of this environment", "truncated data");
    // Empty arrays (no actuator activations, no task state) may have a null data pointer,
    // which memcpy must not get even for 0 bytes (UBSan: nonnull argument).
    if (bytes == 0) return;
    std::memcpy(p, in_.data() + pos_, bytes);
    pos_ += bytes;
  }
  template <typename T>
  T Get() {
    T v;
    Get(&v, 1);
    return v;
  }
  bool done() const { return pos_ == in_.size(); }
  /// Bytes not read yet.
  size_t left() const { return in_.size() - pos_; }

 private:
  const std::string& in_;
  size_t pos_ = 0;
};
constexpr uint32_t kStateMagic = 0x53494D33;  // "SIM3": the stats are count-prefixed
// "SIM2" snapshots wrote EnvStats as one raw struct: 6 counters, or 7 for those written after
// `recoveries` was added and before SIM3 (2026-12-03); both still load.
constexpr uint32_t kStateMagicSim2 = 0x53494D32;
constexpr int kNumStats = 7;
int64_t* StatsField(EnvStats* st, int k) {
  int64_t* f[kNumStats] = {&st->steps,     &st->episodes,      &st->falls,     &st->timeouts,
                           &st->task_ends, &st->instabilities, &st->recoveries};
  return f[k];
}
}  // namespace

std::string BatchedEnv::SaveState() const {
  const mjModel* m = humanoid_->model();
  ByteWriter w;
  w.Put(kStateMagic);
  w.Put(config_.num_envs);
  w.Put(m->nq);
  w.Put(m->nv);
  w.Put(m->nu);
  w.Put(config_.amp_history);
  w.Put(kNumStats);
  EnvStats stats = stats_;
  for (int k = 0; k < kNumStats; ++k) w.Put(*StatsField(&stats, k));
  for (int i = 0; i < config_.num_envs; ++i) {
    const Slot& s = *slots_[i];
    const mjData* d = s.data.get();
    const auto rng = s.rng.state();
    w.Put(rng.data(), rng.size());
    w.Put(s.progress);
    w.Put(s.grace);
    w.Put(static_cast<uint8_t>(s.reference));
    w.Put(s.amp_hist.data(), s.amp_hist.size());
    w.Put(d->time);
    w.Put(d->qpos, m->nq);
    w.Put(s.root_quat_before_pass, 4);
    w.Put(d->qvel, m->nv);
    w.Put(d->act, m->na);
    w.Put(d->ctrl, m->nu);
    w.Put(d->qacc_warmstart, m->nv);
    const std::vector<double> task_state = task_ ? task_->SaveEnvState(i) : std::vector<double>{};
    w.Put(task_state.size());
    w.Put(task_state.data(), task_state.size());
  }
  return std::move(w.str());
}

void BatchedEnv::LoadState(const std::string& state) {
  // A snapshot is read and applied env by env; one rejected part way through must not leave
  // the environment half-restored, so the current state is put back.
  const std::string before = SaveState();
  try {
    try {
      ApplyState(state, 6);
    } catch (const Error&) {
      // A SIM2 snapshot with 7 counters (see kStateMagicSim2); SIM3 ignores the hint.
      ApplyState(state, 7);
    }
  } catch (const Error&) {
    ApplyState(before, 0);
    throw;
  }
}

void BatchedEnv::ApplyState(const std::string& state, int sim2_stats) {
  const mjModel* m = humanoid_->model();
  ByteReader r(state);
  const auto expect = [&](auto value, const char* field) {
    if (r.Get<decltype(value)>() != value)
      ThrowInputError("environment state", field, "the same value as this environment",
                      "a different one (config or model changed since the snapshot)");
  };
  const auto magic = r.Get<uint32_t>();
  if (magic != kStateMagic && magic != kStateMagicSim2)
    ThrowInputError("environment state", "magic", "SIM3 (or SIM2)", "another value");
  expect(config_.num_envs, "num_envs");
  expect(m->nq, "nq");
  expect(m->nv, "nv");
  expect(m->nu, "nu");
  expect(config_.amp_history, "amp_history");
  const int num_stats = magic == kStateMagic ? r.Get<int>() : sim2_stats;
  if (num_stats < 6 || num_stats > kNumStats)
    ThrowInputError("environment state", "stats", "6 to " + std::to_string(kNumStats) + " counters",
                    std::to_string(num_stats));
  EnvStats stats;
  for (int k = 0; k < num_stats; ++k) *StatsField(&stats, k) = r.Get<int64_t>();
  stats_ = stats;
  for (int i = 0; i < config_.num_envs; ++i) {
    Slot& s = *slots_[i];
    mjData* d = s.data.get();
    std::array<uint64_t, 4> rng;
    r.Get(rng.data(), rng.size());
    s.rng.set_state(rng);
    s.progress = r.Get<int>();
    // An episode never runs past its length (fuzzer finding: INT_MAX overflowed at the step).
    if (s.progress < 0 || s.progress > config_.episode_length)
      ThrowInputError(
          "environment state", "progress",
          "control steps in [0, episode_length = " + std::to_string(config_.episode_length) + "]",
          std::to_string(s.progress));
    s.grace = r.Get<int>();
    if (s.grace < 0)
      ThrowInputError("environment state", "grace", "a step count ≥ 0", std::to_string(s.grace));
    s.reference = r.Get<uint8_t>() != 0;
    r.Get(s.amp_hist.data(), s.amp_hist.size());
    mj_resetData(m, d);
    d->time = r.Get<double>();
    r.Get(d->qpos, m->nq);
    r.Get(s.root_quat_before_pass, 4);
    std::memcpy(d->qpos + humanoid_->root_qpos_adr() + 3, s.root_quat_before_pass,
                4 * sizeof(double));
    r.Get(d->qvel, m->nv);
    r.Get(d->act, m->na);
    r.Get(d->ctrl, m->nu);
    r.Get(d->qacc_warmstart, m->nv);
    const size_t task_values = r.Get<size_t>();
    if (task_values > r.left() / sizeof(double))
      ThrowInputError("environment state", "task_state", "a snapshot of this environment",
                      "a count of " + std::to_string(task_values) + " values past its end");
    std::vector<double> task_state(task_values);
    r.Get(task_state.data(), task_state.size());
    if (task_) task_->LoadEnvState(i, task_state);
    // The env always rests after mj_step1 (or mj_forward); replaying that pass from the
    // pre-pass quaternion reproduces the saved data exactly.
    mj_step1(m, d);
    s.warnings_seen = 0;
    for (int wi : kWatchedWarnings) s.warnings_seen += d->warning[wi].number;
    humanoid::ReadPose(*humanoid_, d, &s.pose);
    humanoid::ReadBodyStates(*humanoid_, d, &s.bodies);
    float* row = obs_.data() + static_cast<size_t>(i) * obs_dim_;
    humanoid::ComputeSelfObservation(s.bodies, obs_options_, row);
    if (task_) task_->Observe(View(i), row + humanoid::kSelfObsDim);
  }
  if (!r.done())
    ThrowInputError("environment state", "", "a snapshot of this environment", "trailing data");
}

void BatchedEnv::SetState(int env_id, const humanoid::HumanoidPose& pose) {
  Slot& s = *slots_.at(env_id);
  humanoid::WritePose(*humanoid_, pose, s.data.get());
  RememberRootQuaternion(*humanoid_, s.data.get(), s.root_quat_before_pass);
  mj_forward(humanoid_->model(), s.data.get());
  RefreshObservation(env_id, false);
}

}  // namespace sims::sim
