// The page's text helpers: escaping, base64 (RFC 4648's test vectors), numbers the same everywhere.
#include <gtest/gtest.h>

#include <cmath>

#include "reports/html/html_text.hpp"

namespace cullcheck::html {
namespace {

TEST(HtmlText, EscapesEveryCharacterThatCouldOpenMarkup) {
  EXPECT_EQ(escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
  EXPECT_EQ(escape("--params '{\"x\":1}'"), "--params &#39;{&quot;x&quot;:1}&#39;");
  EXPECT_EQ(escape("plain"), "plain");
}

TEST(HtmlText, Base64MatchesTheRfcVectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\x89PNG\xff\x00", 6)), "iVBOR/8A");
}

TEST(HtmlText, NumbersKeepSignificantDigitsWithoutExponentsInTheUsualRange) {
  EXPECT_EQ(number(0.0), "0");
  EXPECT_EQ(number(3.14159), "3.14");
  EXPECT_EQ(number(1234.6), "1235");
  EXPECT_EQ(number(0.012345), "0.0123");
  EXPECT_EQ(number(-2.5, 2), "-2.5");
  EXPECT_EQ(number(1.5e-6), "1.50e-06");
  EXPECT_EQ(number(NAN), "\u2013");
  EXPECT_EQ(number(INFINITY), "\u2013");
}

TEST(HtmlText, CountsAndPercentages) {
  EXPECT_EQ(count(22187), "22,187");
  EXPECT_EQ(count(999), "999");
  EXPECT_EQ(count(1000000), "1,000,000");
  EXPECT_EQ(count(-4200), "-4,200");
  EXPECT_EQ(count(NAN), "\u2013");
  EXPECT_EQ(percent(0.253), "+25%");
  EXPECT_EQ(percent(-0.0652, 1), "-6.5%");
  EXPECT_EQ(svg_coordinate(-0.001), "0.00");
  EXPECT_EQ(svg_coordinate(12.345), "12.35");
}

}  // namespace
}  // namespace cullcheck::html
