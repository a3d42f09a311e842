#pragma once
// Checks of cloud files against their own headers, run BEFORE PCL reads a body (private to perception).
// PCL's readers trust a header: they allocate what POINTS or `element vertex` claims, map a
// binary_compressed body of the size it claims (reading past the end of a short file), and load a short,
// long or non-numeric ASCII row as zeros. These checks parse every header here, compare it with the
// file's size, and for ASCII bodies read every row, so that PCL only ever sees a file that agrees with
// its header and every allocation is bounded by the file's size. A failure throws std::invalid_argument
// naming the file and, for text, the line.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace graspmix::cloud_check {

/// A header longer than this is not a header (real ones are a few hundred bytes); it also bounds the
/// search for the end of a header in a file that has none.
inline constexpr std::uint64_t kMaxHeaderBytes = 1u << 20;

/// The error of a bad file: its path, then what is wrong.
[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what);
}

inline std::string str(std::uint64_t v) { return std::to_string(v); }

/// What a checked PCD header says (only what the loader needs afterwards).
struct PcdHeader {
  enum Data { kAscii, kBinary, kBinaryCompressed } data = kAscii;
  std::uint64_t points = 0;       ///< POINTS (== WIDTH * HEIGHT)
  std::uint64_t point_step = 0;   ///< bytes per point: sum of SIZE * COUNT
  std::uint64_t data_offset = 0;  ///< byte offset of the body (just after the DATA line)
};

/// Checks a .pcd file's header and body as described above; returns the header.
PcdHeader check_pcd(const std::string& path);

/// Checks a .ply file's header, then every ASCII row or the binary body's size, as described above;
/// returns the number of vertices.
std::uint64_t check_ply(const std::string& path);

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

// ---- shared by the checkers (and tested through load_cloud) ----

/// The file's size in bytes; throws naming the file when it cannot be read.
std::uint64_t file_size(const std::string& path);

/// Tokens of a line split at spaces, tabs and carriage returns (as PCL splits PCD and PLY text).
std::vector<std::string_view> split_tokens(std::string_view line);

/// Numeric kinds a text token must parse as.
enum class Kind { kFloat, kSigned, kUnsigned };

/// True when the whole token is a number of the kind whose binary size is `size` bytes: a decimal
/// float (nan and inf included) for kFloat, an integer within the type's range otherwise.
bool is_number(std::string_view token, Kind kind, int size);

/// A token of the file for a message: at most 40 characters, bytes outside printable ASCII as \xNN (the
/// message must stay one line of valid UTF-8 whatever the file holds).
std::string printable(std::string_view token);

/// Parses a non-negative decimal integer (digits only, at most 2^63 - 1); false otherwise.
bool parse_count(std::string_view token, std::uint64_t& value);

}  // namespace graspmix::cloud_check
