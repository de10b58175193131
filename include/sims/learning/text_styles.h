// Text-aligned style embeddings for the learner (SIMS §3.3): each clip's z comes from the
// trained motion–text auto-encoder's embedding bank, so the conditional discriminator and
// the policy see the same space a caption is embedded into at run time.
#pragma once

#include <filesystem>
#include <memory>

#include "sims/motion/motion_library.h"
#include "sims/task/skill.h"
#include "sims/task/styles.h"

namespace sims::learning {

/// z per library clip from the model in `model_dir` (bank entry of the clip, else the
/// embedding of its first caption); throws sims::Error naming the folder if it cannot load.
std::shared_ptr<const task::StyleTable> TextAlignedStyles(const motion::MotionLibrary& library,
                                                          const std::filesystem::path& model_dir);

/// When config.style_model is set (and clips are loaded), replaces the setup's clip-name style
/// codes by TextAlignedStyles in both the context and the skill, so training, evaluation and
/// benchmarks all see the z the policy was trained with.
void ApplyStyleModel(const task::SkillConfig& config, task::SkillSetup* setup);

}  // namespace sims::learning
