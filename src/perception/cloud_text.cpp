// The text helpers the cloud readers share (see cloud_check.hpp).
#include <sys/stat.h>
#include <charconv>
#include <cstring>
#include <limits>

#include "cloud_check.hpp"

namespace graspmix::cloud_check {

namespace {

/// For a decimal token from_chars found out of range: true when its magnitude is too large (it overflows),
/// false when too small (it underflows). The token is known to be [-]digits[.digits][(e|E)[+-]digits].
bool overflows(std::string_view t) {
  std::size_t i = t[0] == '-' ? 1 : 0;
  std::int64_t int_digits = 0, frac_digits = 0, first = 0;  // first: the 1-based place of the first nonzero digit
  bool point = false, fraction_first = false;
  for (; i < t.size() && t[i] != 'e' && t[i] != 'E'; ++i) {
    if (t[i] == '.') {
      point = true;
      continue;
    }
    (point ? frac_digits : int_digits) += 1;
    if (first == 0 && t[i] != '0') first = point ? frac_digits : int_digits, fraction_first = point;
  }
  // The decimal exponent of the first nonzero digit, without the token's exponent.
  const std::int64_t lead = fraction_first ? -first : int_digits - first;
  if (i == t.size()) return lead > 0;
  std::string_view e = t.substr(i + 1);
  if (!e.empty() && e[0] == '+') e.remove_prefix(1);
  std::int64_t exponent = 0;
  const auto r = std::from_chars(e.data(), e.data() + e.size(), exponent);
  // An exponent this large decides alone (no token has a million digits before it that could offset it).
  if (r.ec != std::errc() || exponent > 1000000 || exponent < -1000000) return e[0] != '-';
  return lead + exponent > 0;
}

template <typename T>
bool parse_float(std::string_view t, void* out) {
  T v{};
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ptr != t.data() + t.size()) return false;
  if (r.ec == std::errc::result_out_of_range) {
    v = overflows(t) ? std::numeric_limits<T>::infinity() : T(0);
    if (t[0] == '-') v = -v;
  } else if (r.ec != std::errc()) {
    return false;
  }
  std::memcpy(out, &v, sizeof v);
  return true;
}

template <typename T, typename Wide>
bool parse_integer(std::string_view t, void* out) {
  Wide v = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ptr != t.data() + t.size() || r.ec != std::errc()) return false;
  if (v < static_cast<Wide>(std::numeric_limits<T>::min()) || v > static_cast<Wide>(std::numeric_limits<T>::max()))
    return false;
  const T narrow = static_cast<T>(v);
  std::memcpy(out, &narrow, sizeof narrow);
  return true;
}

}  // namespace

std::uint64_t file_size(const std::string& path) {
  struct stat st{};
  if (::stat(path.c_str(), &st) != 0) fail(path, "no such file");
  return static_cast<std::uint64_t>(st.st_size);
}

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool parse_number(std::string_view t, Kind kind, int size, void* out) {
  if (!t.empty() && t[0] == '+') {
    t.remove_prefix(1);  // C++ streams, which PCL reads with, accept a '+'
    if (!t.empty() && t[0] == '-') return false;
  }
  if (t.empty()) return false;
  if (kind == Kind::kFloat) return size == 4 ? parse_float<float>(t, out) : parse_float<double>(t, out);
  if (kind == Kind::kSigned) {
    switch (size) {
      case 1:
        return parse_integer<std::int8_t, long long>(t, out);
      case 2:
        return parse_integer<std::int16_t, long long>(t, out);
      case 4:
        return parse_integer<std::int32_t, long long>(t, out);
      default:
        return parse_integer<std::int64_t, long long>(t, out);
    }
  }
  switch (size) {
    case 1:
      return parse_integer<std::uint8_t, unsigned long long>(t, out);
    case 2:
      return parse_integer<std::uint16_t, unsigned long long>(t, out);
    case 4:
      return parse_integer<std::uint32_t, unsigned long long>(t, out);
    default:
      return parse_integer<std::uint64_t, unsigned long long>(t, out);
  }
}

std::string printable(std::string_view token) {
  std::string out;
  for (const char ch : token.substr(0, 40)) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f) {
      out += ch;
    } else {
      const char* hex = "0123456789abcdef";
      out += {'\\', 'x', hex[c >> 4], hex[c & 15]};
    }
  }
  return out + (token.size() > 40 ? "..." : "");
}

bool parse_count(std::string_view t, std::uint64_t& value) {
  if (t.empty() || t.find_first_not_of("0123456789") != std::string_view::npos) return false;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
  return r.ec == std::errc() && value <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
}

}  // namespace graspmix::cloud_check
