#include "harbour/core/Text.h"

#include <unistd.h>

#include <cstdio>

namespace harbour::core {
namespace {

// length of the valid UTF-8 sequence at `at` (0 if there is none); rejects overlong forms, surrogates and
// code points above U+10FFFF
std::size_t utf8_length(std::string_view s, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(at);
  if (b < 0x80) return 1;
  std::size_t n = 0;
  unsigned int cp = 0;
  if (b >= 0xC2 && b <= 0xDF) {
    n = 2;
    cp = b & 0x1Fu;
  } else if (b >= 0xE0 && b <= 0xEF) {
    n = 3;
    cp = b & 0x0Fu;
  } else if (b >= 0xF0 && b <= 0xF4) {
    n = 4;
    cp = b & 0x07u;
  } else {
    return 0;
  }
  if (at + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(at + k) & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (byte(at + k) & 0x3Fu);
  }
  const unsigned int min[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < min[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}

bool is_control(std::string_view s, std::size_t at, std::size_t n) {
  const auto b = static_cast<unsigned char>(s[at]);
  if (n == 1) return b < 0x20 || b == 0x7F;
  // C1 controls U+0080-U+009F are encoded C2 80 - C2 9F
  return n == 2 && b == 0xC2 && static_cast<unsigned char>(s[at + 1]) < 0xA0;
}

// a bidirectional formatting character (the Unicode "Trojan Source" set): U+061C, U+200E, U+200F,
// U+202A-U+202E, U+2066-U+2069. They reorder what follows them on screen: "anna\u202Egnp.exe" shows as
// another name.
bool is_bidi_control(std::string_view s, std::size_t at, std::size_t n) {
  const auto byte = [&](std::size_t k) {
    return static_cast<unsigned int>(static_cast<unsigned char>(s[at + k]));
  };
  if (n == 2) return byte(0) == 0xD8 && byte(1) == 0x9C;  // U+061C
  if (n != 3 || byte(0) != 0xE2) return false;
  const unsigned int cp = 0x2000u | ((byte(1) & 0x3Fu) << 6) | (byte(2) & 0x3Fu);
  return cp == 0x200E || cp == 0x200F || (cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069);
}

}  // namespace

std::string why_bad_name(std::string_view text, std::size_t max_bytes) {
  if (text.empty()) return "is empty";
  if (text.size() > max_bytes)
    return "is " + std::to_string(text.size()) + " bytes long (at most " + std::to_string(max_bytes) + ")";
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t n = utf8_length(text, at);
    if (n == 0) return "is not valid UTF-8 (byte " + std::to_string(at) + ")";
    if (is_control(text, at, n)) return "holds a control character (byte " + std::to_string(at) + ")";
    if (is_bidi_control(text, at, n))
      return "holds a bidirectional control character (byte " + std::to_string(at) + ")";
    at += n;
  }
  return {};
}

std::string printable(std::string_view text, std::size_t max_bytes) {
  std::string out;
  for (std::size_t at = 0; at < text.size() && at < max_bytes;) {
    const std::size_t n = utf8_length(text, at);
    if (n == 0 || is_control(text, at, n)) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned char>(text[at]));
      out += hex;
      ++at;
    } else if (is_bidi_control(text, at, n)) {
      for (std::size_t k = 0; k < n; ++k, ++at) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned char>(text[at]));
        out += hex;
      }
    } else {
      out.append(text.substr(at, n));
      at += n;
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

std::string comma_separated(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items)
    text += (text.empty() ? "" : ", ") + item;
  return text;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

}  // namespace harbour::core
