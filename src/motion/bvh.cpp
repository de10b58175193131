#include "sims/motion/bvh.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include <spdlog/spdlog.h>

#include "sims/core/config.h"
#include "sims/core/error.h"

namespace sims::motion {

namespace {

constexpr int kMaxDepth = 256;

struct Token {
  std::string_view text;
  int line = 0;
};

// Whitespace tokenizer that remembers line numbers (braces are tokens of their own).
class Lexer {
 public:
  Lexer(const std::string& text, std::string source) : text_(text), source_(std::move(source)) {}

  bool AtEnd() {
    SkipSpace();
    return pos_ >= text_.size();
  }
  Token Next(const char* expected) {
    SkipSpace();
    if (pos_ >= text_.size())
      Fail(line_, expected, std::string("more input"), std::string("end of file (truncated?)"));
    const std::size_t start = pos_;
    if (text_[pos_] == '{' || text_[pos_] == '}') {
      ++pos_;
    } else {
      while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) &&
             text_[pos_] != '{' && text_[pos_] != '}')
        ++pos_;
    }
    return {std::string_view(text_).substr(start, pos_ - start), line_};
  }
  void Expect(std::string_view word, const std::string& field) {
    const Token t = Next(field.c_str());
    if (t.text != word) Fail(t.line, field, "'" + std::string(word) + "'", t);
  }
  double Number(const char* field) {
    const Token t = Next(field);
    return ParseNumber(t, field);
  }
  double ParseNumber(const Token& t, const char* field) const {
    const std::string s(t.text);
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
      Fail(t.line, field, "a number", t);
    return v;
  }
  // Rest of the current line from the current position (used by the frame rows).
  std::size_t pos() const { return pos_; }
  int line() const { return line_; }
  void set_pos(std::size_t p, int line) {
    pos_ = p;
    line_ = line;
  }
  const std::string& text() const { return text_; }
  const std::string& source() const { return source_; }

  [[noreturn]] void Fail(int line, const std::string& field, const std::string& expected,
                         const Token& got) const {
    Fail(line, field, expected, "'" + std::string(got.text) + "'");
  }
  [[noreturn]] void Fail(int line, const std::string& field, const std::string& expected,
                         const std::string& got) const {
    ThrowInputError(source_ + ":" + std::to_string(line), field, expected, got);
  }

 private:
  void SkipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  const std::string& text_;
  std::string source_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

bool ParseChannel(std::string_view s, BvhChannel* c) {
  static const std::pair<const char*, BvhChannel> names[] = {
      {"Xposition", BvhChannel::kXposition}, {"Yposition", BvhChannel::kYposition},
      {"Zposition", BvhChannel::kZposition}, {"Xrotation", BvhChannel::kXrotation},
      {"Yrotation", BvhChannel::kYrotation}, {"Zrotation", BvhChannel::kZrotation}};
  for (const auto& [n, v] : names)
    if (s == n) {
      *c = v;
      return true;
    }
  return false;
}

bool IsRotation(BvhChannel c) { return static_cast<int>(c) >= 3; }
int Axis(BvhChannel c) { return static_cast<int>(c) % 3; }

void ParseJoint(Lexer& lex, BvhMotion* bvh, int parent, int depth, int* channel_count) {
  if (depth > kMaxDepth)
    lex.Fail(lex.line(), "HIERARCHY", "a hierarchy at most 256 deep", "deeper");
  const Token name = lex.Next("joint name");
  BvhJoint joint;
  joint.name = std::string(name.text);
  joint.parent = parent;
  const int index = static_cast<int>(bvh->joints.size());
  lex.Expect("{", "joint '" + joint.name + "'");
  lex.Expect("OFFSET", "OFFSET");
  for (int k = 0; k < 3; ++k) joint.offset[k] = lex.Number("OFFSET");
  Token t = lex.Next("CHANNELS, JOINT, End Site or }");
  if (t.text == "CHANNELS") {
    const Token nt = lex.Next("CHANNELS");
    const double n = lex.ParseNumber(nt, "CHANNELS");
    if (n < 0 || n > 6 || n != std::floor(n))
      lex.Fail(nt.line, "CHANNELS", "a channel count between 0 and 6", nt);
    for (int k = 0; k < static_cast<int>(n); ++k) {
      const Token ct = lex.Next("CHANNELS");
      BvhChannel c;
      if (!ParseChannel(ct.text, &c))
        lex.Fail(ct.line, "CHANNELS of '" + joint.name + "'",
                 std::to_string(static_cast<int>(n)) + " channel names (Xposition ... Zrotation)",
                 ct);
      for (BvhChannel prev : joint.channels)
        if (prev == c)
          lex.Fail(ct.line, "CHANNELS of '" + joint.name + "'", "distinct channels", ct);
      joint.channels.push_back(c);
    }
    t = lex.Next("JOINT, End Site or }");
  }
  joint.channel_start = *channel_count;
  *channel_count += static_cast<int>(joint.channels.size());
  bvh->joints.push_back(joint);
  while (t.text != "}") {
    if (t.text == "JOINT") {
      ParseJoint(lex, bvh, index, depth + 1, channel_count);
    } else if (t.text == "End") {
      lex.Expect("Site", "End Site");
      lex.Expect("{", "End Site");
      lex.Expect("OFFSET", "End Site OFFSET");
      Eigen::Vector3d e;
      for (int k = 0; k < 3; ++k) e[k] = lex.Number("End Site OFFSET");
      lex.Expect("}", "End Site");
      bvh->joints[index].has_end_site = true;
      bvh->joints[index].end_site = e;
    } else {
      lex.Fail(t.line, "joint '" + joint.name + "'", "JOINT, End Site or }", t);
    }
    t = lex.Next("JOINT, End Site or }");
  }
}

std::string FormatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

void FormatJoint(const BvhMotion& bvh, int j, int depth, std::string* out) {
  const std::string ind(depth, '\t');
  const BvhJoint& jt = bvh.joints[j];
  *out += ind + (jt.parent < 0 ? "ROOT " : "JOINT ") + jt.name + "\n" + ind + "{\n";
  *out += ind + "\tOFFSET " + FormatNumber(jt.offset.x()) + " " + FormatNumber(jt.offset.y()) +
          " " + FormatNumber(jt.offset.z()) + "\n";
  if (!jt.channels.empty() || jt.parent < 0) {
    *out += ind + "\tCHANNELS " + std::to_string(jt.channels.size());
    for (BvhChannel c : jt.channels) *out += std::string(" ") + BvhChannelName(c);
    *out += "\n";
  }
  for (int c : bvh.Children(j)) FormatJoint(bvh, c, depth + 1, out);
  if (jt.has_end_site) {
    *out += ind + "\tEnd Site\n" + ind + "\t{\n" + ind + "\t\tOFFSET " +
            FormatNumber(jt.end_site.x()) + " " + FormatNumber(jt.end_site.y()) + " " +
            FormatNumber(jt.end_site.z()) + "\n" + ind + "\t}\n";
  }
  *out += ind + "}\n";
}

}  // namespace

const char* BvhChannelName(BvhChannel c) {
  switch (c) {
    case BvhChannel::kXposition:
      return "Xposition";
    case BvhChannel::kYposition:
      return "Yposition";
    case BvhChannel::kZposition:
      return "Zposition";
    case BvhChannel::kXrotation:
      return "Xrotation";
    case BvhChannel::kYrotation:
      return "Yrotation";
    case BvhChannel::kZrotation:
      return "Zrotation";
  }
  return "?";
}

int BvhMotion::num_channels() const {
  int n = 0;
  for (const auto& j : joints) n += static_cast<int>(j.channels.size());
  return n;
}

int BvhMotion::FindJoint(const std::string& name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<int> BvhMotion::Children(int j) const {
  std::vector<int> out;
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].parent == j) out.push_back(static_cast<int>(i));
  return out;
}

BvhMotion ParseBvh(const std::string& text, const std::string& source) {
  Lexer lex(text, source);
  BvhMotion bvh;
  lex.Expect("HIERARCHY", "HIERARCHY");
  lex.Expect("ROOT", "ROOT");
  int channels = 0;
  ParseJoint(lex, &bvh, -1, 0, &channels);
  Token t = lex.Next("MOTION");
  if (t.text == "ROOT") lex.Fail(t.line, "ROOT", "a single root joint", "a second ROOT");
  if (t.text != "MOTION") lex.Fail(t.line, "MOTION", "'MOTION'", t);
  t = lex.Next("Frames:");
  if (t.text == "Frames")
    lex.Expect(":", "Frames:");
  else if (t.text != "Frames:")
    lex.Fail(t.line, "Frames", "'Frames:'", t);
  const Token ft = lex.Next("Frames");
  const double frames = lex.ParseNumber(ft, "Frames");
  if (frames != std::floor(frames) || frames < 0) lex.Fail(ft.line, "Frames", "a frame count", ft);
  if (frames < 1) lex.Fail(ft.line, "Frames", "at least 1 frame", ft);
  if (frames > 1e8) lex.Fail(ft.line, "Frames", "at most 1e8 frames", ft);
  lex.Expect("Frame", "Frame Time:");
  t = lex.Next("Frame Time:");
  if (t.text == "Time")
    lex.Expect(":", "Frame Time:");
  else if (t.text != "Time:")
    lex.Fail(t.line, "Frame Time", "'Time:'", t);
  const Token tt = lex.Next("Frame Time");
  bvh.frame_time = lex.ParseNumber(tt, "Frame Time");
  // Capture runs at tens to hundreds of frames per second; a frame time of hours (fuzzer
  // finding: 15408337 s) turned two frames into half a billion when resampled.
  if (!(bvh.frame_time > 0 && bvh.frame_time <= 1))
    lex.Fail(tt.line, "Frame Time", "seconds per frame in (0, 1]", tt);
  bvh.num_frames = static_cast<int>(frames);

  // Frame rows: one frame per line, exactly num_channels() numbers each.
  const std::string& s = lex.text();
  std::size_t p = lex.pos();
  int line = lex.line();
  while (p < s.size() && s[p] != '\n') {
    if (!std::isspace(static_cast<unsigned char>(s[p])))
      lex.Fail(line, "Frame Time", "a line break after the frame time", "more text");
    ++p;
  }
  // No more than the rest of the text can hold (each number takes at least two characters).
  bvh.values.reserve(std::min(static_cast<std::size_t>(bvh.num_frames) * std::max(channels, 1),
                              (s.size() - p) / 2 + 1));
  int frame = 0;
  while (p < s.size()) {
    // p is at a '\n' (or start); move to the next line.
    if (s[p] == '\n') {
      ++p;
      ++line;
    }
    const std::size_t eol = std::min(s.find('\n', p), s.size());
    const char* c = s.c_str() + p;
    const char* end = s.c_str() + eol;
    int count = 0;
    while (true) {
      while (c < end && std::isspace(static_cast<unsigned char>(*c))) ++c;
      if (c >= end) break;
      char* next = nullptr;
      const double v = std::strtod(c, &next);
      if (next == c || next > end ||
          (next < end && !std::isspace(static_cast<unsigned char>(*next))) || !std::isfinite(v)) {
        const char* stop = c;
        while (stop < end && !std::isspace(static_cast<unsigned char>(*stop))) ++stop;
        lex.Fail(line, "frame " + std::to_string(frame), "numbers",
                 "'" + std::string(c, stop) + "'");
      }
      if (frame < bvh.num_frames) bvh.values.push_back(v);
      ++count;
      c = next;
    }
    p = eol;
    if (count == 0) continue;
    if (frame >= bvh.num_frames) {
      spdlog::warn("{}:{}: more frame rows than 'Frames: {}'; ignoring the rest", source, line,
                   bvh.num_frames);
      break;
    }
    if (count != channels) {
      const bool last = s.find_first_not_of(" \t\r\n", eol) == std::string::npos;
      lex.Fail(line, "frame " + std::to_string(frame),
               std::to_string(channels) + " values (the CHANNELS declared in HIERARCHY)",
               std::to_string(count) + " values" +
                   (last && count < channels ? " (truncated file?)" : ""));
    }
    ++frame;
  }
  if (frame < bvh.num_frames)
    lex.Fail(line, "MOTION", std::to_string(bvh.num_frames) + " frames (as declared by 'Frames:')",
             std::to_string(frame) + " frames (truncated file?)");
  return bvh;
}

BvhMotion ReadBvh(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(path.string(), "", "a readable BVH file", "cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseBvh(ss.str(), path.string());
}

std::string FormatBvh(const BvhMotion& bvh) {
  SIMS_CHECK(!bvh.joints.empty() && bvh.joints[0].parent < 0);
  const int nc = bvh.num_channels();
  SIMS_CHECK(bvh.values.size() == static_cast<std::size_t>(bvh.num_frames) * nc);
  std::string out = "HIERARCHY\n";
  FormatJoint(bvh, 0, 0, &out);
  out += "MOTION\nFrames: " + std::to_string(bvh.num_frames) +
         "\nFrame Time: " + FormatNumber(bvh.frame_time) + "\n";
  out.reserve(out.size() + bvh.values.size() * 10);
  for (int f = 0; f < bvh.num_frames; ++f) {
    const double* row = bvh.frame(f);
    for (int k = 0; k < nc; ++k) {
      if (k) out += ' ';
      out += FormatNumber(row[k]);
    }
    out += '\n';
  }
  return out;
}

void WriteBvh(const BvhMotion& bvh, const std::filesystem::path& path) {
  WriteFileAtomic(path, FormatBvh(bvh));
}

Eigen::Quaterniond BvhLocalRotation(const BvhMotion& bvh, int j, int f) {
  const BvhJoint& jt = bvh.joints[j];
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  if (f < 0) return q;
  const double* row = bvh.frame(f) + jt.channel_start;
  for (std::size_t k = 0; k < jt.channels.size(); ++k) {
    const BvhChannel c = jt.channels[k];
    if (!IsRotation(c)) continue;
    q = q * Eigen::Quaterniond(
                Eigen::AngleAxisd(row[k] * M_PI / 180.0, Eigen::Vector3d::Unit(Axis(c))));
  }
  return q;
}

Eigen::Vector3d BvhLocalTranslation(const BvhMotion& bvh, int j, int f) {
  const BvhJoint& jt = bvh.joints[j];
  Eigen::Vector3d t = jt.offset;
  if (f < 0) return t;
  const double* row = bvh.frame(f) + jt.channel_start;
  for (std::size_t k = 0; k < jt.channels.size(); ++k)
    if (!IsRotation(jt.channels[k])) t[Axis(jt.channels[k])] += row[k];
  return t;
}

void BvhGlobalPose(const BvhMotion& bvh, int f, std::vector<Eigen::Quaterniond>* rot,
                   std::vector<Eigen::Vector3d>* pos) {
  const std::size_t n = bvh.joints.size();
  rot->resize(n);
  pos->resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const int p = bvh.joints[j].parent;
    const Eigen::Quaterniond r = BvhLocalRotation(bvh, static_cast<int>(j), f);
    const Eigen::Vector3d t = BvhLocalTranslation(bvh, static_cast<int>(j), f);
    if (p < 0) {
      (*rot)[j] = r;
      (*pos)[j] = t;
    } else {
      (*pos)[j] = (*pos)[p] + (*rot)[p] * t;
      (*rot)[j] = (*rot)[p] * r;
    }
  }
}

}  // namespace sims::motion
