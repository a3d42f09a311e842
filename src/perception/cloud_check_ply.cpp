// PLY header and body checks (see cloud_check.hpp).
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>

#include "cloud_check.hpp"

namespace graspmix::cloud_check {

namespace {

struct Scalar {
  Kind kind = Kind::kFloat;
  int size = 4;
};

struct Property {
  std::string name;
  Scalar type;
  bool list = false;
  Scalar count_type;  ///< of a list's length
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  bool has_list() const {
    for (const auto& p : properties)
      if (p.list) return true;
    return false;
  }
  std::uint64_t row_bytes() const {  // of rows without lists
    std::uint64_t n = 0;
    for (const auto& p : properties) n += static_cast<std::uint64_t>(p.type.size);
    return n;
  }
};

struct PlyText {
  enum Format { kAscii, kLittle, kBig } format = kAscii;
  std::vector<Element> elements;
  std::uint64_t data_offset = 0;
  int end_line = 0;
  std::uint64_t num_cols = 0, num_rows = 0;  ///< obj_info's organisation, 0 when not given
};

bool scalar_type(std::string_view t, Scalar& s) {
  static const struct {
    const char* names[2];
    Kind kind;
    int size;
  } kTypes[] = {{{"char", "int8"}, Kind::kSigned, 1},    {{"uchar", "uint8"}, Kind::kUnsigned, 1},
                {{"short", "int16"}, Kind::kSigned, 2},  {{"ushort", "uint16"}, Kind::kUnsigned, 2},
                {{"int", "int32"}, Kind::kSigned, 4},    {{"uint", "uint32"}, Kind::kUnsigned, 4},
                {{"float", "float32"}, Kind::kFloat, 4}, {{"double", "float64"}, Kind::kFloat, 8}};
  for (const auto& k : kTypes) {
    if (t == k.names[0] || t == k.names[1]) {
      s = {k.kind, k.size};
      return true;
    }
  }
  return false;
}

/// `property TYPE NAME` or `property list COUNT_TYPE TYPE NAME`.
Property read_property(const std::vector<std::string_view>& tok, const std::function<void(std::string)>& bad) {
  Property p;
  const bool list = tok.size() > 1 && tok[1] == "list";
  if (tok.size() != (list ? 5u : 3u)) bad("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
  p.list = list;
  if (list && (!scalar_type(tok[2], p.count_type) || p.count_type.kind == Kind::kFloat)) {
    bad("the length type of list '" + printable(tok[4]) + "' must be an integer type, got '" + printable(tok[2]) + "'");
  }
  const std::string_view type = tok[list ? 3 : 1];
  if (!scalar_type(type, p.type)) bad("unknown property type '" + printable(type) + "'");
  p.name = printable(tok.back());  // only for messages
  return p;
}

void read_ply_line(const std::vector<std::string_view>& tok, PlyText& h, bool& have_format,
                   const std::function<void(std::string)>& bad) {
  const std::string_view key = tok[0];
  if (key == "comment") return;
  if (key == "obj_info") {
    // PCL sizes the cloud by num_cols x num_rows when they are given (before reading any vertex).
    if (tok.size() > 1 && (tok[1] == "num_cols" || tok[1] == "num_rows")) {
      std::uint64_t v = 0;
      if (tok.size() != 3 || !parse_count(tok[2], v) || v > std::numeric_limits<std::uint32_t>::max()) {
        bad("obj_info " + printable(tok[1]) + " needs one integer in [0, 2^32 - 1]");
      }
      (tok[1] == "num_cols" ? h.num_cols : h.num_rows) = v;
    }
    return;
  }
  if (key == "format") {
    if (have_format) bad("a second format line");
    if (tok.size() != 3 || tok[2] != "1.0") bad("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    if (tok[1] == "ascii")
      h.format = PlyText::kAscii;
    else if (tok[1] == "binary_little_endian")
      h.format = PlyText::kLittle;
    else if (tok[1] == "binary_big_endian")
      h.format = PlyText::kBig;
    else
      bad("unknown format '" + printable(tok[1]) + "'");
    have_format = true;
    return;
  }
  if (!have_format) bad("'" + printable(key) + "' before the format line");
  if (key == "element") {
    Element e;
    if (tok.size() != 3) bad("expected 'element NAME COUNT'");
    e.name = printable(tok[1]);
    if (!parse_count(tok[2], e.count)) {
      bad("element '" + e.name + "' count '" + printable(tok[2]) + "' is not a non-negative integer");
    }
    if (e.count > std::numeric_limits<std::uint32_t>::max()) bad("element '" + e.name + "' count exceeds 2^32 - 1");
    h.elements.push_back(std::move(e));
    return;
  }
  if (key == "property") {
    if (h.elements.empty()) bad("a property before any element");
    h.elements.back().properties.push_back(read_property(tok, bad));
    return;
  }
  bad("'" + printable(key) +
      "' is not a PLY header keyword (format, comment, obj_info, element, "
      "property, end_header)");
}

PlyText read_ply_header(const std::string& path, std::istream& in) {
  PlyText h;
  std::string line;
  std::uint64_t offset = 0;
  bool have_format = false;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    offset += line.size() + (in.eof() ? 0 : 1);
    if (offset > kMaxHeaderBytes) fail(path, "not a valid PLY header: no end_header in the first 1 MiB");
    const auto bad = [&](const std::string& what) {
      fail(path, "not a valid PLY header: line " + std::to_string(line_no) + ": " + what);
    };
    const auto tok = split_tokens(line);
    if (line_no == 1) {
      if (tok.size() != 1 || tok[0] != "ply") fail(path, "not a valid PLY header (the file does not start with 'ply')");
      continue;
    }
    if (tok.empty()) bad("a blank line");
    if (tok[0] == "end_header") {
      if (!have_format) bad("end_header before the format line");
      h.data_offset = offset;
      h.end_line = line_no;
      for (const auto& e : h.elements) {
        if (e.count > 0 && e.properties.empty()) {
          fail(path,
               "not a valid PLY header: element '" + e.name + "' has " + str(e.count) + " rows but no properties");
        }
      }
      return h;
    }
    read_ply_line(tok, h, have_format, bad);
  }
  fail(path, "not a valid PLY header: it ends without end_header");
}

/// Every row of every element on a line of its own, with the values its properties need.
void check_ascii_rows(const std::string& path, const PlyText& h, std::istream& in) {
  std::string line;
  int line_no = h.end_line;
  for (const auto& e : h.elements) {
    for (std::uint64_t row = 0; row < e.count; ++row) {
      if (!std::getline(in, line)) {
        fail(path, "the data section is truncated: element '" + e.name + "' has " + str(row) + " of " + str(e.count) +
                       " declared rows");
      }
      const std::string where = "line " + std::to_string(++line_no) + ": ";
      const auto tok = split_tokens(line);
      std::size_t i = 0;
      auto number = [&](const Scalar& s, const std::string& name) {
        if (i >= tok.size()) {
          fail(path, where + "too few values for element '" + e.name + "' (property '" + name + "' is missing)");
        }
        if (!is_number(tok[i], s.kind, s.size)) {
          fail(path, where + "value " + str(i + 1) + " '" + printable(tok[i]) + "' is not " +
                         (s.kind == Kind::kFloat ? "a number" : "an integer in range") + " for property '" + name +
                         "'");
        }
        return tok[i++];
      };
      for (const auto& p : e.properties) {
        if (!p.list) {
          number(p.type, p.name);
          continue;
        }
        std::uint64_t n = 0;
        if (!parse_count(number(p.count_type, p.name), n)) {
          fail(path, where + "the length of list '" + p.name + "' is not a non-negative integer");
        }
        for (std::uint64_t k = 0; k < n; ++k) number(p.type, p.name);
      }
      if (i != tok.size()) {
        fail(path, where + str(tok.size()) + " values, element '" + e.name + "' needs " + str(i));
      }
    }
  }
  while (std::getline(in, line)) {
    ++line_no;
    if (!split_tokens(line).empty()) {
      fail(path, "line " + std::to_string(line_no) + ": more rows than the header's elements declare");
    }
  }
}

/// The bytes the binary body needs: rows of scalars by multiplication, rows with lists by reading
/// every list length (each row holds at least one byte, so this ends within the file).
void check_binary_size(const std::string& path, const PlyText& h, std::uint64_t size, std::istream& in) {
  std::uint64_t left = size - h.data_offset;
  const auto truncated = [&](const Element& e, std::uint64_t row) {
    fail(path, "the data section is truncated: element '" + e.name + "' needs more bytes than the file has (row " +
                   str(row) + " of " + str(e.count) + ")");
  };
  for (const auto& e : h.elements) {
    if (e.count == 0) continue;  // (and rows without properties have none: see read_ply_header)
    if (!e.has_list()) {
      const std::uint64_t row = e.row_bytes();
      if (e.count > left / row) truncated(e, left / row);
      left -= e.count * row;
      in.ignore(static_cast<std::streamsize>(e.count * row));
      continue;
    }
    for (std::uint64_t r = 0; r < e.count; ++r) {
      for (const auto& p : e.properties) {
        if (!p.list) {
          if (left < static_cast<std::uint64_t>(p.type.size)) truncated(e, r);
          left -= p.type.size;
          in.ignore(p.type.size);
          continue;
        }
        unsigned char b[4] = {0, 0, 0, 0};
        const int cs = p.count_type.size;
        if (left < static_cast<std::uint64_t>(cs) || !in.read(reinterpret_cast<char*>(b), cs)) truncated(e, r);
        left -= cs;
        std::uint64_t n = 0;
        for (int k = 0; k < cs; ++k)
          n |= static_cast<std::uint64_t>(b[h.format == PlyText::kBig ? cs - 1 - k : k]) << (8 * k);
        if (p.count_type.kind == Kind::kSigned && (n >> (8 * cs - 1)) & 1) {
          fail(path, "the data section is corrupt: row " + str(r) + " of element '" + e.name +
                         "' has a negative length of list '" + p.name + "'");
        }
        if (n > left / p.type.size) truncated(e, r);
        left -= n * p.type.size;
        in.ignore(static_cast<std::streamsize>(n * p.type.size));
      }
    }
  }
}

}  // namespace

std::uint64_t check_ply(const std::string& path) {
  const std::uint64_t size = file_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open for reading");
  const PlyText h = read_ply_header(path, in);
  const Element* vertex = nullptr;
  for (const auto& e : h.elements)
    if (e.name == "vertex") vertex = &e;
  if (!vertex) fail(path, "not a valid PLY header: there is no 'vertex' element");
  if (vertex->count == 0) fail(path, "the cloud is empty (the header declares 0 vertices)");
  if (h.num_cols > 0 && h.num_rows > 0 && h.num_cols * h.num_rows != vertex->count) {
    fail(path, "not a valid PLY header: obj_info num_cols " + str(h.num_cols) + " x num_rows " + str(h.num_rows) +
                   " != " + str(vertex->count) + " vertices");
  }
  for (const auto& e : h.elements) {
    // PCL copies range_grid rows by the vertex indices they list, unchecked.
    if (e.name == "range_grid") fail(path, "range_grid elements (scanner-organised PLY) are not supported");
  }
  if (h.format == PlyText::kAscii) {
    check_ascii_rows(path, h, in);
  } else {
    check_binary_size(path, h, size, in);
  }
  return vertex->count;
}

}  // namespace graspmix::cloud_check
