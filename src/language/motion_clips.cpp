#include "sims/language/motion_clips.h"

#include "sims/humanoid/features.h"
#include "sims/humanoid/model_builder.h"

namespace sims::language {

std::string StyleKey(const motion::MotionMeta& meta) {
  return meta.name + (meta.mirrored ? "#mirror" : "");
}

std::vector<CaptionedSequence> SequencesFromLibrary(const motion::MotionLibrary& library) {
  std::vector<CaptionedSequence> out;
  for (int i = 0; i < library.num_clips(); ++i) {
    const auto& meta = library.clip(i).meta();
    const std::vector<float> f = library.ClipAmpFeatures(i, 30.0);
    const int frames = static_cast<int>(f.size() / humanoid::kAmpObsStepDim);
    CaptionedSequence s;
    s.clip_name = StyleKey(meta);
    s.fps = 30.0;
    s.captions = meta.captions;
    s.features.resize(frames, humanoid::kAmpObsStepDim);
    for (int r = 0; r < frames; ++r)
      for (int c = 0; c < humanoid::kAmpObsStepDim; ++c)
        s.features(r, c) = f[static_cast<size_t>(r) * humanoid::kAmpObsStepDim + c];
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<CaptionedSequence> SequencesFromManifest(const std::filesystem::path& manifest) {
  auto humanoid = std::make_shared<const humanoid::Humanoid>(humanoid::BuildModel());
  motion::MotionLibraryOptions opt;
  opt.mirror = true;
  return SequencesFromLibrary(motion::MotionLibrary::Load(manifest, humanoid, opt));
}

}  // namespace sims::language
