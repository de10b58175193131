#include "sims/language/text_encoder.h"

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <torch/script.h>
#include <torch/torch.h>

#include "common/test_util.h"
#include "sims/core/error.h"
#include "sims/language/tokenizer.h"

namespace sims::language {
namespace {

namespace fs = std::filesystem;

float Cos(const Eigen::VectorXf& a, const Eigen::VectorXf& b) {
  return a.dot(b) / (a.norm() * b.norm());
}

class BuiltinEncoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!BuiltinTextEncoder::DataAvailable())
      GTEST_SKIP() << "GloVe subset / CLIP vocabulary not prepared: run cmake/setup.sh, then "
                      "build/bin/prepare_assets";
    enc_ = std::make_unique<BuiltinTextEncoder>();
  }
  std::unique_ptr<BuiltinTextEncoder> enc_;
};

TEST_F(BuiltinEncoderTest, DeterministicUnitFeatures) {
  EXPECT_EQ(enc_->dim(), 100);
  const Eigen::VectorXf a = enc_->Encode("a person walks sadly with the head bowed");
  EXPECT_NEAR(a.norm(), 1.0f, 1e-5f);
  EXPECT_EQ(a, enc_->Encode("a person walks sadly with the head bowed"));
  BuiltinTextEncoder other;
  EXPECT_EQ(a, other.Encode("a person walks sadly with the head bowed"));
  // Whitespace, case and HTML entities are normalised like CLIP does.
  EXPECT_EQ(a, enc_->Encode("A person WALKS sadly   with the head bowed"));
  const Eigen::MatrixXf batch =
      enc_->EncodeBatch({"walk", "a person walks sadly with the head bowed"});
  EXPECT_EQ(Eigen::VectorXf(batch.row(1).transpose()), a);
  EXPECT_EQ(enc_->Encode("").size(), 100);
  EXPECT_EQ(enc_->Encode("").norm(), 0.f);
}

TEST_F(BuiltinEncoderTest, ParaphrasesAreCloserThanOtherStyles) {
  const auto sad = enc_->Encode("a person walks sadly");
  const auto unhappy = enc_->Encode("an unhappy man walking in sorrow");
  const auto joyful = enc_->Encode("a person jumps joyfully");
  const auto chair = enc_->Encode("someone sits down on a wooden chair");
  EXPECT_GT(Cos(sad, unhappy), Cos(sad, chair));
  EXPECT_GT(Cos(enc_->Encode("sits on the sofa"), enc_->Encode("sitting on a couch")),
            Cos(enc_->Encode("sits on the sofa"), enc_->Encode("running down the street")));
  EXPECT_GT(Cos(sad, unhappy), Cos(unhappy, joyful));
}

TEST_F(BuiltinEncoderTest, ExplainShowsLemmaAndFallbacks) {
  const auto traces = enc_->Explain("she sat zxqvbn");
  ASSERT_EQ(traces.size(), 3u);
  EXPECT_EQ(traces[1].word, "sat");
  EXPECT_EQ(traces[1].source, "exact+lemma");
  EXPECT_NE(traces[1].used.find("sit"), std::string::npos);
  EXPECT_EQ(traces[2].source, "subword");
  EXPECT_GT(traces[2].weight, traces[0].weight);  // rare words weigh more than "she"
}

TEST_F(BuiltinEncoderTest, ProjectionKeepsGeometry) {
  TextEncoderConfig c;
  c.dim = 256;
  BuiltinTextEncoder wide(c);
  EXPECT_EQ(wide.dim(), 256);
  const auto a = wide.Encode("a person walks sadly"), b = wide.Encode("a tired old man");
  EXPECT_NEAR(a.norm(), 1.f, 1e-5f);
  EXPECT_NEAR(Cos(a, b), Cos(enc_->Encode("a person walks sadly"), enc_->Encode("a tired old man")),
              1e-4f);
  c.dim = 64;
  EXPECT_EQ(BuiltinTextEncoder(c).Encode("walk").size(), 64);
}

TEST(TextEncoderConfigTest, ValidationNamesField) {
  TextEncoderConfig c;
  c.kind = "bert";
  try {
    MakeTextEncoder(c, "configs/x.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("configs/x.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("kind"), std::string::npos);
  }
  c.kind = "torchscript";
  EXPECT_THROW(MakeTextEncoder(c, "x"), Error);  // no torchscript_path
}

// --- TorchScript encoder ---------------------------------------------------------------------

class TorchScriptEncoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(ClipTokenizer::DefaultPath()))
      GTEST_SKIP() << "CLIP vocabulary not prepared: run build/bin/prepare_assets";
    dir_ = sims::testing::TempDir("torchscript");
  }
  // Checks a module whose forward returns [first 4 token ids, 4 pooled embedding values].
  void CheckTinyModule(const fs::path& file) {
    TextEncoderConfig c;
    c.kind = "torchscript";
    c.torchscript_path = file.string();
    c.normalize = false;
    auto enc = MakeTextEncoder(c);
    ASSERT_EQ(enc->dim(), 8);
    const Eigen::VectorXf f = enc->Encode("a person sits on the chair");
    EXPECT_EQ(f.head(4), Eigen::Vector4f(49406, 320, 2533, 12726));
    EXPECT_EQ(f, enc->Encode("a person sits on the chair"));
    const Eigen::MatrixXf batch = enc->EncodeBatch({"walk", "a person sits on the chair"});
    ASSERT_EQ(batch.rows(), 2);
    EXPECT_TRUE(batch.row(1).transpose().isApprox(f, 1e-6f));
    EXPECT_FALSE(batch.row(0).transpose().isApprox(f, 1e-3f));
    c.normalize = true;
    EXPECT_NEAR(MakeTextEncoder(c)->Encode("walk").norm(), 1.f, 1e-5f);
  }
  fs::path dir_;
};

TEST_F(TorchScriptEncoderTest, ModuleBuiltWithCppApi) {
  torch::manual_seed(0);
  torch::jit::Module m("TinyTextTower");
  m.register_parameter("emb", torch::randn({49408, 4}), false);
  m.define(R"JIT(
def forward(self, tokens):
    mask = (tokens > 0).float().unsqueeze(-1)
    pooled = (torch.embedding(self.emb, tokens) * mask).sum(1) / mask.sum(1)
    return torch.cat([tokens[:, :4].float(), pooled], 1)
)JIT");
  const fs::path file = dir_ / "tiny_cpp.pt";
  m.save(file.string());
  CheckTinyModule(file);
}

TEST_F(TorchScriptEncoderTest, ModuleScriptedByPythonTorch) {
  // Debian's python3-torch writes the module the way a user would (torch.jit.script + save).
  std::string python;
  for (const char* cand : {"/usr/bin/python3", "python3"}) {
    const std::string probe = std::string(cand) + " -c 'import torch' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) {
      python = cand;
      break;
    }
  }
  if (python.empty()) GTEST_SKIP() << "no python3 with torch (Debian python3-torch)";
  const fs::path script = dir_ / "make_tiny.py", file = dir_ / "tiny_py.pt";
  std::ofstream(script) << R"PY(
import sys, torch
class Tiny(torch.nn.Module):
    def __init__(self):
        super().__init__()
        torch.manual_seed(0)
        self.emb = torch.nn.Embedding(49408, 4)
    def forward(self, tokens: torch.Tensor) -> torch.Tensor:
        mask = (tokens > 0).float().unsqueeze(-1)
        pooled = (self.emb(tokens) * mask).sum(1) / mask.sum(1)
        return torch.cat([tokens[:, :4].float(), pooled], 1)
torch.jit.script(Tiny()).save(sys.argv[1])
)PY";
  const std::string cmd = python + " " + script.string() + " " + file.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  CheckTinyModule(file);
}

TEST_F(TorchScriptEncoderTest, BadFileAndMethodAreReported) {
  TextEncoderConfig c;
  c.kind = "torchscript";
  c.torchscript_path = (dir_ / "missing.pt").string();
  try {
    MakeTextEncoder(c);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.pt"), std::string::npos) << e.what();
  }
  torch::jit::Module m("M");
  m.define("def forward(self, x):\n    return x\n");
  m.save((dir_ / "m.pt").string());
  c.torchscript_path = (dir_ / "m.pt").string();
  c.method = "encode_text";
  EXPECT_THROW(MakeTextEncoder(c), Error);
}

}  // namespace
}  // namespace sims::language
