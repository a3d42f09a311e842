// The PCD and PLY writers (see cloud_write.hpp).
#include "cloud_write.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

#include <lzf.h>

#include "cloud_check.hpp"

namespace graspmix::cloud_write {

namespace {

using cloud_check::fail;

/// A float as the shortest text that reads back to the same float; "nan" for every NaN (PCL's spelling).
void append_float(std::string& out, float v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

std::ofstream open_for_writing(const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail(path, "cannot open for writing (is the directory there and writable?)");
  return out;
}

void finish(const std::string& path, std::ofstream& out) {
  out.close();
  if (!out) fail(path, "cannot write (is the disk full?)");
}

/// Every point as one line of its values; written in pieces of about 1 MB.
void write_text_rows(std::ofstream& out, const FloatCloud& c) {
  const std::size_t k = c.names.size();
  std::string text;
  for (std::size_t i = 0; i < c.values.size(); ++i) {
    append_float(text, c.values[i]);
    text += (i + 1) % k == 0 ? '\n' : ' ';
    if (text.size() > (1u << 20)) out << text, text.clear();
  }
  out << text;
}

void write_binary_rows(std::ofstream& out, const FloatCloud& c) {  // the host is little endian (cloud_check.hpp)
  out.write(reinterpret_cast<const char*>(c.values.data()), static_cast<std::streamsize>(c.values.size() * 4));
}

std::string pcd_header(const FloatCloud& c, const std::string& encoding, const std::array<float, 7>& viewpoint) {
  std::string fields, sizes, types, counts, vp;
  for (const auto& name : c.names) fields += " " + name, sizes += " 4", types += " F", counts += " 1";
  for (const float v : viewpoint) vp += " ", append_float(vp, v);
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" + fields + "\nSIZE" + sizes + "\nTYPE" +
         types + "\nCOUNT" + counts + "\nWIDTH " + std::to_string(c.width) + "\nHEIGHT " + std::to_string(c.height) +
         "\nVIEWPOINT" + vp + "\nPOINTS " + std::to_string(c.values.size() / c.names.size()) + "\nDATA " + encoding +
         "\n";
}

void put_le32(char* to, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) to[i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

/// binary_compressed: every field's values for all points, then the next field's (PCL's layout, which
/// compresses better), LZF-compressed behind the compressed and the uncompressed size (4 bytes each).
std::vector<char> compressed_body(const std::string& path, const FloatCloud& c) {
  const std::size_t k = c.names.size(), n = c.values.size() / k;
  const std::uint64_t bytes = c.values.size() * sizeof(float);
  // LZF's sizes are unsigned int, PCD's 4 bytes: the input and its worst-case output must fit in 32 bits.
  if (bytes > 0xF0000000u) {
    fail(path, "too many points for binary_compressed (" + std::to_string(bytes) +
                   " bytes; its sizes are 32-bit): write binary");
  }
  std::vector<float> by_field(c.values.size());
  for (std::size_t j = 0; j < k; ++j)
    for (std::size_t i = 0; i < n; ++i) by_field[j * n + i] = c.values[i * k + j];
  std::vector<char> out(8 + bytes + bytes / 16 + 64);  // room for LZF's worst case (about 1/32 more)
  const unsigned int size = lzf_compress(by_field.data(), static_cast<unsigned int>(bytes), out.data() + 8,
                                         static_cast<unsigned int>(out.size() - 8));
  if (size == 0) fail(path, "cannot compress the data (liblzf)");
  put_le32(out.data(), size);
  put_le32(out.data() + 4, static_cast<std::uint32_t>(bytes));
  out.resize(8 + size);
  return out;
}

}  // namespace

void write_pcd(const std::string& path, const FloatCloud& cloud, const std::string& encoding,
               const std::array<float, 7>& viewpoint) {
  std::vector<char> packed;
  if (encoding == "binary_compressed") packed = compressed_body(path, cloud);  // before the file is touched
  std::ofstream out = open_for_writing(path);
  out << pcd_header(cloud, encoding, viewpoint);
  if (encoding == "ascii") {
    write_text_rows(out, cloud);
  } else if (encoding == "binary") {
    write_binary_rows(out, cloud);
  } else {
    out.write(packed.data(), static_cast<std::streamsize>(packed.size()));
  }
  finish(path, out);
}

void write_ply(const std::string& path, const FloatCloud& cloud, bool binary) {
  std::ofstream out = open_for_writing(path);
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\ncomment graspmix\nelement vertex "
      << cloud.values.size() / cloud.names.size() << "\n";
  for (const auto& name : cloud.names) {
    const bool normal = name.rfind("normal_", 0) == 0;  // nx ny nz, the names PLY files use
    out << "property float " << (normal ? "n" + name.substr(7) : name) << "\n";
  }
  out << "end_header\n";
  if (binary) {
    write_binary_rows(out, cloud);
  } else {
    write_text_rows(out, cloud);
  }
  finish(path, out);
}

}  // namespace graspmix::cloud_write
