#include "language/unicode.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace sims::language {

void AppendUtf8(char32_t cp, std::string* out) {
  if (cp < 0x80) {
    out->push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out->push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out->push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out->push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

}  // namespace sims::language

namespace sims::language::internal {

namespace {

struct Range {
  char32_t lo, hi;
};

// Sorted, non-overlapping. Approximates \p{L} for the scripts named in tokenizer.h.
constexpr Range kLetters[] = {
    {0x41, 0x5A},       {0x61, 0x7A},     {0xAA, 0xAA},     {0xB5, 0xB5},       {0xBA, 0xBA},
    {0xC0, 0xD6},       {0xD8, 0xF6},     {0xF8, 0x2C1},    {0x2C6, 0x2D1},     {0x2E0, 0x2E4},
    {0x2EC, 0x2EC},     {0x2EE, 0x2EE},   {0x370, 0x374},   {0x376, 0x377},     {0x37A, 0x37D},
    {0x37F, 0x37F},     {0x386, 0x386},   {0x388, 0x38A},   {0x38C, 0x38C},     {0x38E, 0x3A1},
    {0x3A3, 0x3F5},     {0x3F7, 0x481},   {0x48A, 0x52F},   {0x531, 0x556},     {0x559, 0x559},
    {0x560, 0x588},     {0x5D0, 0x5EA},   {0x5EF, 0x5F2},   {0x620, 0x64A},     {0x66E, 0x66F},
    {0x671, 0x6D3},     {0x6D5, 0x6D5},   {0x6E5, 0x6E6},   {0x6EE, 0x6EF},     {0x6FA, 0x6FC},
    {0x6FF, 0x6FF},     {0x904, 0x939},   {0x93D, 0x93D},   {0x950, 0x950},     {0x958, 0x961},
    {0x971, 0x980},     {0x985, 0x9B9},   {0xE01, 0xE30},   {0xE32, 0xE33},     {0xE40, 0xE46},
    {0x10A0, 0x10FA},   {0x10FC, 0x10FF}, {0x1100, 0x11FF}, {0x1E00, 0x1F15},   {0x1F18, 0x1F1D},
    {0x1F20, 0x1F45},   {0x1F48, 0x1F4D}, {0x1F50, 0x1F57}, {0x1F59, 0x1F59},   {0x1F5B, 0x1F5B},
    {0x1F5D, 0x1F5D},   {0x1F5F, 0x1F7D}, {0x1F80, 0x1FB4}, {0x1FB6, 0x1FBC},   {0x1FBE, 0x1FBE},
    {0x1FC2, 0x1FC4},   {0x1FC6, 0x1FCC}, {0x1FD0, 0x1FD3}, {0x1FD6, 0x1FDB},   {0x1FE0, 0x1FEC},
    {0x1FF2, 0x1FF4},   {0x1FF6, 0x1FFC}, {0x2071, 0x2071}, {0x207F, 0x207F},   {0x2090, 0x209C},
    {0x2102, 0x2102},   {0x2107, 0x2107}, {0x210A, 0x2113}, {0x2115, 0x2115},   {0x2119, 0x211D},
    {0x2124, 0x2124},   {0x2126, 0x2126}, {0x2128, 0x2128}, {0x212A, 0x212D},   {0x212F, 0x2139},
    {0x213C, 0x213F},   {0x2145, 0x2149}, {0x214E, 0x214E}, {0x2183, 0x2184},   {0x2C00, 0x2CE4},
    {0x3005, 0x3006},   {0x3031, 0x3035}, {0x303B, 0x303C}, {0x3041, 0x3096},   {0x309D, 0x309F},
    {0x30A1, 0x30FA},   {0x30FC, 0x30FF}, {0x3105, 0x312F}, {0x3131, 0x318E},   {0x31A0, 0x31BF},
    {0x31F0, 0x31FF},   {0x3400, 0x4DBF}, {0x4E00, 0x9FFF}, {0xA000, 0xA48C},   {0xA640, 0xA66E},
    {0xA680, 0xA69D},   {0xA722, 0xA788}, {0xA78B, 0xA7CA}, {0xAC00, 0xD7A3},   {0xF900, 0xFA6D},
    {0xFB00, 0xFB06},   {0xFB1D, 0xFB1D}, {0xFB1F, 0xFB28}, {0xFB2A, 0xFBB1},   {0xFE70, 0xFEFC},
    {0xFF21, 0xFF3A},   {0xFF41, 0xFF5A}, {0xFF66, 0xFFBE}, {0x1D400, 0x1D7CB}, {0x20000, 0x2A6DF},
    {0x2A700, 0x2EBE0},
};

constexpr Range kNumbers[] = {
    {0x30, 0x39},     {0xB2, 0xB3},     {0xB9, 0xB9},       {0xBC, 0xBE},     {0x660, 0x669},
    {0x6F0, 0x6F9},   {0x966, 0x96F},   {0x9E6, 0x9EF},     {0xE50, 0xE59},   {0x2070, 0x2070},
    {0x2074, 0x2079}, {0x2080, 0x2089}, {0x2150, 0x2182},   {0x2185, 0x2189}, {0x2460, 0x249B},
    {0x24EA, 0x24FF}, {0x2776, 0x2793}, {0x3007, 0x3007},   {0x3021, 0x3029}, {0x3038, 0x303A},
    {0x3192, 0x3195}, {0x3220, 0x3229}, {0x3248, 0x324F},   {0x3251, 0x325F}, {0x3280, 0x3289},
    {0x32B1, 0x32BF}, {0xFF10, 0xFF19}, {0x1D7CE, 0x1D7FF},
};

template <std::size_t N>
bool InRanges(const Range (&ranges)[N], char32_t cp) {
  const Range* end = ranges + N;
  const Range* it =
      std::upper_bound(ranges, end, cp, [](char32_t c, const Range& r) { return c < r.lo; });
  if (it == ranges) return false;
  --it;
  return cp <= it->hi;
}

// Windows-1252 meanings of numeric references 0x80..0x9F, as html.unescape applies them.
constexpr char32_t kCp1252[32] = {0x20AC, 0x81,   0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021,
                                  0x02C6, 0x2030, 0x0160, 0x2039, 0x0152, 0x8D,   0x017D, 0x8F,
                                  0x90,   0x2018, 0x2019, 0x201C, 0x201D, 0x2022, 0x2013, 0x2014,
                                  0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0x9D,   0x017E, 0x0178};

struct Entity {
  const char* name;
  char32_t cp;
  bool legacy;  // accepted without the trailing ';'
};
constexpr Entity kEntities[] = {
    {"amp", '&', true},        {"lt", '<', true},        {"gt", '>', true},
    {"quot", '"', true},       {"apos", '\'', false},    {"nbsp", 0xA0, true},
    {"copy", 0xA9, true},      {"reg", 0xAE, true},      {"trade", 0x2122, false},
    {"hellip", 0x2026, false}, {"mdash", 0x2014, false}, {"ndash", 0x2013, false},
    {"lsquo", 0x2018, false},  {"rsquo", 0x2019, false}, {"ldquo", 0x201C, false},
    {"rdquo", 0x201D, false},  {"laquo", 0xAB, true},    {"raquo", 0xBB, true},
    {"deg", 0xB0, true},       {"eacute", 0xE9, true},   {"egrave", 0xE8, true},
    {"agrave", 0xE0, true},    {"aacute", 0xE1, true},   {"ccedil", 0xE7, true},
    {"uuml", 0xFC, true},      {"ouml", 0xF6, true},     {"auml", 0xE4, true},
    {"szlig", 0xDF, true},     {"ntilde", 0xF1, true},   {"times", 0xD7, true},
    {"divide", 0xF7, true},    {"middot", 0xB7, true},   {"bull", 0x2022, false},
    {"euro", 0x20AC, false},   {"pound", 0xA3, true},    {"yen", 0xA5, true},
    {"cent", 0xA2, true},      {"sect", 0xA7, true},     {"para", 0xB6, true},
    {"iexcl", 0xA1, true},     {"iquest", 0xBF, true},   {"shy", 0xAD, true},
};

char32_t SanitizeCharRef(unsigned long v) {
  if (v >= 0x80 && v <= 0x9F) return kCp1252[v - 0x80];
  if (v == 0 || (v >= 0xD800 && v <= 0xDFFF) || v > 0x10FFFF) return 0xFFFD;
  return static_cast<char32_t>(v);
}

}  // namespace

std::u32string DecodeUtf8(const std::string& s) {
  std::u32string out;
  out.reserve(s.size());
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = p[i];
    int len = 0;
    char32_t cp = 0;
    if (c < 0x80) {
      len = 1;
      cp = c;
    } else if ((c & 0xE0) == 0xC0) {
      len = 2;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4;
      cp = c & 0x07;
    }
    bool ok = len > 0 && i + static_cast<std::size_t>(len) <= n;
    for (int k = 1; ok && k < len; ++k) {
      if ((p[i + k] & 0xC0) != 0x80) ok = false;
      cp = (cp << 6) | (p[i + k] & 0x3F);
    }
    if (!ok) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    out.push_back(cp);
    i += static_cast<std::size_t>(len);
  }
  return out;
}

std::string EncodeUtf8(const std::u32string& s) {
  std::string out;
  out.reserve(s.size());
  for (char32_t cp : s) AppendUtf8(cp, &out);
  return out;
}

bool IsLetter(char32_t cp) { return InRanges(kLetters, cp); }
bool IsNumber(char32_t cp) { return InRanges(kNumbers, cp); }

bool IsSpace(char32_t cp) {
  return (cp >= 0x09 && cp <= 0x0D) || (cp >= 0x1C && cp <= 0x20) || cp == 0x85 || cp == 0xA0 ||
         cp == 0x1680 || (cp >= 0x2000 && cp <= 0x200A) || cp == 0x2028 || cp == 0x2029 ||
         cp == 0x202F || cp == 0x205F || cp == 0x3000;
}

void AppendLower(char32_t c, std::u32string* out) {
  auto even_up = [c](char32_t lo, char32_t hi) { return c >= lo && c <= hi && (c % 2) == 0; };
  auto odd_up = [c](char32_t lo, char32_t hi) { return c >= lo && c <= hi && (c % 2) == 1; };
  char32_t r = c;
  if (c < 0x80) {
    if (c >= 'A' && c <= 'Z') r = c + 32;
  } else if (c == 0x130) {  // 'İ'.lower() is "i" + combining dot above
    out->push_back('i');
    out->push_back(0x307);
    return;
  } else if (c >= 0xC0 && c <= 0xDE && c != 0xD7) {
    r = c + 32;
  } else if (even_up(0x100, 0x137) || odd_up(0x139, 0x148) || even_up(0x14A, 0x177) ||
             odd_up(0x179, 0x17E) || odd_up(0x1CD, 0x1DC) || even_up(0x1DE, 0x1EF) ||
             even_up(0x1F8, 0x21F) || even_up(0x222, 0x233) || even_up(0x246, 0x24F) ||
             even_up(0x3D8, 0x3EF) || even_up(0x460, 0x481) || even_up(0x48A, 0x4BF) ||
             odd_up(0x4C1, 0x4CE) || even_up(0x4D0, 0x52F) || even_up(0x1E00, 0x1E95) ||
             even_up(0x1EA0, 0x1EFF)) {
    r = c + 1;
  } else if (c == 0x178) {
    r = 0xFF;
  } else if (c == 0x386) {
    r = 0x3AC;
  } else if (c >= 0x388 && c <= 0x38A) {
    r = c + 37;
  } else if (c == 0x38C) {
    r = 0x3CC;
  } else if (c >= 0x38E && c <= 0x38F) {
    r = c + 63;
  } else if ((c >= 0x391 && c <= 0x3A1) || (c >= 0x3A3 && c <= 0x3AB) ||
             (c >= 0x410 && c <= 0x42F) || (c >= 0xFF21 && c <= 0xFF3A)) {
    r = c + 32;
  } else if (c >= 0x400 && c <= 0x40F) {
    r = c + 80;
  } else if (c == 0x4C0) {
    r = 0x4CF;
  } else if (c >= 0x531 && c <= 0x556) {
    r = c + 48;
  } else if (c >= 0x10A0 && c <= 0x10C5) {
    r = c + 0x1C60;
  } else if (c == 0x1E9E) {
    r = 0xDF;
  } else if (c >= 0x2160 && c <= 0x216F) {
    r = c + 16;
  } else if (c >= 0x24B6 && c <= 0x24CF) {
    r = c + 26;
  } else if (c >= 0x2C00 && c <= 0x2C2F) {
    r = c + 48;
  }
  out->push_back(r);
}

std::string HtmlUnescape(const std::string& s) {
  if (s.find('&') == std::string::npos) return s;
  std::string out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] != '&') {
      out.push_back(s[i++]);
      continue;
    }
    // Numeric reference: &#123; or &#x7b; (';' optional, as in Python).
    if (i + 2 < s.size() && s[i + 1] == '#') {
      const bool hex = s[i + 2] == 'x' || s[i + 2] == 'X';
      std::size_t j = i + (hex ? 3 : 2);
      const std::size_t start = j;
      while (j < s.size() && (hex ? std::isxdigit(static_cast<unsigned char>(s[j]))
                                  : std::isdigit(static_cast<unsigned char>(s[j]))))
        ++j;
      if (j > start) {
        const std::string digits = s.substr(start, std::min<std::size_t>(j - start, 10));
        const unsigned long v =
            j - start > 8 ? 0x110000UL : std::strtoul(digits.c_str(), nullptr, hex ? 16 : 10);
        AppendUtf8(SanitizeCharRef(v), &out);
        i = (j < s.size() && s[j] == ';') ? j + 1 : j;
        continue;
      }
    }
    bool matched = false;
    for (const Entity& e : kEntities) {
      const std::size_t len = std::strlen(e.name);
      if (s.compare(i + 1, len, e.name) != 0) continue;
      const bool semi = i + 1 + len < s.size() && s[i + 1 + len] == ';';
      if (!semi && !e.legacy) continue;
      AppendUtf8(e.cp, &out);
      i += 1 + len + (semi ? 1 : 0);
      matched = true;
      break;
    }
    if (!matched) out.push_back(s[i++]);
  }
  return out;
}

}  // namespace sims::language::internal
