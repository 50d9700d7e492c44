// JUnit XML, the format CI systems display (Jenkins, GitLab, GitHub annotations): one
// <testsuite> per scene, one <testcase> per method and check of the gate's verdict
// (reports/gate_verdict.hpp), a failed check as <failure> and a subject that crashed, hung or
// lied as <error>, each with its replay lines. report.json stays the full record.
#pragma once

#include <string>
#include <vector>

#include "reports/gate_verdict.hpp"

namespace cullcheck {

std::string junit_xml(const std::vector<GateVerdict>& suites);
// Text made safe for XML attributes and character data (markup escaped, control characters
// that XML 1.0 forbids replaced by '?').
std::string xml_escape(const std::string& text);

}  // namespace cullcheck
