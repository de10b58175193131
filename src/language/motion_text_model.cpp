#include <atomic>
#include <cmath>

#include <unistd.h>

#include "language/motion_text_net.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"

namespace sims::language {

namespace fs = std::filesystem;
using nlohmann::json;

namespace internal {

namespace {

torch::nn::Sequential Mlp(int in, const std::vector<int>& hidden, int out) {
  torch::nn::Sequential s;
  int prev = in;
  for (int h : hidden) {
    s->push_back(torch::nn::Linear(prev, h));
    s->push_back(torch::nn::GELU());
    prev = h;
  }
  s->push_back(torch::nn::Linear(prev, out));
  return s;
}

torch::nn::TransformerEncoder Transformer(const MotionTextModelConfig& c, int layers) {
  auto layer = torch::nn::TransformerEncoderLayerOptions(c.d_model, c.num_heads)
                   .dim_feedforward(c.ff_dim)
                   .dropout(c.dropout)
                   .activation(torch::kGELU);
  return torch::nn::TransformerEncoder(
      torch::nn::TransformerEncoderOptions(torch::nn::TransformerEncoderLayer(layer), layers));
}

}  // namespace

MotionTextNetImpl::MotionTextNetImpl(const MotionTextModelConfig& c, int text_dim_in)
    : config(c), text_dim(text_dim_in), tokens(c.seq_frames / c.frames_per_token) {
  const int patch = c.frames_per_token * c.feature_dim;
  in_proj = register_module("in_proj", torch::nn::Linear(patch, c.d_model));
  cls = register_parameter("cls", torch::randn({1, 1, c.d_model}) * 0.02);
  enc_pos = register_parameter("enc_pos", torch::randn({tokens + 1, 1, c.d_model}) * 0.02);
  encoder = register_module("encoder", Transformer(c, c.encoder_layers));
  to_z = register_module("to_z", torch::nn::Linear(c.d_model, c.z_dim));
  from_z = register_module("from_z", torch::nn::Linear(c.z_dim, c.d_model));
  dec_pos = register_parameter("dec_pos", torch::randn({tokens, 1, c.d_model}) * 0.02);
  decoder = register_module("decoder", Transformer(c, c.decoder_layers));
  out_proj = register_module("out_proj", torch::nn::Linear(c.d_model, patch));
  mlp_d = register_module("mlp_d", Mlp(text_dim, c.mlp_hidden, c.z_dim));
  mlp_u = register_module("mlp_u", Mlp(c.z_dim, c.mlp_hidden, text_dim));
  feat_mean = register_buffer("feat_mean", torch::zeros({c.feature_dim}));
  feat_std = register_buffer("feat_std", torch::ones({c.feature_dim}));
}

torch::Tensor MotionTextNetImpl::Normalize(const torch::Tensor& x) const {
  return (x - feat_mean) / feat_std;
}

torch::Tensor MotionTextNetImpl::EncodeMotion(const torch::Tensor& x) {
  const int64_t b = x.size(0);
  const int patch = config.frames_per_token * config.feature_dim;
  // [B, T, F] -> [tokens, B, patch]: attention over the whole window in both directions.
  torch::Tensor h = in_proj(Normalize(x).reshape({b, tokens, patch})).transpose(0, 1);
  h = torch::cat({cls.expand({1, b, config.d_model}), h}, 0) + enc_pos;
  h = encoder(h);
  return torch::nn::functional::normalize(
      to_z(h[0]), torch::nn::functional::NormalizeFuncOptions().dim(1).eps(1e-8));
}

torch::Tensor MotionTextNetImpl::Decode(const torch::Tensor& z) {
  const int64_t b = z.size(0);
  torch::Tensor h = dec_pos + from_z(z).unsqueeze(0);  // [tokens, B, d]
  h = out_proj(decoder(h));                            // [tokens, B, patch]
  return h.transpose(0, 1).reshape({b, config.seq_frames, config.feature_dim});
}

torch::Tensor MotionTextNetImpl::TextDown(const torch::Tensor& t) { return mlp_d->forward(t); }
torch::Tensor MotionTextNetImpl::TextUp(const torch::Tensor& zt) { return mlp_u->forward(zt); }

torch::Tensor WindowTensor(const Eigen::MatrixXf& window) {
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor rm = window;
  return torch::from_blob(const_cast<float*>(rm.data()), {1, rm.rows(), rm.cols()}, torch::kFloat)
      .clone();
}

}  // namespace internal

struct MotionTextModel::Impl : internal::MotionTextModelState {};

internal::MotionTextModelState& MotionTextTrainerAccess::State(MotionTextModel& m) {
  return *m.impl_;
}

namespace {

Eigen::VectorXf ToEigen(const torch::Tensor& t) {
  const torch::Tensor c = t.reshape({-1}).to(torch::kFloat).contiguous();
  return Eigen::Map<const Eigen::VectorXf>(c.data_ptr<float>(), c.numel());
}

void SaveModuleAtomic(const torch::nn::Module& module, const fs::path& path) {
  static std::atomic<int> counter{0};
  fs::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  torch::serialize::OutputArchive archive;
  module.save(archive);
  archive.save_to(tmp.string());
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    ThrowInputError(path.string(), "", "a writable location", "rename failed");
  }
}

}  // namespace

MotionTextModel::MotionTextModel(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

MotionTextModel::MotionTextModel(const MotionTextModelConfig& config, int text_dim, uint64_t seed)
    : impl_(std::make_shared<Impl>()) {
  ValidateConfig(config, "model");
  SIMS_CHECK(text_dim > 0);
  torch::manual_seed(seed);
  impl_->config = config;
  impl_->text_dim = text_dim;
  impl_->net = internal::MotionTextNet(config, text_dim);
  impl_->net->eval();
}

MotionTextModel::~MotionTextModel() = default;
MotionTextModel::MotionTextModel(const MotionTextModel&) = default;
MotionTextModel& MotionTextModel::operator=(const MotionTextModel&) = default;

const MotionTextModelConfig& MotionTextModel::config() const { return impl_->config; }
int MotionTextModel::text_dim() const { return impl_->text_dim; }
const TextEncoderConfig& MotionTextModel::text_encoder_config() const {
  return impl_->text_encoder;
}

int64_t MotionTextModel::num_parameters() const {
  int64_t n = 0;
  for (const auto& p : impl_->net->parameters()) n += p.numel();
  return n;
}

void MotionTextModel::Save(const fs::path& dir, const TextEncoderConfig& text_encoder,
                           const std::string& text_encoder_description) const {
  fs::create_directories(dir);
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    SaveModuleAtomic(*impl_->net, dir / "model.pt");
  }
  json j = {{"format", "sims-motion-text-1"},
            {"model", ConfigToJson(impl_->config)},
            {"text_dim", impl_->text_dim},
            {"text_encoder", ConfigToJson(text_encoder)},
            {"text_encoder_description", text_encoder_description}};
  WriteJsonFile(dir / "model.json", j);
  impl_->text_encoder = text_encoder;
}

fs::path DefaultStyleModelDir() {
  const fs::path trained = DataPath("language/text_motion");
  if (fs::exists(trained / "model.json")) return trained;
  const fs::path bundled = AssetPath("language/text_motion");
  if (fs::exists(bundled / "model.json")) return bundled;
  return trained;
}

std::string TrainStyleModelCommand() {
  return "build/bin/train_text_motion --manifest data/motions/synthetic/manifest.json --out " +
         DataPath("language/text_motion").string();
}

MotionTextModel MotionTextModel::Load(const fs::path& dir) {
  const fs::path meta = dir / "model.json";
  if (!fs::exists(meta))
    ThrowInputError(meta.string(), "",
                    "a motion-text model (train one with: " + TrainStyleModelCommand() + ")",
                    "missing");
  const json j = ReadJsonFile(meta);
  if (!j.is_object() || j.value("format", "") != "sims-motion-text-1")
    ThrowInputError(meta.string(), "format", "\"sims-motion-text-1\"",
                    j.is_object() ? j.value("format", "missing") : "not an object");
  if (!j.contains("model") || !j.contains("text_dim") || !j["text_dim"].is_number_integer() ||
      j["text_dim"].get<int>() <= 0)
    ThrowInputError(meta.string(), "text_dim", "a positive integer (and a model section)");
  const auto config = ConfigFromJson<MotionTextModelConfig>(j["model"], meta.string() + ":model");
  TextEncoderConfig text_config;
  if (j.contains("text_encoder"))
    text_config =
        ConfigFromJson<TextEncoderConfig>(j["text_encoder"], meta.string() + ":text_encoder");
  auto impl = std::make_shared<Impl>();
  impl->config = config;
  impl->text_dim = j["text_dim"].get<int>();
  impl->text_encoder = text_config;
  impl->net = internal::MotionTextNet(config, impl->text_dim);
  const fs::path weights = dir / "model.pt";
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(weights.string());
    impl->net->load(archive);
  } catch (const c10::Error& e) {
    ThrowInputError(weights.string(), "", "weights matching " + meta.string(),
                    std::string(e.what_without_backtrace()).substr(0, 200));
  }
  impl->net->eval();
  return MotionTextModel(std::move(impl));
}

Eigen::VectorXf MotionTextModel::EncodeMotion(const Eigen::MatrixXf& window) const {
  if (window.rows() != impl_->config.seq_frames || window.cols() != impl_->config.feature_dim)
    throw Error("MotionTextModel::EncodeMotion: expected a window of " +
                std::to_string(impl_->config.seq_frames) + "x" +
                std::to_string(impl_->config.feature_dim) + " features, got " +
                std::to_string(window.rows()) + "x" + std::to_string(window.cols()));
  std::lock_guard<std::mutex> lock(impl_->mutex);
  torch::NoGradGuard no_grad;
  return ToEigen(impl_->net->EncodeMotion(internal::WindowTensor(window)));
}

Eigen::VectorXf MotionTextModel::EncodeClip(const CaptionedSequence& seq, int windows) const {
  if (seq.features.cols() != impl_->config.feature_dim)
    throw Error("clip '" + seq.clip_name + "': expected " +
                std::to_string(impl_->config.feature_dim) + " features per frame, got " +
                std::to_string(seq.features.cols()));
  const double clip_s = seq.features.rows() / seq.fps;
  const double window_s = impl_->config.seq_frames / impl_->config.sample_fps;
  const int n = clip_s > window_s ? std::max(1, windows) : 1;
  Eigen::VectorXf acc = Eigen::VectorXf::Zero(impl_->config.z_dim);
  for (int k = 0; k < n; ++k) {
    const double start = n == 1 ? 0.5 : static_cast<double>(k) / (n - 1);
    acc += EncodeMotion(SampleWindow(seq, impl_->config, start));
  }
  const float norm = acc.norm();
  return norm > 0 ? Eigen::VectorXf(acc / norm) : acc;
}

Eigen::VectorXf MotionTextModel::EncodeTextFeature(const Eigen::VectorXf& t) const {
  if (t.size() != impl_->text_dim)
    throw Error("MotionTextModel::EncodeTextFeature: expected a text feature of size " +
                std::to_string(impl_->text_dim) + ", got " + std::to_string(t.size()) +
                " (was the model trained with another text encoder?)");
  std::lock_guard<std::mutex> lock(impl_->mutex);
  torch::NoGradGuard no_grad;
  torch::Tensor tt =
      torch::from_blob(const_cast<float*>(t.data()), {1, t.size()}, torch::kFloat).clone();
  torch::Tensor z = torch::nn::functional::normalize(
      impl_->net->TextDown(tt), torch::nn::functional::NormalizeFuncOptions().dim(1).eps(1e-8));
  return ToEigen(z);
}

Eigen::MatrixXf MotionTextModel::Reconstruct(const Eigen::MatrixXf& window) const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  torch::NoGradGuard no_grad;
  auto& net = impl_->net;
  torch::Tensor x = net->Decode(net->EncodeMotion(internal::WindowTensor(window)))[0];
  x = (x * net->feat_std + net->feat_mean).contiguous();
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(x.data_ptr<float>(), x.size(0), x.size(1));
}

}  // namespace sims::language
