// Motion–text training data from the motion library: every clip (mirrors included) becomes a
// CaptionedSequence of its per-frame AMP observations at 30 fps with the clip's captions.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sims/language/motion_text.h"
#include "sims/motion/motion_library.h"

namespace sims::language {

/// The name a clip has in embedding banks and style tables ("<name>" or "<name>#mirror").
std::string StyleKey(const motion::MotionMeta& meta);

/// One sequence per library clip.
std::vector<CaptionedSequence> SequencesFromLibrary(const motion::MotionLibrary& library);

/// Loads a manifest (with mirroring) with the default humanoid and converts it.
std::vector<CaptionedSequence> SequencesFromManifest(const std::filesystem::path& manifest);

}  // namespace sims::language
