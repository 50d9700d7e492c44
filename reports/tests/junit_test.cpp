// JUnit XML from gate verdicts (reports/junit.hpp): the whole document for a small case, the
// counts, and xml_escape.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reports/junit.hpp"

namespace cullcheck {
namespace {

using Outcome = GateCheck::Outcome;

TEST(JUnit, WholeDocumentForTwoSuites) {
  GateVerdict first;
  first.scene = R"(--seed 1 --city "grid")";
  first.checks = {
      {"oh_os", "conservative", Outcome::passed, "", {}, 0.25},
      {"wang", "pixel_budget", Outcome::failed, "2 frames above the budget of 40 misdrawn pixels (worst 95) & <more>",
       {"cullcheck verify --frame 3"}, 1.5},
  };
  GateVerdict second;
  second.scene = "s2";
  second.checks = {
      {"subject:x", "answers", Outcome::error, "subject 'x' at frame 3: crashed", {}, 0.0},
      {"subject:x", "pixel_budget", Outcome::skipped, "the pixel oracle checked no frame", {}, 0.125},
  };
  // Suite times are the sums of their cases' (0.25 + 1.5 = 1.75; 0 + 0.125), printed with 6
  // decimals; a passed case is an empty element; a failure's body is its message and a
  // "replay: " line per replay; a skipped case has no body; markup in any text is escaped.
  const std::string expected =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<testsuites name=\"cullcheck\" tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"1\">\n"
      "  <testsuite name=\"--seed 1 --city &quot;grid&quot;\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\" "
      "time=\"1.750000\">\n"
      "    <testcase classname=\"oh_os\" name=\"conservative\" time=\"0.250000\"/>\n"
      "    <testcase classname=\"wang\" name=\"pixel_budget\" time=\"1.500000\">\n"
      "      <failure message=\"2 frames above the budget of 40 misdrawn pixels (worst 95) &amp; &lt;more&gt;\" "
      "type=\"pixel_budget\">2 frames above the budget of 40 misdrawn pixels (worst 95) &amp; &lt;more&gt;\n"
      "replay: cullcheck verify --frame 3</failure>\n"
      "    </testcase>\n"
      "  </testsuite>\n"
      "  <testsuite name=\"s2\" tests=\"2\" failures=\"0\" errors=\"1\" skipped=\"1\" time=\"0.125000\">\n"
      "    <testcase classname=\"subject:x\" name=\"answers\" time=\"0.000000\">\n"
      "      <error message=\"subject &apos;x&apos; at frame 3: crashed\" type=\"answers\">subject &apos;x&apos; at frame 3: "
      "crashed</error>\n"
      "    </testcase>\n"
      "    <testcase classname=\"subject:x\" name=\"pixel_budget\" time=\"0.125000\">\n"
      "      <skipped message=\"the pixel oracle checked no frame\"/>\n"
      "    </testcase>\n"
      "  </testsuite>\n"
      "</testsuites>\n";
  EXPECT_EQ(junit_xml({first, second}), expected);
}

TEST(JUnit, NoSuites) {
  EXPECT_EQ(junit_xml({}),
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<testsuites name=\"cullcheck\" tests=\"0\" failures=\"0\" errors=\"0\" skipped=\"0\">\n"
            "</testsuites>\n");
}

TEST(JUnit, EveryReplayIsALine) {
  GateVerdict v;
  v.scene = "s";
  v.checks = {{"m", "conservative", Outcome::failed, "culled", {"r1", "r2", "r3"}, 0.0}};
  const std::string xml = junit_xml({v});
  EXPECT_NE(xml.find(">culled\nreplay: r1\nreplay: r2\nreplay: r3</failure>"), std::string::npos) << xml;
  // The message attribute carries the message alone.
  EXPECT_NE(xml.find("<failure message=\"culled\" type=\"conservative\">"), std::string::npos) << xml;
}

TEST(XmlEscape, MarkupAndControlCharacters) {
  EXPECT_EQ(xml_escape("a&b<c>d\"e'f"), "a&amp;b&lt;c&gt;d&quot;e&apos;f");
  // Control characters XML 1.0 forbids become '?'; tab, newline and carriage return stay.
  EXPECT_EQ(xml_escape(std::string("\x01x\x1f") + '\0' + "\x1b[0m"), "?x???[0m");
  EXPECT_EQ(xml_escape("\t\n\r"), "\t\n\r");
  // Bytes of UTF-8 text (here "é", 0xC3 0xA9) pass through.
  EXPECT_EQ(xml_escape("caf\xc3\xa9"), "caf\xc3\xa9");
  EXPECT_EQ(xml_escape(""), "");
  // Text that looks escaped is escaped again: the input is text, not markup.
  EXPECT_EQ(xml_escape("&amp;"), "&amp;amp;");
}

// Whether `s` is well-formed UTF-8 (lead and continuation bytes; overlong forms not checked).
bool valid_utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (extra < 0 || s.size() - i <= static_cast<std::size_t>(extra)) return false;
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return false;
    i += 1 + extra;
  }
  return true;
}

TEST(XmlEscape, Utf8CheckerOfThisTest) {
  EXPECT_TRUE(valid_utf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"));
  EXPECT_FALSE(valid_utf8("a\xff"));
  EXPECT_FALSE(valid_utf8("\xc3"));
  EXPECT_FALSE(valid_utf8("\xe2\x28\xa1"));
}

// Regression test of a bug it found, since fixed (same root cause as GateVerdict.SubjectGarbageThatIsNotUtf8StillGivesAWritableVerdict):
// the document declares encoding="UTF-8", but xml_escape passes bytes that are not UTF-8 through,
// so a subject's binary garbage quoted into a check's message makes the JUnit file not
// well-formed XML (CI systems reject the whole file). The header promises text "made safe for
// XML"; it masks forbidden control characters but not malformed bytes.
TEST(XmlEscape, BytesThatAreNotUtf8AreNotPassedThrough) {
  EXPECT_TRUE(valid_utf8(xml_escape("garbage \xff\xfe from a subject")));
}

}  // namespace
}  // namespace cullcheck
