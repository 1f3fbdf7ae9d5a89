#include "cases/text.hpp"

#include <cmath>

namespace pb {

std::string clip(std::string_view text, std::size_t max) {
  std::size_t cut = text.size();
  if (cut > max) {
    cut = max;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // inside a UTF-8 character
  }
  std::string out(text.substr(0, cut));
  // A control character (a newline in a TOML string) would break the one-line message.
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return cut < text.size() ? out + "..." : out;
}

std::string format_number(double x) { return std::isnan(x) ? std::string() : shortest_text(x); }

}  // namespace pb
