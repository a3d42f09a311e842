// The PLY reader: header, body and their checks (see cloud_check.hpp).
#include <algorithm>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

#include "cloud_check.hpp"

namespace graspmix::cloud_check {

namespace {

struct Scalar {
  Kind kind = Kind::kFloat;
  int size = 4;
};

struct Property {
  std::string name;  ///< for messages (printable)
  std::string raw;   ///< as the file spells it
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
  /// The organisation as PCL's reader sets it while it reads the header: obj_info's num_cols and num_rows
  /// as they come, and at each vertex element, when either is still 0, the vertex count x 1.
  std::uint64_t width = 0, height = 0;
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
  p.name = printable(tok.back());
  p.raw = std::string(tok.back());
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
      (tok[1] == "num_cols" ? h.width : h.height) = v;
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
    if (e.name == "vertex" && (h.width == 0 || h.height == 0)) h.width = e.count, h.height = 1;
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

/// PLY's names of the normals are PCL's normal_x, normal_y, normal_z.
std::string pcl_name(const std::string& name) {
  if (name == "nx" || name == "ny" || name == "nz") return "normal_" + name.substr(1);
  return name;
}

/// The fields PCL 1.13's reader makes of the vertex properties, in order (what CloudData::fields lists).
std::vector<std::string> pcl_names(const Element& vertex) {
  std::vector<std::string> names;
  for (const auto& p : vertex.properties) {
    const bool uchar = p.type.kind == Kind::kUnsigned && p.type.size == 1;
    if (p.list) {
      // PCL reads a vertex list with uchar lengths of int or uint, or with uint lengths; it skips the others.
      const bool u8 = p.count_type.kind == Kind::kUnsigned && p.count_type.size == 1;
      const bool u32 = p.count_type.kind == Kind::kUnsigned && p.count_type.size == 4;
      if (u32 || (u8 && p.type.kind != Kind::kFloat && p.type.size == 4)) names.push_back(pcl_name(p.raw));
    } else if (uchar && (p.raw == "red" || p.raw == "diffuse_red")) {
      names.push_back("rgb");  // red, green and blue packed into one float, as PCL's point types hold them
    } else if (uchar && (p.raw == "green" || p.raw == "blue" || p.raw == "diffuse_green" || p.raw == "diffuse_blue")) {
      continue;
    } else if (uchar && p.raw == "alpha") {
      const auto rgb = std::find(names.begin(), names.end(), "rgb");
      if (rgb != names.end()) *rgb = "rgba";
    } else {
      names.push_back(pcl_name(p.raw));
    }
  }
  return names;
}

/// Where the values the cloud keeps go: every scalar property of the vertex element into the rows of
/// RawCloud::data, the camera element's int viewportx and viewporty (PCL's organisation) into `viewport`.
class Sink {
 public:
  Sink(const PlyText& h, RawCloud& out) : out_(out), roles_(h.elements.size(), kNone) {
    for (std::size_t k = 0; k < h.elements.size(); ++k) {
      if (h.elements[k].name == "vertex") vertex_ = k;
      if (h.elements[k].name == "camera") roles_[k] = kCamera;
    }
    const Element& v = h.elements[vertex_];
    roles_[vertex_] = kVertex;
    out.names = pcl_names(v);
    std::uint64_t row = 0;
    for (const auto& p : v.properties) {
      at_.push_back(p.list ? -1 : static_cast<std::int64_t>(row));
      if (!p.list) out.fields.push_back({pcl_name(p.raw), p.type.kind, p.type.size, 1, row, 0}), row += p.type.size;
    }
    for (auto& f : out.fields) f.stride = row;
    row_bytes_ = row;
  }
  bool keeps(std::size_t element) const { return roles_[element] != kNone; }
  /// Where value p of row r of element k (e) goes, nullptr for nowhere.
  void* slot(const Element& e, std::size_t k, std::uint64_t r, std::size_t p) {
    if (roles_[k] == kVertex) {
      if (at_[p] < 0) return nullptr;
      // Grown a row at a time as rows are read, so the memory is bounded by the file, not by the header.
      if (out_.data.size() < (r + 1) * row_bytes_) out_.data.resize((r + 1) * row_bytes_);
      return out_.data.data() + r * row_bytes_ + at_[p];
    }
    if (roles_[k] != kCamera) return nullptr;
    const Property& q = e.properties[p];
    if (q.list || q.type.kind != Kind::kSigned || q.type.size != 4) return nullptr;  // PCL reads int32 ones only
    const int axis = q.raw == "viewportx" ? 0 : q.raw == "viewporty" ? 1 : -1;
    if (axis < 0) return nullptr;
    has_viewport[axis] = true;
    return &viewport[axis];
  }
  std::int32_t viewport[2] = {0, 0};  ///< the camera element's viewportx, viewporty, where has_viewport says
  bool has_viewport[2] = {false, false};

 private:
  enum Role { kNone, kVertex, kCamera };
  RawCloud& out_;
  std::vector<Role> roles_;
  std::size_t vertex_ = 0;
  std::vector<std::int64_t> at_;  ///< per vertex property: its byte in a row, -1 for a list
  std::uint64_t row_bytes_ = 0;
};

/// Every row of every element on a line of its own, with the values its properties need; the values the
/// sink wants are stored where it says.
void read_ascii_rows(const std::string& path, const PlyText& h, std::istream& in, Sink& sink) {
  std::string line;
  int line_no = h.end_line;
  std::uint64_t scratch = 0;
  for (std::size_t k = 0; k < h.elements.size(); ++k) {
    const Element& e = h.elements[k];
    for (std::uint64_t row = 0; row < e.count; ++row) {
      if (!std::getline(in, line)) {
        fail(path, "the data section is truncated: element '" + e.name + "' has " + str(row) + " of " + str(e.count) +
                       " declared rows");
      }
      const std::string where = "line " + std::to_string(++line_no) + ": ";
      const auto tok = split_tokens(line);
      std::size_t i = 0;
      auto number = [&](const Scalar& s, const std::string& name, void* to) {
        if (i >= tok.size()) {
          fail(path, where + "too few values for element '" + e.name + "' (property '" + name + "' is missing)");
        }
        if (!parse_number(tok[i], s.kind, s.size, to ? to : &scratch)) {
          fail(path, where + "value " + str(i + 1) + " '" + printable(tok[i]) + "' is not " +
                         (s.kind == Kind::kFloat ? "a number" : "an integer in range") + " for property '" + name +
                         "'");
        }
        return tok[i++];
      };
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        const Property& q = e.properties[p];
        if (!q.list) {
          number(q.type, q.name, sink.keeps(k) ? sink.slot(e, k, row, p) : nullptr);
          continue;
        }
        std::uint64_t n = 0;
        if (!parse_count(number(q.count_type, q.name, nullptr), n)) {
          fail(path, where + "the length of list '" + q.name + "' is not a non-negative integer");
        }
        for (std::uint64_t j = 0; j < n; ++j) number(q.type, q.name, nullptr);
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

/// A binary body, its size checked as it is walked: rows of scalars by multiplication, rows with lists by
/// reading every list length (each row holds at least one byte, so this ends within the file). The values
/// the sink wants are read (byte-swapped from big endian) where it says.
class BinaryBody {
 public:
  BinaryBody(const std::string& path, const PlyText& h, std::uint64_t size, std::istream& in)
      : path_(path), big_(h.format == PlyText::kBig), left_(size - h.data_offset), in_(in) {}

  void element(const Element& e, std::size_t k, Sink& sink) {
    if (e.count == 0) return;  // (and rows without properties have none: see read_ply_header)
    if (!e.has_list()) {
      const std::uint64_t row = e.row_bytes();
      if (e.count > left_ / row) truncated(e, left_ / row);
      left_ -= e.count * row;
      if (!sink.keeps(k)) {
        in_.ignore(static_cast<std::streamsize>(e.count * row));
        return;
      }
      std::vector<char> block(e.count * row);
      in_.read(block.data(), static_cast<std::streamsize>(block.size()));
      for (std::uint64_t r = 0; r < e.count; ++r) {
        std::uint64_t at = r * row;
        for (std::size_t p = 0; p < e.properties.size(); at += e.properties[p].type.size, ++p)
          store(sink.slot(e, k, r, p), block.data() + at, e.properties[p].type.size);
      }
      return;
    }
    for (std::uint64_t r = 0; r < e.count; ++r)
      for (std::size_t p = 0; p < e.properties.size(); ++p) property(e, r, e.properties[p], sink.slot(e, k, r, p));
  }

 private:
  void property(const Element& e, std::uint64_t r, const Property& p, void* to) {
    if (!p.list) {
      char v[8];
      take(e, r, p.type.size, v);
      store(to, v, p.type.size);
      return;
    }
    unsigned char b[4] = {0, 0, 0, 0};
    const int cs = p.count_type.size;
    take(e, r, cs, reinterpret_cast<char*>(b));
    std::uint64_t n = 0;
    for (int k = 0; k < cs; ++k) n |= static_cast<std::uint64_t>(b[big_ ? cs - 1 - k : k]) << (8 * k);
    if (p.count_type.kind == Kind::kSigned && (n >> (8 * cs - 1)) & 1) {
      fail(path_, "the data section is corrupt: row " + str(r) + " of element '" + e.name +
                      "' has a negative length of list '" + p.name + "'");
    }
    if (n > left_ / p.type.size) truncated(e, r);
    left_ -= n * p.type.size;
    in_.ignore(static_cast<std::streamsize>(n * p.type.size));
  }
  /// Reads `bytes` bytes of row r of e into `to`.
  void take(const Element& e, std::uint64_t r, int bytes, char* to) {
    if (left_ < static_cast<std::uint64_t>(bytes) || !in_.read(to, bytes)) truncated(e, r);
    left_ -= bytes;
  }
  void store(void* to, const char* from, int bytes) const {
    if (!to) return;
    char v[8];
    for (int i = 0; i < bytes; ++i) v[i] = from[big_ ? bytes - 1 - i : i];  // the host is little endian
    std::memcpy(to, v, bytes);
  }
  [[noreturn]] void truncated(const Element& e, std::uint64_t row) const {
    fail(path_, "the data section is truncated: element '" + e.name + "' needs more bytes than the file has (row " +
                    str(row) + " of " + str(e.count) + ")");
  }

  const std::string& path_;
  bool big_;
  std::uint64_t left_;
  std::istream& in_;
};

}  // namespace

RawCloud read_ply(const std::string& path) {
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
  RawCloud out;
  Sink sink(h, out);
  if (h.format == PlyText::kAscii) {
    read_ascii_rows(path, h, in, sink);
  } else {
    BinaryBody body(path, h, size, in);
    for (std::size_t k = 0; k < h.elements.size(); ++k) body.element(h.elements[k], k, sink);
  }
  // A camera element's viewport re-sizes the cloud after the vertices are read; it must still hold them all.
  out.width = sink.has_viewport[0] ? static_cast<std::uint32_t>(sink.viewport[0]) : h.width;
  out.height = sink.has_viewport[1] ? static_cast<std::uint32_t>(sink.viewport[1]) : h.height;
  if (out.width * out.height != vertex->count) {
    fail(path, "the cloud's organisation (" + str(out.width) + " x " + str(out.height) +
                   ", from obj_info or the camera element) does not match its " + str(vertex->count) + " vertices");
  }
  out.encoding = h.format == PlyText::kAscii    ? "ascii"
                 : h.format == PlyText::kLittle ? "binary_little_endian"
                                                : "binary_big_endian";
  return out;
}

}  // namespace graspmix::cloud_check
