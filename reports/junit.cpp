#include "reports/junit.hpp"

#include <cstdio>

#include "core/utf8.hpp"

namespace cullcheck {
namespace {

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", s);
  return text;
}

}  // namespace

std::string xml_escape(const std::string& raw) {
  const std::string text = valid_utf8(raw);  // the document says UTF-8; a subject's bytes may not be
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t' && c != '\r') out += '?';
        else out += c;
    }
  }
  return out;
}

std::string junit_xml(const std::vector<GateVerdict>& suites) {
  using Outcome = GateCheck::Outcome;
  std::size_t tests = 0, failures = 0, errors = 0, skipped = 0;
  std::string body;
  for (const GateVerdict& suite : suites) {
    std::size_t f = 0, e = 0, s = 0;
    double time = 0.0;
    std::string cases;
    for (const GateCheck& c : suite.checks) {
      time += c.seconds;
      cases += "    <testcase classname=\"" + xml_escape(c.method) + "\" name=\"" + xml_escape(c.check) + "\" time=\"" +
               seconds_text(c.seconds) + "\"";
      if (c.outcome == Outcome::passed) {
        cases += "/>\n";
        continue;
      }
      std::string detail = c.message;
      for (const std::string& r : c.replays) detail += "\nreplay: " + r;
      const char* tag = c.outcome == Outcome::failed ? "failure" : c.outcome == Outcome::error ? "error" : "skipped";
      (c.outcome == Outcome::failed ? f : c.outcome == Outcome::error ? e : s) += 1;
      cases += ">\n      <" + std::string(tag) + " message=\"" + xml_escape(c.message) + "\"";
      if (c.outcome == Outcome::skipped) {
        cases += "/>\n";
      } else {
        cases += " type=\"" + xml_escape(c.check) + "\">" + xml_escape(detail) + "</" + tag + ">\n";
      }
      cases += "    </testcase>\n";
    }
    tests += suite.checks.size(), failures += f, errors += e, skipped += s;
    body += "  <testsuite name=\"" + xml_escape(suite.scene) + "\" tests=\"" + std::to_string(suite.checks.size()) +
            "\" failures=\"" + std::to_string(f) + "\" errors=\"" + std::to_string(e) + "\" skipped=\"" + std::to_string(s) +
            "\" time=\"" + seconds_text(time) + "\">\n" + cases + "  </testsuite>\n";
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"cullcheck\" tests=\"" + std::to_string(tests) +
         "\" failures=\"" + std::to_string(failures) + "\" errors=\"" + std::to_string(errors) + "\" skipped=\"" +
         std::to_string(skipped) + "\">\n" + body + "</testsuites>\n";
}

}  // namespace cullcheck
