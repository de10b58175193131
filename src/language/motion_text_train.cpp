// Training loop of the motion–text auto-encoder (SIMS eq. 3–5) with resumable checkpoints.
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "language/motion_text_net.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/parallel.h"
#include "sims/core/progress.h"
#include "sims/core/rng.h"
#include "sims/language/embedding_bank.h"

namespace sims::language {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kCsvHeader =
    "step,loss,recon,align,text_recon,uniformity,learning_rate,steps_per_s,elapsed_s";

struct Caption {
  int clip;
  std::string text;
};

void SaveCheckpoint(const fs::path& path, internal::MotionTextNet& net,
                    torch::optim::Optimizer& opt, int step, const Rng& rng) {
  static std::atomic<int> counter{0};
  torch::serialize::OutputArchive root, model, optim;
  net->save(model);
  opt.save(optim);
  root.write("model", model);
  root.write("optimizer", optim);
  root.write("step", torch::tensor({static_cast<int64_t>(step)}, torch::kInt64));
  const auto s = rng.state();
  torch::Tensor rng_t = torch::empty({4}, torch::kInt64);
  for (int i = 0; i < 4; ++i) rng_t[i] = static_cast<int64_t>(s[static_cast<std::size_t>(i)]);
  root.write("rng", rng_t);
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  root.save_to(tmp.string());
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    ThrowInputError(path.string(), "", "a writable checkpoint location", "rename failed");
  }
}

int LoadCheckpoint(const fs::path& path, internal::MotionTextNet& net, torch::optim::Optimizer& opt,
                   Rng* rng) {
  try {
    torch::serialize::InputArchive root, model, optim;
    root.load_from(path.string());
    root.read("model", model);
    root.read("optimizer", optim);
    net->load(model);
    opt.load(optim);
    torch::Tensor step_t, rng_t;
    root.read("step", step_t);
    root.read("rng", rng_t);
    std::array<uint64_t, 4> s{};
    for (int i = 0; i < 4; ++i) s[std::size_t(i)] = static_cast<uint64_t>(rng_t[i].item<int64_t>());
    rng->set_state(s);
    return static_cast<int>(step_t.item<int64_t>());
  } catch (const c10::Error& e) {
    ThrowInputError(path.string(), "", "a checkpoint written by train_text_motion with this config",
                    std::string(e.what_without_backtrace()).substr(0, 200));
  }
}

// Keeps the CSV rows up to `step` (a resumed run rewrites what came after its checkpoint).
void PrepareCsv(const fs::path& path, int step) {
  std::string kept = std::string(kCsvHeader) + "\n";
  if (step > 0 && fs::exists(path)) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (std::atoi(line.c_str()) <= step) kept += line + "\n";
    }
  }
  WriteFileAtomic(path, kept);
}

// The resolved config, minus fields that may change on resume (steps, logging, paths).
json ResumeKey(const json& resolved) {
  json key = {{"model", resolved.at("model")}, {"text_encoder", resolved.at("text_encoder")}};
  return key;
}

}  // namespace

MotionTextLosses TrainMotionText(const MotionTextTrainConfig& config,
                                 const std::vector<CaptionedSequence>& data,
                                 const TextEncoder& encoder, bool resume) {
  ValidateConfig(config, "train_text_motion config");
  const auto& mc = config.model;
  if (data.empty()) throw Error("train_text_motion: no training clips");
  std::vector<Caption> captions;
  std::vector<std::vector<int>> clip_captions(data.size());
  for (std::size_t c = 0; c < data.size(); ++c) {
    const auto& seq = data[c];
    if (seq.features.cols() != mc.feature_dim)
      ThrowInputError("clip " + seq.clip_name, "features",
                      std::to_string(mc.feature_dim) + " values per frame (model.feature_dim)",
                      std::to_string(seq.features.cols()));
    if (seq.features.rows() == 0 || seq.fps <= 0)
      ThrowInputError("clip " + seq.clip_name, "features", "at least one frame at fps > 0");
    for (const auto& text : seq.captions) {
      clip_captions[c].push_back(static_cast<int>(captions.size()));
      captions.push_back({static_cast<int>(c), text});
    }
  }
  if (captions.empty()) throw Error("train_text_motion: no clip has a caption");

  if (config.threads > 0) SetThreadCount(config.threads);
  torch::set_num_threads(ThreadCount());

  const fs::path out(config.out_dir);
  fs::create_directories(out);
  json resolved = ConfigToJson(config);
  resolved["text_encoder_description"] = encoder.Describe();
  const fs::path config_path = out / "config.json";
  const fs::path ckpt_path = out / "checkpoint.pt";
  const bool have_ckpt = resume && fs::exists(ckpt_path);
  if (have_ckpt && fs::exists(config_path)) {
    const json previous = ReadJsonFile(config_path);
    if (!previous.contains("model") || !previous.contains("text_encoder") ||
        ResumeKey(previous) != ResumeKey(resolved))
      ThrowInputError(config_path.string(), "model/text_encoder",
                      "the same network and text encoder settings as the run being resumed",
                      "different settings (use a new out_dir or drop --resume)");
  }
  if (resume && !have_ckpt) spdlog::warn("--resume: no {} yet, starting fresh", ckpt_path.string());
  WriteJsonFile(config_path, resolved);

  // Frozen text encoder: every caption's feature is computed once.
  std::vector<std::string> texts;
  for (const auto& c : captions) texts.push_back(c.text);
  const Eigen::MatrixXf text_features = encoder.EncodeBatch(texts);
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor text_rm = text_features;
  const torch::Tensor text_t = torch::from_blob(const_cast<float*>(text_rm.data()),
                                                {text_rm.rows(), text_rm.cols()}, torch::kFloat)
                                   .clone();

  MotionTextModel model(mc, encoder.dim(), config.seed);
  auto& state = MotionTextTrainerAccess::State(model);
  auto& net = state.net;
  {
    // Per-feature normalisation over every frame of the training set.
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(mc.feature_dim);
    Eigen::VectorXd sq = Eigen::VectorXd::Zero(mc.feature_dim);
    double n = 0;
    for (const auto& seq : data) {
      const Eigen::MatrixXd f = seq.features.cast<double>();
      sum += f.colwise().sum().transpose();
      sq += f.array().square().colwise().sum().matrix().transpose();
      n += static_cast<double>(f.rows());
    }
    const Eigen::VectorXd mean = sum / n;
    const Eigen::VectorXd var = (sq / n - mean.array().square().matrix()).cwiseMax(0.0);
    torch::NoGradGuard ng;
    for (int i = 0; i < mc.feature_dim; ++i) {
      net->feat_mean[i] = static_cast<float>(mean[i]);
      net->feat_std[i] = static_cast<float>(std::max(std::sqrt(var[i]), 1e-3));
    }
  }
  torch::optim::AdamW opt(
      net->parameters(),
      torch::optim::AdamWOptions(config.learning_rate).weight_decay(config.weight_decay));
  Rng rng(config.seed * 0x9E3779B97F4A7C15ULL + 17);
  int step = 0;
  if (have_ckpt) {
    step = LoadCheckpoint(ckpt_path, net, opt, &rng);
    spdlog::info("resumed from {} at step {}", ckpt_path.string(), step);
  }
  const fs::path csv_path = out / "train_log.csv";
  PrepareCsv(csv_path, step);
  std::ofstream csv(csv_path, std::ios::app);

  spdlog::info(
      "train_text_motion: {} clips, {} captions, text {} ({}-d), {} parameters, {} threads",
      data.size(), captions.size(), encoder.Describe(), encoder.dim(), model.num_parameters(),
      ThreadCount());
  ProgressReporter progress("train_text_motion", config.steps, "steps");
  const auto t0 = std::chrono::steady_clock::now();
  const int start_step = step;
  const int64_t b = config.batch_size;
  MotionTextLosses last, running;
  int running_n = 0;
  net->train();
  std::vector<float> xbuf(static_cast<std::size_t>(b * mc.seq_frames * mc.feature_dim));
  while (step < config.steps) {
    std::vector<int64_t> cap_idx(static_cast<std::size_t>(b), 0);
    std::vector<float> mask(static_cast<std::size_t>(b), 0.f);
    for (int64_t i = 0; i < b; ++i) {
      const int c = static_cast<int>(rng.UniformInt(static_cast<int64_t>(data.size())));
      const Eigen::MatrixXf w = SampleWindow(data[std::size_t(c)], mc, rng.Uniform());
      // Eigen is column-major; the tensor wants [T, F] row-major per sample.
      float* dst = xbuf.data() + i * mc.seq_frames * mc.feature_dim;
      for (int r = 0; r < mc.seq_frames; ++r)
        for (int k = 0; k < mc.feature_dim; ++k) dst[r * mc.feature_dim + k] = w(r, k);
      const auto& caps = clip_captions[std::size_t(c)];
      if (!caps.empty()) {
        cap_idx[std::size_t(i)] = caps[std::size_t(rng.UniformInt(int64_t(caps.size())))];
        mask[std::size_t(i)] = 1.f;
      }
    }
    const torch::Tensor x =
        torch::from_blob(xbuf.data(), {b, mc.seq_frames, mc.feature_dim}, torch::kFloat);
    const torch::Tensor t = text_t.index_select(0, torch::tensor(cap_idx, torch::kInt64));
    const torch::Tensor m = torch::tensor(mask);
    const torch::Tensor denom = m.sum().clamp_min(1.0);

    const torch::Tensor z = net->EncodeMotion(x);
    const torch::Tensor recon = torch::mse_loss(net->Decode(z), net->Normalize(x));
    const torch::Tensor td = net->TextDown(t);
    const torch::Tensor cos = torch::cosine_similarity(z, td, 1, 1e-8);
    const torch::Tensor align = ((1 - cos) * m).sum() / denom;
    const torch::Tensor text_recon = ((net->TextUp(td) - t).norm(2, {1}) * m).sum() / denom;
    // Pairwise squared distances of unit vectors: 2 - 2 z_i.z_j, off-diagonal pairs only.
    const torch::Tensor sq = (2 - 2 * torch::mm(z, z.t())).clamp_min(0);
    const torch::Tensor off = 1 - torch::eye(b);
    const torch::Tensor uniformity =
        b > 1 ? torch::log(((-2 * sq).exp() * off).sum() / off.sum()) : torch::zeros({});
    const torch::Tensor loss = config.recon_weight * recon + config.align_weight * align +
                               config.text_recon_weight * text_recon +
                               config.uniformity_weight * uniformity;
    opt.zero_grad();
    loss.backward();
    if (config.grad_clip > 0)
      torch::nn::utils::clip_grad_norm_(net->parameters(), config.grad_clip);
    opt.step();
    ++step;

    running.total += loss.item<double>();
    running.recon += recon.item<double>();
    running.align += align.item<double>();
    running.text_recon += text_recon.item<double>();
    running.uniformity += uniformity.item<double>();
    ++running_n;
    const bool final_step = step == config.steps;
    if (step % config.log_every == 0 || final_step) {
      last = {step,
              running.total / running_n,
              running.recon / running_n,
              running.align / running_n,
              running.text_recon / running_n,
              running.uniformity / running_n};
      running = {};
      running_n = 0;
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double rate = elapsed > 0 ? (step - start_step) / elapsed : 0.0;
      char row[256];
      std::snprintf(row, sizeof(row), "%d,%.6f,%.6f,%.6f,%.6f,%.6f,%g,%.3f,%.2f\n", step,
                    last.total, last.recon, last.align, last.text_recon, last.uniformity,
                    config.learning_rate, rate, elapsed);
      csv << row << std::flush;
      char extra[160];
      std::snprintf(extra, sizeof(extra),
                    "loss %.4f (recon %.4f, align %.4f, text %.4f, unif %.3f)", last.total,
                    last.recon, last.align, last.text_recon, last.uniformity);
      progress.Update(step, extra);
    }
    if (step % config.checkpoint_every == 0 || final_step)
      SaveCheckpoint(ckpt_path, net, opt, step, rng);
  }
  progress.Finish();
  net->eval();
  model.Save(out, config.text_encoder, encoder.Describe());

  EmbeddingBank bank;
  bank.set_text_encoder(encoder.Describe());
  for (std::size_t i = 0; i < captions.size(); ++i)
    bank.AddCaption(captions[i].text, data[std::size_t(captions[i].clip)].clip_name,
                    model.EncodeTextFeature(text_features.row(Eigen::Index(i)).transpose()));
  for (const auto& seq : data)
    bank.AddClip(seq.clip_name, model.EncodeClip(seq, config.bank_windows));
  bank.Save(out / "bank.json");
  spdlog::info("wrote {} (model.pt, model.json, bank.json, train_log.csv)", out.string());
  return last;
}

}  // namespace sims::language
