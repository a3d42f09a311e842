// .npy header checks (see cloud_check.hpp): numpy's format, version 1 to 3, for an (N, 3) array.
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "cloud_check.hpp"

namespace graspmix::cloud_check {

namespace {

/// The text after `'key':` in the header dictionary (spaces skipped); throws when the key is missing.
std::string_view value_of(const std::string& path, std::string_view dict, const char* key) {
  for (const char q : {'\'', '"'}) {
    const std::string quoted = std::string(1, q) + key + q;
    const auto k = dict.find(quoted);
    if (k == std::string_view::npos) continue;
    auto v = dict.find_first_not_of(' ', k + quoted.size());
    if (v == std::string_view::npos || dict[v] != ':') break;
    v = dict.find_first_not_of(' ', v + 1);
    if (v != std::string_view::npos) return dict.substr(v);
  }
  fail(path, "not a valid .npy header: no '" + std::string(key) + "' entry");
}

std::string read_descr(const std::string& path, std::string_view v) {
  const char q = v.empty() ? 0 : v[0];
  const auto end = q == '\'' || q == '"' ? v.find(q, 1) : std::string_view::npos;
  if (end == std::string_view::npos) fail(path, "not a valid .npy header: 'descr' is not a quoted string");
  return std::string(v.substr(1, end - 1));
}

std::vector<std::uint64_t> read_shape(const std::string& path, std::string_view v) {
  const auto close = v.find(')');
  if (v.empty() || v[0] != '(' || close == std::string_view::npos) {
    fail(path, "not a valid .npy header: 'shape' is not a tuple");
  }
  std::vector<std::uint64_t> dims;
  std::string_view inner = v.substr(1, close - 1);
  while (!inner.empty()) {
    const auto comma = inner.find(',');
    std::string_view tok = inner.substr(0, comma);
    while (!tok.empty() && tok.front() == ' ') tok.remove_prefix(1);
    while (!tok.empty() && tok.back() == ' ') tok.remove_suffix(1);
    if (!tok.empty() || comma == std::string_view::npos) {
      std::uint64_t d = 0;
      if (!parse_count(tok, d)) {
        fail(path, "not a valid .npy header: shape entry '" + printable(tok) + "' is not a non-negative integer");
      }
      dims.push_back(d);
    }
    if (comma == std::string_view::npos) break;
    inner.remove_prefix(comma + 1);
  }
  return dims;
}

}  // namespace

NpyHeader check_npy(const std::string& path) {
  const std::uint64_t size = file_size(path);
  std::ifstream in(path, std::ios::binary);
  unsigned char pre[12];
  if (!in.read(reinterpret_cast<char*>(pre), 8) || std::memcmp(pre, "\x93NUMPY", 6) != 0) {
    fail(path, "not a .npy file (bad magic)");
  }
  if (pre[6] < 1 || pre[6] > 3) fail(path, "unsupported .npy format version " + std::to_string(pre[6]));
  const int len_bytes = pre[6] == 1 ? 2 : 4;
  if (!in.read(reinterpret_cast<char*>(pre + 8), len_bytes)) fail(path, "truncated .npy header");
  std::uint64_t header_len = pre[8] | (pre[9] << 8);
  if (len_bytes == 4)
    header_len |= (static_cast<std::uint64_t>(pre[10]) << 16) | (static_cast<std::uint64_t>(pre[11]) << 24);
  NpyHeader h;
  h.data_offset = 8 + len_bytes + header_len;
  if (h.data_offset > size) {
    fail(path, "truncated .npy header: it declares " + std::to_string(header_len) + " bytes, the file has " +
                   std::to_string(size - 8 - len_bytes));
  }
  std::string dict(header_len, '\0');
  in.read(dict.data(), static_cast<std::streamsize>(header_len));
  h.descr = read_descr(path, value_of(path, dict, "descr"));
  const std::string_view fortran = value_of(path, dict, "fortran_order");
  if (fortran.rfind("True", 0) != 0 && fortran.rfind("False", 0) != 0) {
    fail(path, "not a valid .npy header: 'fortran_order' is neither True nor False");
  }
  h.fortran = fortran[0] == 'T';
  h.shape = read_shape(path, value_of(path, dict, "shape"));
  h.file_size = size;
  return h;
}

}  // namespace graspmix::cloud_check
