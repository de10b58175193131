// TorchScript text encoder: CLIP tokenizer -> user module -> feature rows.
#include <mutex>

#include <torch/script.h>
#include <torch/torch.h>

#include "sims/core/error.h"
#include "sims/language/text_encoder.h"
#include "sims/language/tokenizer.h"

namespace sims::language {

namespace {

class TorchScriptTextEncoder : public TextEncoder {
 public:
  explicit TorchScriptTextEncoder(const TextEncoderConfig& config)
      : config_(config),
        tok_(config.bpe.empty() ? ClipTokenizer::LoadDefault()
                                : ClipTokenizer::FromFile(config.bpe)) {
    const std::string& path = config.torchscript_path;
    try {
      module_ = torch::jit::load(path, torch::kCPU);
    } catch (const c10::Error& e) {
      ThrowInputError(path, "torchscript_path", "a TorchScript file saved with torch.jit.save",
                      std::string(e.what_without_backtrace()).substr(0, 200));
    }
    module_.eval();
    if (!module_.find_method(config.method))
      ThrowInputError(path, "method", "a method named '" + config.method + "' in the module",
                      "no such method");
    dim_ = static_cast<int>(Run({""}).size(1));
  }

  int dim() const override { return dim_; }

  Eigen::VectorXf Encode(const std::string& caption) const override {
    return EncodeBatch({caption}).row(0).transpose();
  }

  Eigen::MatrixXf EncodeBatch(const std::vector<std::string>& captions) const override {
    if (captions.empty()) return Eigen::MatrixXf(0, dim_);
    torch::Tensor out = Run(captions);
    using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    return Eigen::Map<const RowMajor>(out.data_ptr<float>(), out.size(0), out.size(1));
  }

  std::string Describe() const override {
    return "torchscript:" + config_.torchscript_path + ":" + config_.method + ":dim" +
           std::to_string(dim_);
  }

 private:
  torch::Tensor Run(const std::vector<std::string>& captions) const {
    const int64_t b = static_cast<int64_t>(captions.size());
    const int64_t l = config_.context_length;
    torch::Tensor ids = torch::zeros({b, l}, torch::kInt64);
    auto acc = ids.accessor<int64_t, 2>();
    for (int64_t i = 0; i < b; ++i) {
      const auto row =
          tok_.EncodeForClip(captions[static_cast<std::size_t>(i)], static_cast<int>(l));
      for (int64_t j = 0; j < l; ++j) acc[i][j] = row[static_cast<std::size_t>(j)];
    }
    torch::Tensor out;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      torch::NoGradGuard no_grad;
      torch::jit::IValue result;
      try {
        result = module_.get_method(config_.method)({ids});
      } catch (const std::exception& e) {
        ThrowInputError(config_.torchscript_path, config_.method,
                        "a method taking int64 token ids [B, " + std::to_string(l) + "]",
                        std::string(e.what()).substr(0, 200));
      }
      if (!result.isTensor())
        ThrowInputError(config_.torchscript_path, config_.method, "a tensor result [B, D]",
                        "a non-tensor value");
      out = result.toTensor();
    }
    if (out.dim() == 1) out = out.unsqueeze(0);
    if (out.dim() != 2 || out.size(0) != b)
      ThrowInputError(config_.torchscript_path, config_.method,
                      "a result of shape [" + std::to_string(b) + ", D]",
                      "shape " + c10::str(out.sizes()));
    out = out.to(torch::kFloat).contiguous();
    if (config_.normalize) out = out / out.norm(2, {1}, true).clamp_min(1e-12);
    return out.contiguous();
  }

  TextEncoderConfig config_;
  ClipTokenizer tok_;
  mutable torch::jit::Module module_;
  mutable std::mutex mutex_;
  int dim_ = 0;
};

}  // namespace

std::unique_ptr<TextEncoder> MakeTorchScriptTextEncoder(const TextEncoderConfig& config) {
  ValidateConfig(config, "text_encoder");
  return std::make_unique<TorchScriptTextEncoder>(config);
}

}  // namespace sims::language
