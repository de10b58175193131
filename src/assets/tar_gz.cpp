#include "assets/tar_gz.h"

#include <algorithm>
#include <array>
#include <cstring>

#include <zlib.h>

#include "sims/core/error.h"

namespace sims::assets::internal {

namespace {

constexpr std::size_t kBlock = 512;

gzFile Gz(void* p) { return static_cast<gzFile>(p); }

// Tar numeric fields are octal text, or base-256 when the top bit of the first byte is set.
uint64_t ParseNumber(const char* field, std::size_t len) {
  const auto* u = reinterpret_cast<const unsigned char*>(field);
  if (len > 0 && (u[0] & 0x80)) {
    uint64_t v = u[0] & 0x7f;
    for (std::size_t i = 1; i < len; ++i) v = (v << 8) | u[i];
    return v;
  }
  uint64_t v = 0;
  for (std::size_t i = 0; i < len; ++i) {
    const char c = field[i];
    if (c == ' ' || c == '\0') {
      if (v != 0) break;
      continue;
    }
    if (c < '0' || c > '7') break;
    v = v * 8 + static_cast<uint64_t>(c - '0');
  }
  return v;
}

std::string FieldString(const char* field, std::size_t len) {
  return std::string(field, strnlen(field, len));
}

// Extracts "path=..." from a pax extended header body ("<len> key=value\n" records).
std::string PaxPath(const std::string& body) {
  std::size_t pos = 0;
  while (pos < body.size()) {
    const std::size_t space = body.find(' ', pos);
    if (space == std::string::npos) break;
    const uint64_t len = std::strtoull(body.c_str() + pos, nullptr, 10);
    if (len == 0 || pos + len > body.size()) break;
    const std::string record = body.substr(space + 1, pos + len - space - 2);
    if (record.rfind("path=", 0) == 0) return record.substr(5);
    pos += len;
  }
  return {};
}

}  // namespace

TarGzReader::TarGzReader(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  file_size_ = std::filesystem::file_size(path, ec);
  if (ec) ThrowInputError(path.string(), "", "an existing .tgz archive", "file not found");
  gz_ = gzopen(path.c_str(), "rb");
  if (gz_ == nullptr) ThrowInputError(path.string(), "", "a readable .tgz archive", "cannot open");
  gzbuffer(Gz(gz_), 1 << 18);
}

TarGzReader::~TarGzReader() {
  if (gz_ != nullptr) gzclose(Gz(gz_));
}

uint64_t TarGzReader::CompressedOffset() const {
  const z_off_t off = gzoffset(Gz(gz_));
  return off < 0 ? 0 : static_cast<uint64_t>(off);
}

void TarGzReader::ReadExact(char* out, std::size_t n, const char* what) {
  std::size_t done = 0;
  while (done < n) {
    const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(n - done, 1u << 30));
    const int got = gzread(Gz(gz_), out + done, chunk);
    if (got <= 0) {
      int err = Z_OK;
      const char* msg = gzerror(Gz(gz_), &err);
      ThrowInputError(path_.string(), what, "a complete gzip-compressed tar archive",
                      err != Z_OK && msg ? msg : "unexpected end of data");
    }
    done += static_cast<std::size_t>(got);
  }
}

void TarGzReader::SkipBytes(uint64_t n) {
  std::array<char, 1 << 16> scratch;
  while (n > 0) {
    const std::size_t chunk = static_cast<std::size_t>(std::min<uint64_t>(n, scratch.size()));
    ReadExact(scratch.data(), chunk, "entry data");
    n -= chunk;
  }
}

bool TarGzReader::Next(TarEntry* entry) {
  SkipBytes(remaining_ + padding_);
  remaining_ = padding_ = 0;
  std::string long_name;
  std::array<char, kBlock> header;
  while (true) {
    const int got = gzread(Gz(gz_), header.data(), kBlock);
    if (got == 0) return false;  // archive ended without the zero blocks: accept
    if (got != static_cast<int>(kBlock))
      ThrowInputError(path_.string(), "tar header", "512-byte tar headers", "truncated archive");
    if (std::all_of(header.begin(), header.end(), [](char c) { return c == 0; })) return false;

    const uint64_t size = ParseNumber(&header[124], 12);
    const uint64_t pad = (kBlock - size % kBlock) % kBlock;
    const char type = header[156];
    if (type == 'L' || type == 'x') {  // GNU long name / pax header: body names the next entry
      std::string body(static_cast<std::size_t>(size), '\0');
      ReadExact(body.data(), body.size(), "tar extended header");
      SkipBytes(pad);
      long_name = type == 'L' ? FieldString(body.data(), body.size()) : PaxPath(body);
      continue;
    }
    if (type != '0' && type != '\0' && type != '7') {  // directories, links, global pax, ...
      SkipBytes(size + pad);
      long_name.clear();
      continue;
    }
    std::string name = FieldString(&header[0], 100);
    if (std::memcmp(&header[257], "ustar", 5) == 0) {
      const std::string prefix = FieldString(&header[345], 155);
      if (!prefix.empty()) name = prefix + "/" + name;
    }
    if (!long_name.empty()) name = long_name;
    entry->name = name;
    entry->size = size;
    remaining_ = size;
    padding_ = pad;
    return true;
  }
}

std::size_t TarGzReader::Read(char* out, std::size_t n) {
  const std::size_t take = static_cast<std::size_t>(std::min<uint64_t>(n, remaining_));
  if (take == 0) return 0;
  ReadExact(out, take, "entry data");
  remaining_ -= take;
  return take;
}

std::string TarGzReader::ReadAll() {
  std::string s(static_cast<std::size_t>(remaining_), '\0');
  ReadExact(s.data(), s.size(), "entry data");
  remaining_ = 0;
  return s;
}

TarEntryStreamBuf::TarEntryStreamBuf(TarGzReader* reader, std::size_t buffer_bytes)
    : reader_(reader), buffer_(buffer_bytes) {
  setg(buffer_.data(), buffer_.data(), buffer_.data());
}

TarEntryStreamBuf::int_type TarEntryStreamBuf::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  const std::size_t got = reader_->Read(buffer_.data(), buffer_.size());
  if (got == 0) return traits_type::eof();
  setg(buffer_.data(), buffer_.data(), buffer_.data() + got);
  return traits_type::to_int_type(*gptr());
}

TarEntry SeekEntry(TarGzReader* reader, const std::string& suffix,
                   const std::filesystem::path& archive) {
  TarEntry e;
  while (reader->Next(&e)) {
    if (e.name.size() >= suffix.size() &&
        e.name.compare(e.name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return e;
  }
  ThrowInputError(archive.string(), suffix, "a member named *" + suffix + " in the archive",
                  "not found (is this the right npm package version?)");
}

}  // namespace sims::assets::internal
