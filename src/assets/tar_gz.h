// Streaming reader for .tgz archives (npm package tarballs): zlib inflates, we walk the ustar
// headers ourselves, so a 300 MB member can be parsed without ever touching the disk.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <streambuf>
#include <string>
#include <vector>

namespace sims::assets::internal {

/// One regular file inside the archive.
struct TarEntry {
  std::string name;   ///< Path inside the archive ("package/...").
  uint64_t size = 0;  ///< Bytes of content.
};

/// Sequential reader: Next() moves to the following regular file, Read() returns its bytes.
class TarGzReader {
 public:
  /// Opens `path`; throws sims::Error naming the file if it cannot be opened.
  explicit TarGzReader(const std::filesystem::path& path);
  ~TarGzReader();
  TarGzReader(const TarGzReader&) = delete;
  TarGzReader& operator=(const TarGzReader&) = delete;

  /// Advances to the next regular file (skipping the rest of the current one); false at the end.
  bool Next(TarEntry* entry);
  /// Reads up to `n` bytes of the current file; returns 0 at its end.
  std::size_t Read(char* out, std::size_t n);
  /// Reads the whole current file into a string.
  std::string ReadAll();
  /// Compressed bytes consumed so far (for progress reports).
  uint64_t CompressedOffset() const;
  /// Size of the archive file.
  uint64_t CompressedSize() const { return file_size_; }

 private:
  void ReadExact(char* out, std::size_t n, const char* what);
  void SkipBytes(uint64_t n);

  std::filesystem::path path_;
  void* gz_ = nullptr;  // gzFile, kept opaque so zlib.h stays out of this header
  uint64_t file_size_ = 0;
  uint64_t remaining_ = 0;  // unread bytes of the current entry
  uint64_t padding_ = 0;    // zero padding after the current entry
};

/// A std::streambuf over the current entry of a TarGzReader (for std::istream consumers).
class TarEntryStreamBuf : public std::streambuf {
 public:
  /// `reader` must outlive the buffer and stay on the same entry while it is read.
  explicit TarEntryStreamBuf(TarGzReader* reader, std::size_t buffer_bytes = 1 << 20);

 protected:
  int_type underflow() override;

 private:
  TarGzReader* reader_;
  std::vector<char> buffer_;
};

/// Finds the first regular file whose name ends with `suffix` and leaves the reader on it;
/// throws sims::Error naming the archive and `suffix` when there is none.
TarEntry SeekEntry(TarGzReader* reader, const std::string& suffix,
                   const std::filesystem::path& archive);

}  // namespace sims::assets::internal
