// Text for XML and HTML documents (the MJCF the model builder writes, the HTML reports).
#pragma once

#include <string>
#include <string_view>

namespace sims {

/// `text` with & < > " ' replaced by entities, safe in element content and in single- or
/// double-quoted attribute values of both XML and HTML.
std::string EscapeMarkup(std::string_view text);

}  // namespace sims
