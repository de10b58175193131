#include "sims/learning/text_styles.h"

#include "sims/core/log.h"
#include "sims/language/embedding_bank.h"
#include "sims/language/motion_clips.h"

namespace sims::learning {

std::shared_ptr<const task::StyleTable> TextAlignedStyles(const motion::MotionLibrary& library,
                                                          const std::filesystem::path& model_dir) {
  const auto embedder = language::StyleEmbedder::Load(model_dir);
  std::vector<Eigen::VectorXf> z;
  int from_bank = 0;
  for (int i = 0; i < library.num_clips(); ++i) {
    const auto& meta = library.clip(i).meta();
    if (const Eigen::VectorXf* v = embedder.ClipZ(language::StyleKey(meta))) {
      z.push_back(*v);
      ++from_bank;
    } else {
      z.push_back(embedder.Embed(meta.captions.empty() ? meta.name : meta.captions.front()));
    }
  }
  spdlog::info("text-aligned styles from {}: {} clips from the bank, {} from captions",
               model_dir.string(), from_bank, library.num_clips() - from_bank);
  return std::make_shared<const task::StyleTable>(std::move(z));
}

void ApplyStyleModel(const task::SkillConfig& config, task::SkillSetup* setup) {
  if (config.style_model.empty() || !setup->context.motions) return;
  setup->context.styles = TextAlignedStyles(*setup->context.motions, config.style_model);
  setup->skill->SetStyleTable(setup->context.styles);
}

}  // namespace sims::learning
