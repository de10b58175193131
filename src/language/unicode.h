// Minimal Unicode support for the CLIP tokenizer: UTF-8 coding, the letter / number / whitespace
// classes of CLIP's pre-tokenisation pattern, Python-like lower-casing and HTML unescaping.
// Tables cover the scripts listed in tokenizer.h; everything else counts as "other".
#pragma once

#include <string>

#include "sims/language/utf8.h"  // AppendUtf8, public for the asset converters

namespace sims::language::internal {

/// Decodes UTF-8; invalid bytes become U+FFFD (one per byte) instead of failing.
std::u32string DecodeUtf8(const std::string& s);
/// Encodes code points as UTF-8.
std::string EncodeUtf8(const std::u32string& s);

/// \p{L} (approximate tables).
bool IsLetter(char32_t cp);
/// \p{N} (approximate tables).
bool IsNumber(char32_t cp);
/// Python's str whitespace (the \s of CLIP's patterns).
bool IsSpace(char32_t cp);
/// Python's str.lower() for the covered scripts (may yield two code points, e.g. U+0130).
void AppendLower(char32_t cp, std::u32string* out);

/// Python's html.unescape for numeric references and common named entities.
std::string HtmlUnescape(const std::string& s);

}  // namespace sims::language::internal
