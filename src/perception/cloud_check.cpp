// The PCD reader: header, body and their checks (see cloud_check.hpp).
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include <lzf.h>

#include "cloud_check.hpp"

namespace graspmix::cloud_check {

namespace {

/// LZF's longest back reference is 3 bytes long and copies 264, so no LZF stream expands more.
constexpr std::uint64_t kLzfMaxExpansion = 88;

struct PcdField {
  std::string name;
  int size = 4;
  char type = 'F';
  std::uint64_t count = 1;
};

/// The header as read: every keyword line, in the order PCL's reader needs.
struct PcdText {
  enum Data { kAscii, kBinary, kBinaryCompressed } data = kAscii;
  std::vector<PcdField> fields;
  bool has_size = false, has_type = false, has_width = false, has_height = false, has_points = false;
  std::uint64_t width = 0, height = 0, points = 0;
  std::uint64_t point_step = 0;   ///< bytes per point: sum of SIZE * COUNT
  std::uint64_t data_offset = 0;  ///< byte offset of the body (just after the DATA line)
  int data_line = 0;              ///< line number of DATA
  std::array<float, 7> viewpoint = {0, 0, 0, 1, 0, 0, 0};
};

// Keywords in the order the PCD format (and PCL's reader, which computes offsets as it goes) needs them.
const char* const kKeywords[] = {"VERSION", "FIELDS", "SIZE",      "TYPE",   "COUNT",
                                 "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
enum { kVersion, kFields, kSize, kType, kCount, kWidth, kHeight, kViewpoint, kPoints, kData, kNone };

int keyword_rank(std::string_view key) {
  if (key == "COLUMNS") return kFields;  // PCD 0.5's name for FIELDS
  for (int i = 0; i < kNone; ++i)
    if (key == kKeywords[i]) return i;
  return kNone;
}

class HeaderError {
 public:
  HeaderError(const std::string& path, int line) : path_(path), line_(line) {}
  [[noreturn]] void operator()(const std::string& what) const {
    fail(path_, "not a valid PCD header: line " + std::to_string(line_) + ": " + what);
  }

 private:
  const std::string& path_;
  int line_;
};

std::uint64_t header_count(const std::vector<std::string_view>& tok, const char* key, const HeaderError& bad) {
  std::uint64_t v = 0;
  if (tok.size() != 2 || !parse_count(tok[1], v)) {
    bad(std::string(key) + " must be one non-negative integer, got '" +
        (tok.size() > 1 ? printable(tok[1]) : std::string()) + "'");
  }
  if (v > std::numeric_limits<std::uint32_t>::max()) bad(std::string(key) + " " + str(v) + " exceeds 2^32 - 1");
  return v;
}

/// One field list line (SIZE, TYPE, COUNT) with one entry per field.
void per_field(const std::vector<std::string_view>& tok, PcdText& h, const HeaderError& bad) {
  const std::string key(tok[0]);
  if (h.fields.empty()) bad(key + " comes before FIELDS");
  if (tok.size() - 1 != h.fields.size()) {
    bad(key + " has " + str(tok.size() - 1) + " entries, FIELDS has " + str(h.fields.size()));
  }
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    PcdField& f = h.fields[i];
    const std::string_view t = tok[i + 1];
    std::uint64_t v = 0;
    const std::string what = key + " of field '" + printable(f.name) + "' ";
    if (key == "SIZE") {
      if (!parse_count(t, v) || (v != 1 && v != 2 && v != 4 && v != 8))
        bad(what + "must be 1, 2, 4 or 8, got '" + printable(t) + "'");
      f.size = static_cast<int>(v);
    } else if (key == "TYPE") {
      if (t != "F" && t != "I" && t != "U") bad(what + "must be F, I or U, got '" + printable(t) + "'");
      f.type = t[0];
      if (f.type == 'F' && f.size != 4 && f.size != 8) bad(what + "F needs SIZE 4 or 8, got " + std::to_string(f.size));
    } else {
      if (!parse_count(t, v) || v < 1 || v > (1u << 24))
        bad(what + "must be an integer in [1, 2^24], got '" + printable(t) + "'");
      f.count = v;
    }
  }
}

void read_keyword(int rank, const std::vector<std::string_view>& tok, PcdText& h, const HeaderError& bad) {
  switch (rank) {
    case kFields:
      if (tok.size() < 2) bad("FIELDS names no field");
      for (std::size_t i = 1; i < tok.size(); ++i) h.fields.push_back({std::string(tok[i])});
      break;
    case kSize:
      h.has_size = true;
      per_field(tok, h, bad);
      break;
    case kType:
      if (!h.has_size) bad("TYPE comes before SIZE");
      h.has_type = true;
      per_field(tok, h, bad);
      break;
    case kCount:
      if (!h.has_type) bad("COUNT comes before SIZE and TYPE");
      per_field(tok, h, bad);
      break;
    case kWidth:
      h.width = header_count(tok, "WIDTH", bad);
      h.has_width = true;
      break;
    case kHeight:
      h.height = header_count(tok, "HEIGHT", bad);
      h.has_height = true;
      break;
    case kPoints:
      h.points = header_count(tok, "POINTS", bad);
      h.has_points = true;
      break;
    case kViewpoint:
      if (tok.size() != 8) bad("VIEWPOINT needs 7 numbers (tx ty tz qw qx qy qz), got " + str(tok.size() - 1));
      for (std::size_t i = 1; i < 8; ++i) {  // floats, as PCL reads them
        float& v = h.viewpoint[i - 1];
        if (!parse_number(tok[i], Kind::kFloat, 4, &v) || !std::isfinite(v)) {
          bad("VIEWPOINT value '" + printable(tok[i]) + "' is not a finite number");
        }
      }
      break;
    case kData:
      if (tok.size() != 2) bad("DATA needs one of ascii, binary, binary_compressed");
      if (tok[1] == "ascii")
        h.data = PcdText::kAscii;
      else if (tok[1] == "binary")
        h.data = PcdText::kBinary;
      else if (tok[1] == "binary_compressed")
        h.data = PcdText::kBinaryCompressed;
      else
        bad("unknown DATA '" + printable(tok[1]) + "' (expected ascii, binary or binary_compressed)");
      break;
    default:
      break;  // VERSION: any
  }
}

/// Reads the header lines up to DATA; the stream is left at the body.
PcdText read_pcd_header(const std::string& path, std::istream& in) {
  PcdText h;
  std::string line;
  std::uint64_t offset = 0;
  int line_no = 0, last = -1;
  while (std::getline(in, line)) {
    ++line_no;
    offset += line.size() + (in.eof() ? 0 : 1);
    if (offset > kMaxHeaderBytes) fail(path, "not a valid PCD header: no DATA line in the first 1 MiB");
    if (line.empty()) continue;  // skipped by PCL too
    const HeaderError bad(path, line_no);
    const auto tok = split_tokens(line);
    if (tok.empty()) bad("a blank line (PCL's reader would end the header there)");
    if (tok[0][0] == '#') continue;
    const int rank = keyword_rank(tok[0]);
    if (rank == kNone) {
      bad("'" + printable(tok[0]) +
          "' is not a PCD keyword (VERSION, FIELDS, SIZE, TYPE, COUNT, "
          "WIDTH, HEIGHT, VIEWPOINT, POINTS, DATA)");
    }
    if (rank <= last)
      bad(std::string(kKeywords[rank]) +
          " is repeated or out of order (expected the order "
          "VERSION FIELDS SIZE TYPE COUNT WIDTH HEIGHT VIEWPOINT POINTS DATA)");
    last = rank;
    read_keyword(rank, tok, h, bad);
    if (rank == kData) {
      h.data_offset = offset;
      h.data_line = line_no;
      return h;
    }
  }
  fail(path, "not a valid PCD header: it ends without a DATA line");
}

/// FIELDS/SIZE/TYPE present and agreeing, WIDTH x HEIGHT == POINTS (PCL's defaults for missing ones).
void check_pcd_counts(const std::string& path, PcdText& h) {
  const std::string bad = "not a valid PCD header: ";
  if (h.fields.empty()) fail(path, bad + "no FIELDS line");
  if (!h.has_size || !h.has_type) fail(path, bad + "FIELDS needs SIZE and TYPE lines");
  if (!h.has_points) fail(path, bad + "no POINTS line");
  if (!h.has_width && !h.has_height) h.width = h.points, h.height = 1;
  if (!h.has_width && h.has_height) fail(path, bad + "HEIGHT given without WIDTH");
  if (!h.has_height) h.height = 1;
  if (h.width * h.height != h.points) {
    fail(path, bad + "WIDTH " + str(h.width) + " x HEIGHT " + str(h.height) + " != POINTS " + str(h.points));
  }
  if (h.points == 0) fail(path, "the cloud is empty (the header declares 0 points)");
  std::uint64_t step = 0;
  for (const auto& f : h.fields) step += f.count * static_cast<std::uint64_t>(f.size);  // <= 2^24 * 8 per field
  if (step > std::numeric_limits<std::uint32_t>::max()) fail(path, bad + "a point of " + str(step) + " bytes");
  h.point_step = step;
}

/// The fields of the header, laid out row by row (binary_compressed: field by field) over `points` points.
RawCloud layout(const PcdText& h) {
  RawCloud c;
  c.width = h.width;
  c.height = h.height;
  c.viewpoint = h.viewpoint;
  const char* encodings[] = {"ascii", "binary", "binary_compressed"};
  c.encoding = encodings[h.data];
  std::uint64_t at = 0;
  for (const auto& f : h.fields) {
    Field field{f.name,
                f.type == 'F'   ? Kind::kFloat
                : f.type == 'I' ? Kind::kSigned
                                : Kind::kUnsigned,
                f.size, f.count};
    const std::uint64_t bytes = f.count * static_cast<std::uint64_t>(f.size);
    // binary_compressed holds each field's values for every point, then the next field's (PCL's writer).
    const bool by_field = h.data == PcdText::kBinaryCompressed;
    field.start = by_field ? at * h.points : at;
    field.stride = by_field ? bytes : h.point_step;
    at += bytes;
    c.names.push_back(f.name);
    c.fields.push_back(std::move(field));
  }
  return c;
}

std::uint32_t le32(const unsigned char* b) {
  return b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
}

/// Binary and binary_compressed bodies: checks the sizes the header implies against the file, then reads them
/// (a binary_compressed body is decompressed by liblzf, whose decoder checks every reference).
void read_binary_body(const std::string& path, const PcdText& h, std::uint64_t size, std::istream& in, RawCloud& out) {
  const std::uint64_t body = size - h.data_offset;
  const std::string declared = str(h.points) + " points x " + str(h.point_step) + " bytes";
  const std::uint64_t bytes = h.points * h.point_step;
  if (h.data == PcdText::kBinary) {
    if (h.points > body / h.point_step) {
      fail(path, "the data section is truncated: the header declares " + declared + ", only " + str(body) +
                     " bytes follow it");
    }
    out.data.resize(bytes);
    if (!in.read(reinterpret_cast<char*>(out.data.data()), static_cast<std::streamsize>(bytes))) {
      fail(path, "cannot read the data section");
    }
    return;
  }
  unsigned char sizes[8];
  if (body < 8 || !in.read(reinterpret_cast<char*>(sizes), 8)) {
    fail(path, "the binary_compressed data section is truncated: " + str(body) +
                   " bytes after the header, its two 4-byte sizes need 8");
  }
  const std::uint64_t compressed = le32(sizes), uncompressed = le32(sizes + 4);
  if (compressed > body - 8) {
    fail(path, "the binary_compressed data section is truncated: it declares " + str(compressed) +
                   " compressed bytes, only " + str(body - 8) + " follow");
  }
  if (uncompressed != bytes) {
    fail(path, "the binary_compressed data section declares " + str(uncompressed) +
                   " uncompressed bytes, the header's " + declared + " make " + str(bytes));
  }
  if (uncompressed > kLzfMaxExpansion * compressed) {
    fail(path, "the binary_compressed data section is corrupt: " + str(compressed) + " compressed bytes cannot hold " +
                   str(uncompressed) + " (LZF expands at most 88 times)");
  }
  std::vector<char> packed(compressed);
  if (!in.read(packed.data(), static_cast<std::streamsize>(compressed))) fail(path, "cannot read the data section");
  out.data.resize(bytes);
  const unsigned int got = lzf_decompress(packed.data(), static_cast<unsigned int>(compressed), out.data.data(),
                                          static_cast<unsigned int>(bytes));
  if (got != bytes) fail(path, "cannot read the data section (corrupt binary_compressed data)");
}

/// What every token of an ASCII row must parse as, and where its value goes in the point's row; PCL skips
/// the padding fields named "_".
struct TokenRule {
  Kind kind;
  int size;
  bool skip;
  const PcdField* field;
  std::uint64_t at;
};

std::vector<TokenRule> token_rules(const std::vector<PcdField>& fields) {
  std::vector<TokenRule> rules;
  std::uint64_t at = 0;
  for (const auto& f : fields) {
    const Kind k = f.type == 'F' ? Kind::kFloat : f.type == 'I' ? Kind::kSigned : Kind::kUnsigned;
    for (std::uint64_t c = 0; c < f.count; ++c, at += f.size) rules.push_back({k, f.size, f.name == "_", &f, at});
  }
  return rules;
}

/// ASCII body: exactly POINTS rows, each with one number of the right kind per field entry, read into `out`.
void read_ascii_body(const std::string& path, const PcdText& h, std::istream& in, RawCloud& out) {
  const std::vector<TokenRule> rules = token_rules(h.fields);
  std::string line;
  std::uint64_t rows = 0;
  for (int line_no = h.data_line + 1; std::getline(in, line); ++line_no) {
    if (line.empty()) continue;  // PCL skips empty lines
    const auto tok = split_tokens(line);
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (rows == h.points) {
      if (tok.empty()) continue;
      fail(path, where + "more data rows than the " + str(h.points) + " points the header declares");
    }
    if (tok.empty()) fail(path, where + "a blank data row (PCL would read it as a point of zeros)");
    if (tok.size() < rules.size() && in.eof()) {  // the last line, with no newline: cut off
      fail(path, "the data section is truncated: " + where + str(tok.size()) + " of " + str(rules.size()) +
                     " values of point " + str(rows + 1) + " of " + str(h.points));
    }
    if (tok.size() != rules.size()) {
      fail(path, where + str(tok.size()) + " values, the header's fields need " + str(rules.size()));
    }
    // Each row grows the cloud by one point, so the memory is bounded by the file's size, not by POINTS.
    out.data.resize(out.data.size() + h.point_step);
    std::uint8_t* row = out.data.data() + rows * h.point_step;
    for (std::size_t i = 0; i < tok.size(); ++i) {
      const TokenRule& r = rules[i];
      if (r.skip || parse_number(tok[i], r.kind, r.size, row + r.at)) continue;
      fail(path, where + "value " + str(i + 1) + " '" + printable(tok[i]) + "' is not " +
                     (r.kind == Kind::kFloat ? "a number" : "an integer in range") + " for field '" +
                     printable(r.field->name) + "' (TYPE " + r.field->type + " SIZE " + std::to_string(r.size) + ")");
    }
    ++rows;
  }
  if (rows < h.points) {
    fail(path, "the data section is truncated: " + str(rows) + " of " + str(h.points) + " declared points present");
  }
}

}  // namespace

RawCloud read_pcd(const std::string& path) {
  const std::uint64_t size = file_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open for reading");
  PcdText h = read_pcd_header(path, in);
  check_pcd_counts(path, h);
  RawCloud out = layout(h);
  if (h.data == PcdText::kAscii) {
    read_ascii_body(path, h, in, out);
  } else {
    read_binary_body(path, h, size, in, out);
  }
  return out;
}

}  // namespace graspmix::cloud_check
