// Dataset folder format and windowing of the motion–text auto-encoder (no torch here).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/language/motion_text.h"

namespace sims::language {

namespace fs = std::filesystem;
using nlohmann::json;

void MotionTextModelConfig::Validate() const {
  Require(feature_dim > 0, "feature_dim", "a positive size");
  Require(seq_frames > 0, "seq_frames", "a positive frame count");
  Require(sample_fps > 0, "sample_fps", "a positive frame rate");
  Require(frames_per_token > 0 && seq_frames % frames_per_token == 0, "frames_per_token",
          "a positive divisor of seq_frames");
  Require(d_model > 0, "d_model", "a positive width");
  Require(num_heads > 0 && d_model % num_heads == 0, "num_heads", "a positive divisor of d_model");
  Require(encoder_layers > 0, "encoder_layers", "at least 1 layer");
  Require(decoder_layers > 0, "decoder_layers", "at least 1 layer");
  Require(ff_dim > 0, "ff_dim", "a positive width");
  Require(dropout >= 0 && dropout < 1, "dropout", "a probability in [0, 1)");
  Require(z_dim > 0, "z_dim", "a positive size");
  for (int h : mlp_hidden) Require(h > 0, "mlp_hidden", "positive layer sizes");
}

void MotionTextTrainConfig::Validate() const {
  Require(steps > 0, "steps", "a positive step count");
  Require(batch_size > 0, "batch_size", "a positive batch size");
  Require(learning_rate > 0, "learning_rate", "a positive learning rate");
  Require(weight_decay >= 0, "weight_decay", "a non-negative number");
  Require(grad_clip >= 0, "grad_clip", "0 (off) or a positive norm");
  Require(
      recon_weight >= 0 && align_weight >= 0 && text_recon_weight >= 0 && uniformity_weight >= 0,
      "recon_weight", "non-negative loss weights");
  Require(threads >= 0, "threads", "0 (all cores) or a positive count");
  Require(log_every > 0, "log_every", "a positive step count");
  Require(checkpoint_every > 0, "checkpoint_every", "a positive step count");
  Require(bank_windows > 0, "bank_windows", "at least 1 window");
  Require(!out_dir.empty(), "out_dir", "an output folder");
}

void SaveCaptionedSequence(const fs::path& file, const CaptionedSequence& seq) {
  std::ostringstream out;
  out.precision(7);
  out << "{\"clip\": " << json(seq.clip_name).dump() << ", \"fps\": " << seq.fps
      << ", \"captions\": " << json(seq.captions).dump() << ",\n \"features\": [";
  for (Eigen::Index r = 0; r < seq.features.rows(); ++r) {
    out << (r ? ",\n  [" : "\n  [");
    for (Eigen::Index c = 0; c < seq.features.cols(); ++c)
      out << (c ? "," : "") << seq.features(r, c);
    out << "]";
  }
  out << "]}\n";
  WriteFileAtomic(file, out.str());
}

CaptionedSequence LoadCaptionedSequence(const fs::path& file) {
  const json j = ReadJsonFile(file);
  const std::string src = file.string();
  if (!j.is_object()) ThrowInputError(src, "", "a JSON object {clip, fps, captions, features}");
  CaptionedSequence seq;
  seq.clip_name = file.stem().string();
  if (j.contains("clip")) {
    if (!j["clip"].is_string()) ThrowInputError(src, "clip", "a string", j["clip"].dump());
    seq.clip_name = j["clip"].get<std::string>();
  }
  if (j.contains("fps")) {
    if (!j["fps"].is_number() || j["fps"].get<double>() <= 0)
      ThrowInputError(src, "fps", "a positive frame rate", j["fps"].dump());
    seq.fps = j["fps"].get<double>();
  }
  if (j.contains("captions")) {
    const json& c = j["captions"];
    if (!c.is_array()) ThrowInputError(src, "captions", "an array of strings");
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (!c[i].is_string())
        ThrowInputError(src, "captions[" + std::to_string(i) + "]", "a string", c[i].dump());
      seq.captions.push_back(c[i].get<std::string>());
    }
  }
  if (!j.contains("features") || !j["features"].is_array() || j["features"].empty())
    ThrowInputError(src, "features", "a non-empty array of frames (arrays of numbers)");
  const json& f = j["features"];
  const std::size_t cols = f[0].is_array() ? f[0].size() : 0;
  if (cols == 0) ThrowInputError(src, "features[0]", "a non-empty array of numbers");
  seq.features.resize(static_cast<Eigen::Index>(f.size()), static_cast<Eigen::Index>(cols));
  for (std::size_t r = 0; r < f.size(); ++r) {
    const std::string field = "features[" + std::to_string(r) + "]";
    if (!f[r].is_array() || f[r].size() != cols)
      ThrowInputError(src, field, "an array of " + std::to_string(cols) + " numbers");
    for (std::size_t c = 0; c < cols; ++c) {
      if (!f[r][c].is_number())
        ThrowInputError(src, field + "[" + std::to_string(c) + "]", "a number", f[r][c].dump());
      const double v = f[r][c].get<double>();
      if (!std::isfinite(v)) ThrowInputError(src, field, "finite numbers", "NaN or infinity");
      seq.features(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
          static_cast<float>(v);
    }
  }
  return seq;
}

std::vector<CaptionedSequence> LoadCaptionedSequences(const fs::path& dir) {
  if (!fs::is_directory(dir))
    ThrowInputError(dir.string(), "data_dir", "a folder of clip JSON files", "not a folder");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty())
    ThrowInputError(dir.string(), "data_dir", "at least one <clip>.json file", "an empty folder");
  std::vector<CaptionedSequence> out;
  for (const auto& f : files) {
    out.push_back(LoadCaptionedSequence(f));
    if (out.back().features.cols() != out.front().features.cols())
      ThrowInputError(f.string(), "features",
                      std::to_string(out.front().features.cols()) + " values per frame (as in " +
                          files.front().filename().string() + ")",
                      std::to_string(out.back().features.cols()));
  }
  return out;
}

std::vector<int> WindowFrameIndices(int num_frames, double fps, const MotionTextModelConfig& config,
                                    double start_fraction) {
  SIMS_CHECK(num_frames > 0 && fps > 0);
  std::vector<int> idx(static_cast<std::size_t>(config.seq_frames));
  const double clip_s = num_frames / fps;
  const double window_s = config.seq_frames / config.sample_fps;
  if (clip_s >= window_s) {
    const double start_s = std::clamp(start_fraction, 0.0, 1.0) * (clip_s - window_s);
    for (int i = 0; i < config.seq_frames; ++i) {
      const double t = start_s + i / config.sample_fps;
      idx[static_cast<std::size_t>(i)] =
          std::clamp(static_cast<int>(std::lround(t * fps)), 0, num_frames - 1);
    }
  } else {
    // Shorter clip: spread the window's samples over the whole clip.
    for (int i = 0; i < config.seq_frames; ++i)
      idx[static_cast<std::size_t>(i)] =
          std::min(num_frames - 1,
                   static_cast<int>(static_cast<int64_t>(i) * num_frames / config.seq_frames));
  }
  return idx;
}

Eigen::MatrixXf SampleWindow(const CaptionedSequence& seq, const MotionTextModelConfig& config,
                             double start_fraction) {
  SIMS_CHECK(seq.features.cols() == config.feature_dim);
  const auto idx =
      WindowFrameIndices(static_cast<int>(seq.features.rows()), seq.fps, config, start_fraction);
  Eigen::MatrixXf w(config.seq_frames, config.feature_dim);
  for (int i = 0; i < config.seq_frames; ++i) w.row(i) = seq.features.row(idx[std::size_t(i)]);
  return w;
}

}  // namespace sims::language
