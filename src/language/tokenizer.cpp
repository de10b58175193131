#include "sims/language/tokenizer.h"

#include <fstream>
#include <sstream>
#include <unordered_map>

#include "language/unicode.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"

namespace sims::language {

using internal::DecodeUtf8;

namespace {

constexpr const char* kEndOfWord = "</w>";
constexpr const char* kSotText = "<|startoftext|>";
constexpr const char* kEotText = "<|endoftext|>";

// CLIP's bytes_to_unicode(): printable bytes stand for themselves, the other 68 bytes map to
// U+0100.. in increasing order. The returned order is the vocabulary order of the 256 base symbols.
std::vector<std::pair<int, char32_t>> ByteStandIns() {
  std::vector<std::pair<int, char32_t>> table;
  std::vector<bool> printable(256, false);
  auto add_range = [&](int lo, int hi) {
    for (int b = lo; b <= hi; ++b) {
      printable[b] = true;
      table.emplace_back(b, static_cast<char32_t>(b));
    }
  };
  add_range('!', '~');
  add_range(0xA1, 0xAC);
  add_range(0xAE, 0xFF);
  int n = 0;
  for (int b = 0; b < 256; ++b) {
    if (!printable[b]) table.emplace_back(b, static_cast<char32_t>(256 + n++));
  }
  return table;
}

}  // namespace

struct ClipTokenizer::Impl {
  std::vector<std::string> byte_encoder;           // byte -> stand-in (UTF-8)
  std::unordered_map<char32_t, int> byte_decoder;  // stand-in -> byte
  std::vector<std::string> vocab;                  // id -> symbol
  std::unordered_map<std::string, int> encoder;    // symbol -> id
  std::unordered_map<std::string, int> ranks;      // "first second" -> merge rank
  int sot = 0, eot = 0;
};

ClipTokenizer::ClipTokenizer(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

ClipTokenizer ClipTokenizer::FromMergesText(const std::string& text, const std::string& source,
                                            int max_merges) {
  auto impl = std::make_shared<Impl>();
  impl->byte_encoder.resize(256);
  for (const auto& [byte, cp] : ByteStandIns()) {
    std::string s;
    AppendUtf8(cp, &s);
    impl->byte_encoder[byte] = s;
    impl->byte_decoder[cp] = byte;
    impl->vocab.push_back(s);
  }
  for (int i = 0; i < 256; ++i) impl->vocab.push_back(impl->vocab[i] + kEndOfWord);

  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // header ("#version: 0.2")
  int line_no = 1;
  while (static_cast<int>(impl->ranks.size()) < max_merges && std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;
    const std::size_t space = line.find(' ');
    if (space == std::string::npos || space == 0 || space + 1 == line.size() ||
        line.find(' ', space + 1) != std::string::npos)
      ThrowInputError(source, "line " + std::to_string(line_no), "a BPE merge \"<first> <second>\"",
                      line.substr(0, 60));
    const int rank = static_cast<int>(impl->ranks.size());
    if (!impl->ranks.emplace(line, rank).second)
      ThrowInputError(source, "line " + std::to_string(line_no), "each merge listed once",
                      "duplicate merge " + line);
    impl->vocab.push_back(line.substr(0, space) + line.substr(space + 1));
  }
  impl->sot = static_cast<int>(impl->vocab.size());
  impl->vocab.push_back(kSotText);
  impl->eot = static_cast<int>(impl->vocab.size());
  impl->vocab.push_back(kEotText);
  for (int id = 0; id < static_cast<int>(impl->vocab.size()); ++id)
    impl->encoder.emplace(impl->vocab[id], id);
  return ClipTokenizer(std::move(impl));
}

ClipTokenizer ClipTokenizer::FromFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    ThrowInputError(path.string(), "", "the CLIP BPE merges file",
                    "file not found (run `prepare_assets --only clip_bpe` after cmake/setup.sh)");
  std::stringstream ss;
  ss << in.rdbuf();
  ClipTokenizer tok = FromMergesText(ss.str(), path.string());
  const int merges = tok.vocab_size() - 512 - 2;
  if (merges != kClipMerges)
    ThrowInputError(path.string(), "merges", std::to_string(kClipMerges) + " merge lines",
                    std::to_string(merges));
  return tok;
}

std::filesystem::path ClipTokenizer::DefaultPath() { return DataPath("language/clip_bpe.txt"); }

ClipTokenizer ClipTokenizer::LoadDefault() { return FromFile(DefaultPath()); }

int ClipTokenizer::sot() const { return impl_->sot; }
int ClipTokenizer::eot() const { return impl_->eot; }
int ClipTokenizer::vocab_size() const { return static_cast<int>(impl_->vocab.size()); }

const std::string& ClipTokenizer::Symbol(int id) const {
  SIMS_CHECK(id >= 0 && id < vocab_size());
  return impl_->vocab[static_cast<std::size_t>(id)];
}

std::string ClipTokenizer::CleanText(const std::string& text) {
  const std::string unescaped = internal::HtmlUnescape(internal::HtmlUnescape(text));
  const std::u32string cps = DecodeUtf8(unescaped);
  std::u32string collapsed;
  collapsed.reserve(cps.size());
  bool pending_space = false;
  for (char32_t c : cps) {
    if (internal::IsSpace(c)) {
      pending_space = !collapsed.empty();
      continue;
    }
    if (pending_space) collapsed.push_back(' ');
    pending_space = false;
    internal::AppendLower(c, &collapsed);
  }
  return internal::EncodeUtf8(collapsed);
}

std::vector<std::string> ClipTokenizer::PreTokenize(const std::string& cleaned) {
  using internal::IsLetter;
  using internal::IsNumber;
  using internal::IsSpace;
  const std::u32string s = DecodeUtf8(cleaned);
  const std::u32string sot = DecodeUtf8(kSotText), eot = DecodeUtf8(kEotText);
  std::vector<std::string> tokens;
  const std::size_t n = s.size();
  std::size_t i = 0;
  auto emit = [&](std::size_t len) {
    tokens.push_back(internal::EncodeUtf8(s.substr(i, len)));
    i += len;
  };
  while (i < n) {
    const char32_t c = s[i];
    if (s.compare(i, sot.size(), sot) == 0) {
      emit(sot.size());
    } else if (s.compare(i, eot.size(), eot) == 0) {
      emit(eot.size());
    } else if (c == '\'' && i + 1 < n &&
               (s[i + 1] == 's' || s[i + 1] == 't' || s[i + 1] == 'm' || s[i + 1] == 'd')) {
      emit(2);
    } else if (c == '\'' && i + 2 < n &&
               ((s[i + 1] == 'r' && s[i + 2] == 'e') || (s[i + 1] == 'v' && s[i + 2] == 'e') ||
                (s[i + 1] == 'l' && s[i + 2] == 'l'))) {
      emit(3);
    } else if (IsLetter(c)) {
      std::size_t j = i;
      while (j < n && IsLetter(s[j])) ++j;
      emit(j - i);
    } else if (IsNumber(c)) {
      emit(1);
    } else if (!IsSpace(c)) {
      std::size_t j = i;
      while (j < n && !IsSpace(s[j]) && !IsLetter(s[j]) && !IsNumber(s[j])) ++j;
      emit(j - i);
    } else {
      ++i;
    }
  }
  return tokens;
}

std::vector<std::string> ClipTokenizer::Words(const std::string& text) {
  return PreTokenize(CleanText(text));
}

std::vector<std::string> ClipTokenizer::Bpe(const std::string& token) const {
  // Symbols start as the byte stand-ins of the token's UTF-8 bytes; the last one carries </w>.
  std::vector<std::string> word;
  word.reserve(token.size());
  for (unsigned char b : token) word.push_back(impl_->byte_encoder[b]);
  if (word.empty()) return word;
  word.back() += kEndOfWord;
  if (word.size() == 1) return word;

  std::string key;
  while (true) {
    int best_rank = -1;
    std::size_t best_i = 0;
    for (std::size_t i = 0; i + 1 < word.size(); ++i) {
      key.assign(word[i]).append(" ").append(word[i + 1]);
      const auto it = impl_->ranks.find(key);
      if (it != impl_->ranks.end() && (best_rank < 0 || it->second < best_rank)) {
        best_rank = it->second;
        best_i = i;
      }
    }
    if (best_rank < 0) break;
    // Merge every non-overlapping occurrence of the best pair, left to right (as CLIP does).
    const std::string first = word[best_i], second = word[best_i + 1];
    std::vector<std::string> merged;
    merged.reserve(word.size());
    for (std::size_t i = 0; i < word.size();) {
      if (i + 1 < word.size() && word[i] == first && word[i + 1] == second) {
        merged.push_back(first + second);
        i += 2;
      } else {
        merged.push_back(std::move(word[i]));
        i += 1;
      }
    }
    word = std::move(merged);
    if (word.size() == 1) break;
  }
  return word;
}

std::vector<int> ClipTokenizer::Encode(const std::string& text) const {
  std::vector<int> ids;
  for (const std::string& token : Words(text)) {
    if (token == kSotText) {
      ids.push_back(impl_->sot);
      continue;
    }
    if (token == kEotText) {
      ids.push_back(impl_->eot);
      continue;
    }
    for (const std::string& symbol : Bpe(token)) {
      const auto it = impl_->encoder.find(symbol);
      SIMS_CHECK_MSG(it != impl_->encoder.end(), "BPE symbol missing from vocabulary: " + symbol);
      ids.push_back(it->second);
    }
  }
  return ids;
}

std::vector<int> ClipTokenizer::EncodeForClip(const std::string& text, int context_length) const {
  SIMS_CHECK(context_length >= 2);
  std::vector<int> ids;
  ids.push_back(impl_->sot);
  for (int id : Encode(text)) ids.push_back(id);
  ids.push_back(impl_->eot);
  if (static_cast<int>(ids.size()) > context_length) {
    ids.resize(static_cast<std::size_t>(context_length));
    ids.back() = impl_->eot;
  }
  ids.resize(static_cast<std::size_t>(context_length), 0);
  return ids;
}

std::vector<std::string> ClipTokenizer::Pieces(const std::string& word) const {
  std::vector<std::string> pieces;
  for (const std::string& symbol : Bpe(word)) {
    std::string readable;
    std::string body = symbol;
    const bool eow = body.size() >= 4 && body.compare(body.size() - 4, 4, kEndOfWord) == 0;
    if (eow) body.resize(body.size() - 4);
    for (char32_t cp : DecodeUtf8(body)) {
      const auto it = impl_->byte_decoder.find(cp);
      if (it != impl_->byte_decoder.end()) readable.push_back(static_cast<char>(it->second));
    }
    if (eow) readable += kEndOfWord;
    pieces.push_back(std::move(readable));
  }
  return pieces;
}

std::string ClipTokenizer::Decode(const std::vector<int>& ids) const {
  std::string joined;
  for (int id : ids) {
    if (id < 0 || id >= vocab_size()) continue;
    joined += impl_->vocab[static_cast<std::size_t>(id)];
  }
  std::string bytes;
  for (char32_t cp : DecodeUtf8(joined)) {
    const auto it = impl_->byte_decoder.find(cp);
    if (it != impl_->byte_decoder.end()) bytes.push_back(static_cast<char>(it->second));
  }
  // Invalid UTF-8 (a cut multi-byte character) becomes U+FFFD, as errors="replace" does.
  std::string text = internal::EncodeUtf8(DecodeUtf8(bytes));
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    if (text.compare(i, 4, kEndOfWord) == 0) {
      out.push_back(' ');
      i += 4;
    } else {
      out.push_back(text[i++]);
    }
  }
  return out;
}

}  // namespace sims::language
