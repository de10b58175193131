// UTF-8 encoding of one code point. Public because the asset converters (sims_assets) decode
// JavaScript \x / \u escapes with it; the tokenizer's other Unicode tables stay private.
#pragma once

#include <string>

namespace sims::language {

/// Appends one code point as UTF-8 (1-4 bytes; the value is not validated).
void AppendUtf8(char32_t cp, std::string* out);

}  // namespace sims::language
