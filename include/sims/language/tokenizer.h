// CLIP-compatible byte-level BPE tokenizer (the `SimpleTokenizer` of OpenAI CLIP).
//
// Pipeline, as CLIP does it: HTML-unescape twice, collapse whitespace, lower-case, split with
// CLIP's pattern (<|startoftext|>, <|endoftext|>, 's 't 're 've 'm 'll 'd, runs of letters,
// single digits, runs of other non-space characters), map every UTF-8 byte of a piece to its
// printable stand-in, apply the 48 894 merges of bpe_simple_vocab_16e6 with `</w>` marking the end
// of a word, look the symbols up in the 49 408-entry vocabulary. SOT = 49406, EOT = 49407,
// context length 77 (truncation keeps SOT, the first 75 tokens and EOT; padding is 0).
//
// Differences from Python CLIP, all outside plain English text: ftfy's mojibake repair and NFC
// normalisation are not done; Unicode letter/number/whitespace classes and lower-casing use
// built-in tables that cover Latin, Greek, Cyrillic, Armenian, Hebrew, Arabic, Indic, Thai,
// Georgian, Hangul, kana and CJK; only common named HTML entities are decoded (all numeric ones).
//
// The merges come from `data/language/clip_bpe.txt` (written by `prepare_assets`, same text as
// CLIP's bpe_simple_vocab_16e6.txt: a header line, then one "first second" merge per line).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace sims::language {

/// Byte-level BPE tokenizer with CLIP's vocabulary layout; cheap to copy (shared, immutable).
class ClipTokenizer {
 public:
  /// CLIP's context length.
  static constexpr int kContextLength = 77;
  /// Number of merges CLIP uses from its merges file.
  static constexpr int kClipMerges = 49152 - 256 - 2;

  /// Builds from merges text (first line is a header and is skipped); uses at most `max_merges`
  /// merges (fewer only for small test vocabularies). `source` names the origin in errors.
  static ClipTokenizer FromMergesText(const std::string& text, const std::string& source,
                                      int max_merges = kClipMerges);
  /// Loads a merges file; throws sims::Error naming the file if missing or malformed.
  static ClipTokenizer FromFile(const std::filesystem::path& path);
  /// The default vocabulary path: DataPath("language/clip_bpe.txt").
  static std::filesystem::path DefaultPath();
  /// Loads DefaultPath(); the error tells the user to run `prepare_assets` when it is missing.
  static ClipTokenizer LoadDefault();

  /// Token ids of `text` without SOT/EOT.
  std::vector<int> Encode(const std::string& text) const;
  /// [SOT, ids..., EOT] truncated to `context_length` (last kept id replaced by EOT) and padded
  /// with 0 to exactly `context_length` entries, as clip.tokenize(truncate=True) does.
  std::vector<int> EncodeForClip(const std::string& text,
                                 int context_length = kContextLength) const;
  /// Readable BPE pieces of one pre-token ("sluggishly" -> {"slu", "gg", "ish", "ly</w>"}).
  std::vector<std::string> Pieces(const std::string& word) const;
  /// Text of ids: symbols joined, bytes restored, "</w>" turned into spaces.
  std::string Decode(const std::vector<int>& ids) const;

  /// Start-of-text id (49406 with CLIP's vocabulary).
  int sot() const;
  /// End-of-text id (49407 with CLIP's vocabulary).
  int eot() const;
  /// Vocabulary size (49408 with CLIP's vocabulary).
  int vocab_size() const;
  /// Vocabulary string of an id (byte stand-ins, with "</w>" where it ends a word).
  const std::string& Symbol(int id) const;

  /// CLIP's text cleanup: HTML-unescape twice, collapse whitespace, trim, lower-case.
  static std::string CleanText(const std::string& text);
  /// CLIP's pre-tokenisation of already cleaned text into words, digits and punctuation runs.
  static std::vector<std::string> PreTokenize(const std::string& cleaned);
  /// CleanText followed by PreTokenize.
  static std::vector<std::string> Words(const std::string& text);

 private:
  struct Impl;
  explicit ClipTokenizer(std::shared_ptr<const Impl> impl);
  std::vector<std::string> Bpe(const std::string& byte_encoded) const;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace sims::language
