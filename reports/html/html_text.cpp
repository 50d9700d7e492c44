#include "reports/html/html_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>

namespace cullcheck::html {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16 | std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 |
                            std::uint8_t(bytes[i + 2]);
    out += kAlphabet[v >> 18], out += kAlphabet[(v >> 12) & 63], out += kAlphabet[(v >> 6) & 63], out += kAlphabet[v & 63];
  }
  if (const std::size_t rest = bytes.size() - i; rest > 0) {
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (rest == 2) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out += kAlphabet[v >> 18], out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string number(double v, int digits) {
  if (!std::isfinite(v)) return "\u2013";
  if (v == 0.0) return "0";
  char buffer[64];
  const double a = std::fabs(v);
  if (a >= 1e9 || a < 1e-4) {
    std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, v);
    return buffer;
  }
  // Significant digits without an exponent: decimals = digits - 1 - floor(log10|v|), at least 0.
  const int magnitude = int(std::floor(std::log10(a)));
  const int decimals = std::max(0, digits - 1 - magnitude);
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

std::string count(double v) {
  if (!std::isfinite(v)) return "\u2013";
  const bool negative = v < 0;
  std::string digits = std::to_string(static_cast<long long>(std::llround(std::fabs(v))));
  std::string out;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return negative ? "-" + out : out;
}

std::string percent(double v, int decimals) {
  if (!std::isfinite(v)) return "\u2013";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%+.*f%%", decimals, v * 100.0);
  return buffer;
}

std::string svg_coordinate(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.2f", v);
  std::string s = buffer;
  return s == "-0.00" ? "0.00" : s;
}

}  // namespace cullcheck::html
