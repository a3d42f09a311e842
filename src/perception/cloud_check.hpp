#pragma once
// graspmix's own readers of cloud files, each checking a file against its own header (private to perception).
// Every header is parsed here and compared with the file's size before a body is read, and every ASCII row is
// checked against the header as it is read: every allocation is bounded by the file's size, and a short, long or
// non-numeric row, or a binary_compressed body that does not decode to the size it declares, is an error rather
// than zeros (PCL's readers, which these replace, trust a header). The bodies are read as PCL 1.13's readers read
// them (field names, organisation, values), so CloudData stays what it was. A failure throws
// std::invalid_argument naming the file and, for text, the line.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error \
    "the cloud readers and writers keep binary values in the host's order, which is PCD's only on little-endian hosts"
#endif

namespace graspmix::cloud_check {

/// A header longer than this is not a header (real ones are a few hundred bytes); it also bounds the
/// search for the end of a header in a file that has none.
inline constexpr std::uint64_t kMaxHeaderBytes = 1u << 20;

/// The error of a bad file: its path, then what is wrong.
[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what);
}

inline std::string str(std::uint64_t v) { return std::to_string(v); }

/// Numeric kinds of a field and of the text tokens that hold its values.
enum class Kind { kFloat, kSigned, kUnsigned };

/// One field of a cloud in memory: entry c of point i is the `size`-byte number of `kind` at
/// data[start + i * stride + c * size], in the host's byte order.
struct Field {
  std::string name;
  Kind kind = Kind::kFloat;
  int size = 4;
  std::uint64_t count = 1;
  std::uint64_t start = 0, stride = 0;
};

/// A cloud file as read: the values of its fields for width x height points (row by row).
struct RawCloud {
  std::vector<std::string> names;  ///< every field of the file in file order, named as PCL's readers name them
  std::vector<Field> fields;       ///< the fields with values in `data` (a PLY's scalar vertex properties)
  std::vector<std::uint8_t> data;
  std::uint64_t width = 0, height = 0;
  std::array<float, 7> viewpoint = {0, 0, 0, 1, 0, 0, 0};  ///< the PCD VIEWPOINT: tx ty tz qw qx qy qz
  std::string encoding;                                    ///< PCD: ascii, binary or binary_compressed
};

/// Reads a .pcd file (ascii, binary, binary_compressed), checked as described above.
RawCloud read_pcd(const std::string& path);

/// Reads the vertices of a .ply file (ascii, binary little or big endian), checked as described above.
/// Like PCL 1.13's reader: uchar red green blue (or diffuse_*) are named one field "rgb" ("rgba" with alpha),
/// nx ny nz are normal_x normal_y normal_z, the organisation is obj_info's num_cols x num_rows or the camera
/// element's viewport, else the vertex count x 1; the file's camera pose is not read (PCL 1.13 drops it).
RawCloud read_ply(const std::string& path);

/// What a .npy header says; the caller checks dtype and shape against what it reads.
struct NpyHeader {
  std::string descr;  ///< e.g. "<f8"
  bool fortran = false;
  std::vector<std::uint64_t> shape;  ///< every entry non-negative
  std::uint64_t data_offset = 0;     ///< the array's first byte
  std::uint64_t file_size = 0;
};

/// Checks a .npy file's preamble and header dictionary (version 1 to 3) against the file's size.
NpyHeader check_npy(const std::string& path);

// ---- shared by the readers (cloud_text.cpp; tested through load_cloud) ----

/// The file's size in bytes; throws naming the file when it cannot be read.
std::uint64_t file_size(const std::string& path);

/// Tokens of a line split at spaces, tabs and carriage returns (as PCL splits PCD and PLY text).
std::vector<std::string_view> split_tokens(std::string_view line);

/// Parses a whole text token as a number of `kind` whose binary size is `size` bytes and stores it at `out`
/// (host byte order); false when it is not one: a decimal float (nan and inf included; out of the type's range:
/// +-inf or +-0, as PCL's reader makes it) for kFloat, an integer within the type's range otherwise.
bool parse_number(std::string_view token, Kind kind, int size, void* out);

/// A token of the file for a message: at most 40 characters, bytes outside printable ASCII as \xNN (the
/// message must stay one line of valid UTF-8 whatever the file holds).
std::string printable(std::string_view token);

/// Parses a non-negative decimal integer (digits only, at most 2^63 - 1); false otherwise.
bool parse_count(std::string_view token, std::uint64_t& value);

}  // namespace graspmix::cloud_check
