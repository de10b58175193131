#include "sims/core/markup.h"

namespace sims {

std::string EscapeMarkup(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";  // XML 1.0 and HTML 4 both read the numeric reference (&apos; is XML's)
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace sims
