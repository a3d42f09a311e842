#pragma once
// A cheap scan of URDF text before urdfdom sees it. urdfdom parses with TinyXML and ignores TinyXML's
// errors: a truncated file or a mismatched end tag leaves a partial document that urdfdom reads as a
// smaller robot without a word. TinyXML also parses (and frees) nested elements recursively, so the
// nesting depth is bounded here before it can exhaust the stack.
#include <string>

namespace graspmix::detail {

/// What the scan counts: the <link> and <joint> elements directly under the root element.
struct UrdfTextCounts {
  int links = 0;
  int joints = 0;
};

/// Checks that every element of `xml` is closed by a matching end tag and that comments, CDATA and
/// tags end, that nesting stays within kMaxUrdfXmlDepth and that there are at most kMaxUrdfLinks
/// links and joints. Throws std::invalid_argument starting with `what` and naming the line otherwise.
/// Linear in the text, no recursion.
UrdfTextCounts check_urdf_text(const std::string& xml, const std::string& what);

}  // namespace graspmix::detail
