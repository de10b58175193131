#include "sims/motion/mirror.h"

#include <array>
#include <cctype>
#include <cstring>

namespace sims::motion {

namespace {

std::array<int, humanoid::kNumDofs> BuildPartners() {
  std::array<int, humanoid::kNumDofs> partner{};
  const auto& names = humanoid::DofNames();
  for (int i = 0; i < humanoid::kNumDofs; ++i) {
    std::string n = names[i];
    if (n.rfind("left_", 0) == 0)
      n = "right_" + n.substr(5);
    else if (n.rfind("right_", 0) == 0)
      n = "left_" + n.substr(6);
    partner[i] = -1;
    for (int k = 0; k < humanoid::kNumDofs; ++k)
      if (n == names[k]) partner[i] = k;
    SIMS_CHECK(partner[i] >= 0);
  }
  return partner;
}

bool EndsWith(const std::string& s, const char* suffix) {
  const std::size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

std::string MatchCase(const std::string& like, std::string word) {
  bool all_upper = like.size() > 1;
  for (char c : like) all_upper = all_upper && !std::islower(static_cast<unsigned char>(c));
  if (all_upper) {
    for (char& c : word) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  } else if (!like.empty() && std::isupper(static_cast<unsigned char>(like[0]))) {
    word[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(word[0])));
  }
  return word;
}

}  // namespace

int MirrorDof(int i) {
  static const std::array<int, humanoid::kNumDofs> partner = BuildPartners();
  return partner[i];
}

double MirrorDofSign(int i) {
  for (const humanoid::JointSpec& js : humanoid::Joints()) {
    if (i < js.dof_offset || i >= js.dof_offset + js.dof_count) continue;
    if (js.dof_count == 1) return 1.0;
    return (i - js.dof_offset) == 1 ? 1.0 : -1.0;
  }
  return 1.0;
}

MotionFrame MirrorFrame(const MotionFrame& f) {
  MotionFrame m;
  m.root_pos = Eigen::Vector3d(f.root_pos.x(), -f.root_pos.y(), f.root_pos.z());
  m.root_rot = Eigen::Quaterniond(f.root_rot.w(), -f.root_rot.x(), f.root_rot.y(), -f.root_rot.z());
  for (int i = 0; i < humanoid::kNumDofs; ++i)
    m.dof_pos[MirrorDof(i)] = MirrorDofSign(i) * f.dof_pos[i];
  return m;
}

humanoid::HumanoidPose MirrorPose(const humanoid::HumanoidPose& p) {
  humanoid::HumanoidPose m;
  m.root_pos = Eigen::Vector3d(p.root_pos.x(), -p.root_pos.y(), p.root_pos.z());
  m.root_rot = Eigen::Quaterniond(p.root_rot.w(), -p.root_rot.x(), p.root_rot.y(), -p.root_rot.z());
  m.root_lin_vel = Eigen::Vector3d(p.root_lin_vel.x(), -p.root_lin_vel.y(), p.root_lin_vel.z());
  m.root_ang_vel = Eigen::Vector3d(-p.root_ang_vel.x(), p.root_ang_vel.y(), -p.root_ang_vel.z());
  for (int i = 0; i < humanoid::kNumDofs; ++i) {
    m.dof_pos[MirrorDof(i)] = MirrorDofSign(i) * p.dof_pos[i];
    m.dof_vel[MirrorDof(i)] = MirrorDofSign(i) * p.dof_vel[i];
  }
  return m;
}

std::string MirrorText(const std::string& text) {
  static const std::pair<const char*, const char*> pairs[] = {{"left", "right"},
                                                              {"leftward", "rightward"},
                                                              {"leftwards", "rightwards"},
                                                              {"clockwise", "counterclockwise"},
                                                              {"anticlockwise", "clockwise"},
                                                              {"counter-clockwise", "clockwise"}};
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (!std::isalpha(static_cast<unsigned char>(text[i]))) {
      out += text[i++];
      continue;
    }
    std::size_t j = i;
    while (j < text.size() && std::isalpha(static_cast<unsigned char>(text[j]))) ++j;
    // "counter-clockwise" is one word; other hyphens separate words ("left-handed").
    std::string probe = text.substr(i, 17);
    for (char& c : probe) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (probe == "counter-clockwise") j = i + 17;
    const std::string word = text.substr(i, j - i);
    std::string lower = word;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::string replaced = word;
    for (const auto& [a, b] : pairs) {
      if (lower == a)
        replaced = MatchCase(word, b);
      else if (lower == b && std::strcmp(a, "anticlockwise") != 0 &&
               std::strcmp(a, "counter-clockwise") != 0)
        replaced = MatchCase(word, a);
    }
    out += replaced;
    i = j;
  }
  return out;
}

MotionClip MirrorClip(const MotionClip& clip) {
  std::vector<MotionFrame> frames(clip.num_frames());
  for (int i = 0; i < clip.num_frames(); ++i) frames[i] = MirrorFrame(clip.frame(i));
  MotionMeta meta = clip.meta();
  for (auto& c : meta.captions) c = MirrorText(c);
  meta.style = MirrorText(meta.style);
  if (EndsWith(meta.name, "_mirror"))
    meta.name = MirrorText(meta.name.substr(0, meta.name.size() - 7));
  else
    meta.name = MirrorText(meta.name) + "_mirror";
  for (auto& [k, v] : meta.params)
    if (EndsWith(k, "_y") || EndsWith(k, "_yaw")) v = -v;
  meta.mirrored = !meta.mirrored;
  return MotionClip(clip.fps(), std::move(frames), std::move(meta));
}

}  // namespace sims::motion
