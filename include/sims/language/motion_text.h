// Motion–text auto-encoder (SIMS eq. 3–5): a bidirectional transformer encodes a window of
// per-frame motion features (the 125-d AMP observation) into a 64-d unit vector z, a transformer
// decoder reconstructs the window from z, MLP_d maps a frozen text feature t to the same space and
// MLP_u maps it back:  L = MSE(x̂, x) + (1 − cos(z, MLP_d(t))) + ‖MLP_u(MLP_d(t)) − t‖.
//
// Windows: `seq_frames` frames at `sample_fps` (300 at 30 fps = 10 s). Clips are resampled by
// nearest frame (a 120 fps clip is read every 4th frame); a clip shorter than the window is read
// with frame indices spread evenly over its whole length ("skip sampling"), so every window sees
// the complete short clip. Frames are grouped into tokens of `frames_per_token` to keep the
// sequence short on CPUs.
//
// Dataset folder format (train_text_motion --data DIR): one JSON file per clip,
//   {"clip": "name", "fps": 30, "captions": ["...", ...], "features": [[f0 ... f124], ...]}
// (one row per frame; "clip" defaults to the file stem). Save/LoadCaptionedSequence read and
// write it.
//
// Output folder of TrainMotionText: config.json (resolved), checkpoint.pt (model + optimiser +
// step + RNG, atomic), train_log.csv, model.pt + model.json (final model), bank.json (caption → z
// and clip → z, see embedding_bank.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sims/core/config.h"
#include "sims/language/text_encoder.h"

namespace sims::language {

/// One captioned motion clip (the lead maps motion-library clips onto this).
struct CaptionedSequence {
  std::string clip_name;              ///< Unique clip name.
  double fps = 30.0;                  ///< Frame rate of `features`.
  Eigen::MatrixXf features;           ///< [T, feature_dim], one row per frame.
  std::vector<std::string> captions;  ///< Descriptions of the clip (may be empty).
};

/// Writes one clip in the dataset folder format (atomic).
void SaveCaptionedSequence(const std::filesystem::path& file, const CaptionedSequence& seq);
/// Reads one clip; errors name the file and the field.
CaptionedSequence LoadCaptionedSequence(const std::filesystem::path& file);
/// Reads every *.json in `dir` (sorted by name); checks that all share one feature size.
std::vector<CaptionedSequence> LoadCaptionedSequences(const std::filesystem::path& dir);

/// Network sizes and windowing (CPU-small defaults).
struct MotionTextModelConfig {
  int feature_dim = 125;                ///< Per-frame feature size (AMP observation).
  int seq_frames = 300;                 ///< Frames per window.
  double sample_fps = 30.0;             ///< Frame rate of the window.
  int frames_per_token = 10;            ///< Frames grouped into one transformer token.
  int d_model = 64;                     ///< Transformer width.
  int num_heads = 4;                    ///< Attention heads.
  int encoder_layers = 2;               ///< Motion encoder depth (bidirectional, no mask).
  int decoder_layers = 1;               ///< Motion decoder depth.
  int ff_dim = 128;                     ///< Feed-forward width.
  double dropout = 0.0;                 ///< Dropout in the transformer layers.
  int z_dim = 64;                       ///< Size of the unit embedding z.
  std::vector<int> mlp_hidden = {256};  ///< Hidden sizes of MLP_d and MLP_u.

  /// Binds fields to JSON.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(feature_dim));
    a->Visit(SIMS_NVP(seq_frames));
    a->Visit(SIMS_NVP(sample_fps));
    a->Visit(SIMS_NVP(frames_per_token));
    a->Visit(SIMS_NVP(d_model));
    a->Visit(SIMS_NVP(num_heads));
    a->Visit(SIMS_NVP(encoder_layers));
    a->Visit(SIMS_NVP(decoder_layers));
    a->Visit(SIMS_NVP(ff_dim));
    a->Visit(SIMS_NVP(dropout));
    a->Visit(SIMS_NVP(z_dim));
    a->Visit(SIMS_NVP(mlp_hidden));
  }
  /// Checks sizes (seq_frames divisible by frames_per_token, d_model by num_heads, ...).
  void Validate() const;
};

/// Frame indices of one window of a clip with `num_frames` frames at `fps`; `start_fraction` in
/// [0, 1] places the window inside clips longer than it (ignored for shorter clips).
std::vector<int> WindowFrameIndices(int num_frames, double fps, const MotionTextModelConfig& config,
                                    double start_fraction);
/// The window's features, [seq_frames, feature_dim].
Eigen::MatrixXf SampleWindow(const CaptionedSequence& seq, const MotionTextModelConfig& config,
                             double start_fraction);

/// The trained networks (encoder, decoder, MLP_d, MLP_u) plus feature normalisation.
/// Inference methods are const and thread-safe; copies share the weights.
class MotionTextModel {
 public:
  /// A freshly initialised model (seeded) for text features of size `text_dim`.
  MotionTextModel(const MotionTextModelConfig& config, int text_dim, uint64_t seed);
  ~MotionTextModel();
  MotionTextModel(const MotionTextModel&);
  MotionTextModel& operator=(const MotionTextModel&);

  /// Loads model.pt + model.json from a folder written by Save().
  static MotionTextModel Load(const std::filesystem::path& dir);
  /// Writes model.pt and model.json (atomic) with the text encoder settings used in training.
  void Save(const std::filesystem::path& dir, const TextEncoderConfig& text_encoder,
            const std::string& text_encoder_description) const;

  /// Unit z of one window [seq_frames, feature_dim].
  Eigen::VectorXf EncodeMotion(const Eigen::MatrixXf& window) const;
  /// Unit z of a whole clip: mean of up to `windows` evenly spaced windows, re-normalised.
  Eigen::VectorXf EncodeClip(const CaptionedSequence& seq, int windows = 4) const;
  /// Unit MLP_d(t) for a text feature t.
  Eigen::VectorXf EncodeTextFeature(const Eigen::VectorXf& t) const;
  /// Decoder output for a window (in feature units).
  Eigen::MatrixXf Reconstruct(const Eigen::MatrixXf& window) const;

  /// Network settings.
  const MotionTextModelConfig& config() const;
  /// Size of the text feature.
  int text_dim() const;
  /// Text encoder settings stored with a loaded model (defaults for a fresh one).
  const TextEncoderConfig& text_encoder_config() const;
  /// Number of trainable parameters.
  int64_t num_parameters() const;

 private:
  struct Impl;
  explicit MotionTextModel(std::shared_ptr<Impl> impl);
  std::shared_ptr<Impl> impl_;
  friend struct MotionTextTrainerAccess;
};

/// The default motion–text model folder: data/language/text_motion when a model was trained
/// there, else the bundled assets/language/text_motion, else data/language/text_motion (so a
/// missing model is reported under the path train_text_motion writes by default).
std::filesystem::path DefaultStyleModelDir();

/// The command that trains the default model (for error messages and docs).
std::string TrainStyleModelCommand();

/// Training settings of train_text_motion (configs/language/text_motion.json).
struct MotionTextTrainConfig {
  MotionTextModelConfig model;               ///< Network sizes.
  TextEncoderConfig text_encoder;            ///< Frozen text encoder.
  std::string data_dir;                      ///< Dataset folder (format above).
  std::string out_dir = "runs/text_motion";  ///< Outputs and checkpoints.
  int steps = 5000;                          ///< Steps (and align_weight: docs/language.md).
  int batch_size = 32;                       ///< Windows per step.
  double learning_rate = 5e-4;               ///< AdamW learning rate.
  double weight_decay = 1e-4;                ///< AdamW weight decay.
  double grad_clip = 1.0;                    ///< Gradient-norm clip (0 = off).
  double recon_weight = 1.0;                 ///< Weight of the motion reconstruction MSE.
  double align_weight = 0.1;                 ///< Weight of 1 − cos(z, MLP_d(t)).
  double text_recon_weight = 1.0;            ///< Weight of ‖MLP_u(MLP_d(t)) − t‖.
  /// Weight of a uniformity term log mean exp(−2‖z_i − z_j‖²) over the batch (Wang & Isola 2020,
  /// as CALM uses for its encoder). Not in SIMS eq. 3–5 (set 0 for the paper's loss): without it
  /// nothing spreads z over the sphere and all embeddings crowd into a narrow cone.
  double uniformity_weight = 0.1;
  uint64_t seed = 1;           ///< Seed of initialisation and sampling.
  int threads = 0;             ///< Thread count (0 = all cores).
  int log_every = 50;          ///< Steps between CSV rows / progress lines.
  int checkpoint_every = 500;  ///< Steps between checkpoints.
  int bank_windows = 4;        ///< Windows averaged per clip in the bank.

  /// Binds fields to JSON.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(model));
    a->Visit(SIMS_NVP(text_encoder));
    a->Visit(SIMS_NVP(data_dir));
    a->Visit(SIMS_NVP(out_dir));
    a->Visit(SIMS_NVP(steps));
    a->Visit(SIMS_NVP(batch_size));
    a->Visit(SIMS_NVP(learning_rate));
    a->Visit(SIMS_NVP(weight_decay));
    a->Visit(SIMS_NVP(grad_clip));
    a->Visit(SIMS_NVP(recon_weight));
    a->Visit(SIMS_NVP(align_weight));
    a->Visit(SIMS_NVP(text_recon_weight));
    a->Visit(SIMS_NVP(uniformity_weight));
    a->Visit(SIMS_NVP(seed));
    a->Visit(SIMS_NVP(threads));
    a->Visit(SIMS_NVP(log_every));
    a->Visit(SIMS_NVP(checkpoint_every));
    a->Visit(SIMS_NVP(bank_windows));
  }
  /// Checks ranges.
  void Validate() const;
};

/// Loss values of one logged step.
struct MotionTextLosses {
  int step = 0;           ///< Steps completed.
  double total = 0;       ///< Weighted sum.
  double recon = 0;       ///< Motion reconstruction MSE (normalised features).
  double align = 0;       ///< Mean 1 − cos(z, MLP_d(t)).
  double text_recon = 0;  ///< Mean ‖MLP_u(MLP_d(t)) − t‖.
  double uniformity = 0;  ///< log mean exp(−2‖z_i − z_j‖²) over the batch.
};

/// Trains on `data` with the frozen `encoder` (whose dim() sets the text size), writing the
/// output folder described above. With `resume`, continues from out_dir/checkpoint.pt (the
/// network and text settings must match the checkpoint's). Returns the last logged losses.
MotionTextLosses TrainMotionText(const MotionTextTrainConfig& config,
                                 const std::vector<CaptionedSequence>& data,
                                 const TextEncoder& encoder, bool resume = false);

}  // namespace sims::language
