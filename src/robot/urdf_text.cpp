// The structural scan of URDF text (see urdf_text.hpp).
#include "robot/urdf_text.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "graspmix/robot/hand.hpp"

namespace graspmix::detail {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

class Scanner {
 public:
  Scanner(const std::string& xml, const std::string& what) : xml_(xml), what_(what) {}

  UrdfTextCounts run() {
    UrdfTextCounts counts;
    while (i_ < xml_.size()) {
      const char c = xml_[i_];
      if (c != '<') {
        line_ += c == '\n';
        ++i_;
      } else if (starts("<!--")) {
        skip_past("-->", "a comment");
      } else if (starts("<![CDATA[")) {
        skip_past("]]>", "a CDATA section");
      } else if (starts("<?")) {
        skip_past("?>", "a processing instruction");
      } else if (starts("<!")) {
        skip_past(">", "a declaration");
      } else {
        tag(counts);
      }
    }
    if (!open_.empty()) {
      fail("<" + open_.back().name + "> opened on line " + std::to_string(open_.back().line) +
           " is never closed (truncated file?)");
    }
    auto too_many = [&](int n, const char* kind) {
      if (n <= kMaxUrdfLinks) return;
      throw std::invalid_argument(what_ + ": " + std::to_string(n) + " " + kind + ", more than the " +
                                  std::to_string(kMaxUrdfLinks) + " a hand or object URDF may have");
    };
    too_many(counts.links, "links");
    too_many(counts.joints, "joints");
    return counts;
  }

 private:
  struct Open {
    std::string name;
    std::size_t line;
  };

  [[noreturn]] void fail(const std::string& m) const { throw std::invalid_argument(what_ + ": malformed XML: " + m); }

  bool starts(const char* s) const { return xml_.compare(i_, std::strlen(s), s) == 0; }

  void skip_past(const char* end, const char* construct) {
    const std::size_t j = xml_.find(end, i_);
    if (j == std::string::npos) {
      fail(std::string(construct) + " opened on line " + std::to_string(line_) + " is never closed (truncated file?)");
    }
    line_ += static_cast<std::size_t>(std::count(xml_.begin() + static_cast<std::ptrdiff_t>(i_),
                                                 xml_.begin() + static_cast<std::ptrdiff_t>(j), '\n'));
    i_ = j + std::strlen(end);
  }

  /// A start, end or empty-element tag at i_; quoted attribute values may hold '>'.
  void tag(UrdfTextCounts& counts) {
    const bool closing = starts("</");
    const std::size_t tag_line = line_;
    std::size_t j = i_ + (closing ? 2 : 1);
    const std::size_t name_start = j;
    while (j < xml_.size() && !is_space(xml_[j]) && xml_[j] != '>' && xml_[j] != '/') ++j;
    const std::string name = xml_.substr(name_start, j - name_start);
    char quote = 0;
    for (; j < xml_.size(); ++j) {
      const char d = xml_[j];
      line_ += d == '\n';
      if (quote) {
        if (d == quote) quote = 0;
      } else if (d == '"' || d == '\'') {
        quote = d;
      } else if (d == '>') {
        break;
      }
    }
    const std::string at = " on line " + std::to_string(tag_line);
    if (j >= xml_.size()) fail("the tag <" + name + ">" + at + " never ends (truncated file?)");
    if (name.empty()) fail("a tag without a name" + at);
    const bool empty_element = !closing && xml_[j - 1] == '/';
    i_ = j + 1;
    if (closing) {
      if (open_.empty()) fail("</" + name + ">" + at + " closes no element");
      if (open_.back().name != name) {
        fail("</" + name + ">" + at + " closes <" + open_.back().name + "> opened on line " +
             std::to_string(open_.back().line));
      }
      open_.pop_back();
      return;
    }
    const std::size_t depth = open_.size() + 1;
    if (depth > static_cast<std::size_t>(kMaxUrdfXmlDepth)) {
      fail("elements nested more than " + std::to_string(kMaxUrdfXmlDepth) + " deep" + at);
    }
    if (depth == 2 && name == "link") ++counts.links;
    if (depth == 2 && name == "joint") ++counts.joints;
    if (!empty_element) open_.push_back({name, tag_line});
  }

  const std::string& xml_;
  const std::string& what_;
  std::size_t i_ = 0, line_ = 1;
  std::vector<Open> open_;
};

}  // namespace

UrdfTextCounts check_urdf_text(const std::string& xml, const std::string& what) { return Scanner(xml, what).run(); }

}  // namespace graspmix::detail
