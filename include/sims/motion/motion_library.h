// The motion library: clips from a manifest with sampling weights and labels, optional
// left–right mirroring (doubles the data), filters by skill/emotion, and the two samplers
// the learner needs: reference-state initialisation (a pose plus its AMP history) and AMP
// demo windows (10 × 125 values computed exactly like the environment's: the clip pose goes
// through humanoid::ForwardKinematics and humanoid::ComputeAmpObservation).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/core/rng.h"
#include "sims/humanoid/features.h"
#include "sims/motion/motion_clip.h"

namespace sims::motion {

/// One manifest entry; empty labels keep the clip's own.
struct ManifestEntry {
  std::string file;                   ///< Clip JSON, relative to the manifest's folder.
  double weight = 1.0;                ///< Sampling weight (> 0).
  std::vector<std::string> captions;  ///< Overrides the clip's captions when non-empty.
  std::string skill;                  ///< Overrides the clip's skill when non-empty.
  std::string emotion;                ///< Overrides the clip's emotion when non-empty.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(file));
    a->Visit(SIMS_NVP(weight));
    a->Visit(SIMS_NVP(captions));
    a->Visit(SIMS_NVP(skill));
    a->Visit(SIMS_NVP(emotion));
  }
  /// Checks the file name, weight and labels.
  void Validate() const;
};

/// A motion manifest (JSON: {"clips": [...]}).
struct MotionManifest {
  std::string description;           ///< Free text.
  std::vector<ManifestEntry> clips;  ///< Clips.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(description));
    a->Visit(SIMS_NVP(clips));
  }
};

/// Loads and validates a manifest.
MotionManifest LoadManifest(const std::filesystem::path& path);
/// Saves a manifest atomically.
void SaveManifest(const std::filesystem::path& path, const MotionManifest& manifest);

/// Library settings.
struct MotionLibraryOptions {
  bool mirror = false;                ///< Add the left–right mirror of every clip.
  std::vector<std::string> skills;    ///< Keep only these skills (empty = all).
  std::vector<std::string> emotions;  ///< Keep only these emotions (empty = all).
  double control_dt = 1.0 / 30.0;     ///< Spacing of AMP history steps (s).
  int amp_steps = 10;                 ///< AMP observation steps per window.
  bool root_height_obs = true;        ///< As EnvConfig::root_height_obs.
  bool local_root_obs = true;         ///< As EnvConfig::local_root_obs.

  /// Lists the fields for JSON binding.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(mirror));
    a->Visit(SIMS_NVP(skills));
    a->Visit(SIMS_NVP(emotions));
    a->Visit(SIMS_NVP(control_dt));
    a->Visit(SIMS_NVP(amp_steps));
    a->Visit(SIMS_NVP(root_height_obs));
    a->Visit(SIMS_NVP(local_root_obs));
  }
  /// Checks ranges and labels.
  void Validate() const;
};

/// A sampled reference state.
struct ReferenceState {
  int clip = 0;                 ///< Clip index.
  double time = 0;              ///< Time in the clip (s).
  humanoid::HumanoidPose pose;  ///< State at `time`.
  std::vector<humanoid::HumanoidPose>
      history;  ///< States at time − k·dt, k = 1..amp_steps−1 (clamped at 0).
};

/// Weighted clips with samplers. Const methods are thread-safe.
class MotionLibrary {
 public:
  /// Builds from clips and weights (same length, weights > 0) after filtering and mirroring.
  MotionLibrary(std::shared_ptr<const humanoid::Humanoid> humanoid, std::vector<MotionClip> clips,
                std::vector<double> weights, const MotionLibraryOptions& options = {});
  /// Loads the clips of a manifest (labels from the manifest override the clips').
  static MotionLibrary Load(const std::filesystem::path& manifest,
                            std::shared_ptr<const humanoid::Humanoid> humanoid,
                            const MotionLibraryOptions& options = {});

  /// Number of clips (mirrors included).
  int num_clips() const { return static_cast<int>(clips_.size()); }
  /// Clip i.
  const MotionClip& clip(int i) const { return clips_[i]; }
  /// Sampling weight of clip i.
  double weight(int i) const { return weights_[i]; }
  /// Total duration of all clips (s).
  double total_duration() const;
  /// Settings.
  const MotionLibraryOptions& options() const { return options_; }
  /// The humanoid used for FK.
  const humanoid::Humanoid& humanoid() const { return *humanoid_; }
  /// Observation options matching the environment's.
  humanoid::ObsOptions obs_options() const;

  /// A clip index drawn by weight; with `balance_emotions`, an emotion first (each one present
  /// equally likely: the emotional clips are few), then one of its clips by weight.
  int SampleClip(Rng& rng, bool balance_emotions = false) const;
  /// A time in clip i, uniform in [0, max_fraction · duration].
  double SampleTime(int clip, Rng& rng, double max_fraction = 1.0) const;
  /// Reference state at a given clip time (history clamped at t = 0, as CALM).
  ReferenceState StateAt(int clip, double time) const;
  /// Clip by weight, time uniform in [0, max_fraction · duration], and its history.
  ReferenceState SampleReferenceState(Rng& rng, double max_fraction = 1.0) const;

  /// The 125-d AMP observation of clip `clip` at time t, via `scratch` (an mjData of the
  /// library's model).
  void AmpObservation(int clip, double t, mjData* scratch, float* out) const;
  /// One AMP window [t, t−dt, …] (`steps` × 125 values; 0 = amp_steps), times clamped at 0.
  void AmpWindow(int clip, double t, mjData* scratch, float* out, int steps = 0) const;
  /// `count` demo windows: clip by weight (SampleClip with `balance_emotions`),
  /// t ~ U[(steps−1)·dt, duration] (U[0, duration] for shorter clips). Writes
  /// [count, steps·125] to `out` and the clip indices to `clips` (may be null). `steps` is the
  /// window length (0 = amp_steps). Deterministic for a seed at any thread count.
  void SampleAmpDemos(Rng& rng, int count, float* out, int* clips = nullptr, int threads = 1,
                      int steps = 0, bool balance_emotions = false) const;
  /// Per-frame AMP observations of clip i resampled at `fps` ([frames, 125]).
  std::vector<float> ClipAmpFeatures(int clip, double fps = 30.0) const;

  /// Indices of clips with this skill and/or emotion (empty string = any).
  std::vector<int> Find(const std::string& skill, const std::string& emotion = "") const;

 private:
  std::shared_ptr<const humanoid::Humanoid> humanoid_;
  MotionLibraryOptions options_;
  std::vector<MotionClip> clips_;
  std::vector<double> weights_;
  std::vector<double> cumulative_;
  // Per emotion (sorted by name): its clips and their cumulative weights.
  std::vector<std::vector<int>> emotion_clips_;
  std::vector<std::vector<double>> emotion_cumulative_;
};

}  // namespace sims::motion
