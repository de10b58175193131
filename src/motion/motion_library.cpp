#include "sims/motion/motion_library.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "sims/core/error.h"
#include "sims/humanoid/model_builder.h"
#include "sims/motion/mirror.h"

namespace sims::motion {

namespace fs = std::filesystem;

namespace {

bool Contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

void ManifestEntry::Validate() const {
  Require(!file.empty(), "file", "a clip file name");
  Require(weight > 0 && std::isfinite(weight), "weight", "a positive number");
  Require(captions.size() <= 5, "captions", "at most 5 captions");
  Require(skill.empty() || IsSkillLabel(skill), "skill", "a known skill label");
  Require(emotion.empty() || IsEmotionLabel(emotion), "emotion", "one of the 9 emotion labels");
}

void MotionLibraryOptions::Validate() const {
  Require(control_dt > 0, "control_dt", "a positive time step");
  Require(amp_steps >= 1, "amp_steps", "at least 1");
  for (const auto& s : skills) Require(IsSkillLabel(s), "skills", "known skill labels");
  for (const auto& e : emotions) Require(IsEmotionLabel(e), "emotions", "the 9 emotion labels");
}

MotionManifest LoadManifest(const fs::path& path) { return LoadConfig<MotionManifest>(path); }

void SaveManifest(const fs::path& path, const MotionManifest& manifest) {
  SaveConfig(path, manifest);
}

MotionLibrary::MotionLibrary(std::shared_ptr<const humanoid::Humanoid> humanoid,
                             std::vector<MotionClip> clips, std::vector<double> weights,
                             const MotionLibraryOptions& options)
    : humanoid_(humanoid ? std::move(humanoid) : HumanoidSkeleton::DefaultHumanoid()),
      options_(options) {
  ValidateConfig(options_, "motion library options");
  SIMS_CHECK(clips.size() == weights.size());
  for (std::size_t i = 0; i < clips.size(); ++i) {
    const MotionMeta& m = clips[i].meta();
    if (!options_.skills.empty() && !Contains(options_.skills, m.skill)) continue;
    if (!options_.emotions.empty() && !Contains(options_.emotions, m.emotion)) continue;
    SIMS_CHECK(weights[i] > 0);
    // Each original is followed by its mirror.
    clips_.push_back(std::move(clips[i]));
    weights_.push_back(weights[i]);
    if (options_.mirror) {
      clips_.push_back(MirrorClip(clips_.back()));
      weights_.push_back(weights[i]);
    }
  }
  double sum = 0;
  for (double w : weights_) cumulative_.push_back(sum += w);
  std::map<std::string, std::vector<int>> by_emotion;
  for (int i = 0; i < num_clips(); ++i) by_emotion[clips_[i].meta().emotion].push_back(i);
  for (auto& [emotion, ids] : by_emotion) {
    double total = 0;
    std::vector<double> cumulative;
    for (int i : ids) cumulative.push_back(total += weights_[i]);
    emotion_clips_.push_back(std::move(ids));
    emotion_cumulative_.push_back(std::move(cumulative));
  }
}

MotionLibrary MotionLibrary::Load(const fs::path& manifest_path,
                                  std::shared_ptr<const humanoid::Humanoid> humanoid,
                                  const MotionLibraryOptions& options) {
  const MotionManifest manifest = LoadManifest(manifest_path);
  if (manifest.clips.empty())
    ThrowInputError(manifest_path.string(), "clips", "at least one clip", "an empty list");
  std::vector<MotionClip> clips;
  std::vector<double> weights;
  for (std::size_t i = 0; i < manifest.clips.size(); ++i) {
    const ManifestEntry& e = manifest.clips[i];
    MotionClip clip = LoadClip(manifest_path.parent_path() / e.file);
    MotionMeta& m = clip.mutable_meta();
    if (!e.captions.empty()) m.captions = e.captions;
    if (!e.skill.empty()) m.skill = e.skill;
    if (!e.emotion.empty()) m.emotion = e.emotion;
    clips.push_back(std::move(clip));
    weights.push_back(e.weight);
  }
  MotionLibrary lib(std::move(humanoid), std::move(clips), std::move(weights), options);
  if (lib.num_clips() == 0)
    ThrowInputError(manifest_path.string(), "clips",
                    "at least one clip matching the skill/emotion filter", "none");
  return lib;
}

double MotionLibrary::total_duration() const {
  double d = 0;
  for (const auto& c : clips_) d += c.duration();
  return d;
}

humanoid::ObsOptions MotionLibrary::obs_options() const {
  humanoid::ObsOptions o;
  o.root_height = options_.root_height_obs;
  o.local_root_rot = options_.local_root_obs;
  return o;
}

namespace {
// Index of a draw u ∈ [0, total) in a cumulative weight list.
int DrawIndex(const std::vector<double>& cumulative, double u) {
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
  return std::min(static_cast<int>(it - cumulative.begin()),
                  static_cast<int>(cumulative.size()) - 1);
}
}  // namespace

int MotionLibrary::SampleClip(Rng& rng, bool balance_emotions) const {
  SIMS_CHECK(!clips_.empty());
  if (!balance_emotions) return DrawIndex(cumulative_, rng.Uniform() * cumulative_.back());
  const auto e = static_cast<size_t>(rng.UniformInt(static_cast<int64_t>(emotion_clips_.size())));
  const std::vector<double>& c = emotion_cumulative_[e];
  return emotion_clips_[e][DrawIndex(c, rng.Uniform() * c.back())];
}

double MotionLibrary::SampleTime(int clip, Rng& rng, double max_fraction) const {
  return rng.Uniform() * std::clamp(max_fraction, 0.0, 1.0) * clips_[clip].duration();
}

ReferenceState MotionLibrary::StateAt(int clip, double time) const {
  ReferenceState s;
  s.clip = clip;
  s.time = time;
  const MotionClip& c = clips_[clip];
  s.pose = c.SamplePose(time);
  for (int k = 1; k < options_.amp_steps; ++k)
    s.history.push_back(c.SamplePose(std::max(time - k * options_.control_dt, 0.0)));
  return s;
}

ReferenceState MotionLibrary::SampleReferenceState(Rng& rng, double max_fraction) const {
  const int clip = SampleClip(rng);
  return StateAt(clip, SampleTime(clip, rng, max_fraction));
}

void MotionLibrary::AmpObservation(int clip, double t, mjData* scratch, float* out) const {
  const humanoid::HumanoidPose pose = clips_[clip].SamplePose(t);
  humanoid::BodyStates bodies;
  humanoid::ForwardKinematics(*humanoid_, pose, scratch, &bodies);
  humanoid::ComputeAmpObservation(pose, bodies, obs_options(), out);
}

void MotionLibrary::AmpWindow(int clip, double t, mjData* scratch, float* out, int steps) const {
  if (steps <= 0) steps = options_.amp_steps;
  for (int k = 0; k < steps; ++k)
    AmpObservation(clip, std::max(t - k * options_.control_dt, 0.0), scratch,
                   out + static_cast<std::size_t>(k) * humanoid::kAmpObsStepDim);
}

void MotionLibrary::SampleAmpDemos(Rng& rng, int count, float* out, int* clip_ids, int threads,
                                   int steps, bool balance_emotions) const {
  if (steps <= 0) steps = options_.amp_steps;
  // Draw every (clip, time) first so the result does not depend on the thread count.
  std::vector<int> ids(count);
  std::vector<double> times(count);
  const double span = (steps - 1) * options_.control_dt;
  for (int i = 0; i < count; ++i) {
    ids[i] = SampleClip(rng, balance_emotions);
    const double len = clips_[ids[i]].duration();
    times[i] = len > span ? rng.Uniform(span, len) : rng.Uniform() * len;
  }
  const std::size_t width = static_cast<std::size_t>(steps) * humanoid::kAmpObsStepDim;
  threads = std::max(1, threads);
#pragma omp parallel num_threads(threads)
  {
    humanoid::MjDataPtr scratch = humanoid::MakeData(humanoid_->model());
#pragma omp for schedule(static)
    for (int i = 0; i < count; ++i)
      AmpWindow(ids[i], times[i], scratch.get(), out + i * width, steps);
  }
  if (clip_ids) std::copy(ids.begin(), ids.end(), clip_ids);
}

std::vector<float> MotionLibrary::ClipAmpFeatures(int clip, double fps) const {
  SIMS_CHECK(fps > 0);
  const MotionClip& c = clips_[clip];
  const int n = static_cast<int>(std::floor(c.duration() * fps + 1e-6)) + 1;
  std::vector<float> out(static_cast<std::size_t>(n) * humanoid::kAmpObsStepDim);
  humanoid::MjDataPtr scratch = humanoid::MakeData(humanoid_->model());
  for (int i = 0; i < n; ++i)
    AmpObservation(clip, i / fps, scratch.get(),
                   out.data() + static_cast<std::size_t>(i) * humanoid::kAmpObsStepDim);
  return out;
}

std::vector<int> MotionLibrary::Find(const std::string& skill, const std::string& emotion) const {
  std::vector<int> out;
  for (int i = 0; i < num_clips(); ++i) {
    const MotionMeta& m = clips_[i].meta();
    if ((skill.empty() || m.skill == skill) && (emotion.empty() || m.emotion == emotion))
      out.push_back(i);
  }
  return out;
}

}  // namespace sims::motion
