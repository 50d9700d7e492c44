// Text for the report page (reports/html/): escaping, numbers written the same on every machine,
// and base64 for the pictures the page carries inline (it opens offline, so nothing is linked).
#pragma once

#include <string>
#include <string_view>

namespace cullcheck::html {

// Escapes &, <, >, " and ' for HTML text and attribute values.
std::string escape(std::string_view text);
// RFC 4648 base64 with padding.
std::string base64(std::string_view bytes);
// A number with `digits` significant digits, no exponent for |v| in [1e-4, 1e9), "–" for NaN or
// infinity (a report's null or missing value): locale-independent, the same bytes everywhere.
std::string number(double v, int digits = 3);
// A count with thousands separators: 22187 -> "22,187".
std::string count(double v);
// v as a signed percentage: 0.253 -> "+25%".
std::string percent(double v, int decimals = 0);
// A coordinate in an SVG attribute: two decimals, "-0.00" written "0.00".
std::string svg_coordinate(double v);

}  // namespace cullcheck::html
