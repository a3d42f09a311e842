#pragma once
// graspmix's own writers of cloud files (private to perception): float32 fields as PCD (ascii, binary, and
// binary_compressed through liblzf) or PLY (ascii, binary little endian), laid out as PCL's readers read them.
// A failure throws std::invalid_argument naming the file.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace graspmix::cloud_write {

/// width x height points of float32 fields, row by row: values[i * names.size() + j] is field j of point i.
struct FloatCloud {
  std::vector<std::string> names;  ///< PCL's names: x y z [normal_x normal_y normal_z] [vp_x vp_y vp_z]
  std::vector<float> values;
  std::uint32_t width = 0, height = 1;
};

/// encoding: "ascii", "binary" or "binary_compressed"; viewpoint: the VIEWPOINT line, tx ty tz qw qx qy qz.
void write_pcd(const std::string& path, const FloatCloud& cloud, const std::string& encoding,
               const std::array<float, 7>& viewpoint);

/// ASCII or binary little endian; the normals as nx ny nz (PLY's names). PLY keeps no viewpoint and no
/// organisation (the caller refuses an organised cloud).
void write_ply(const std::string& path, const FloatCloud& cloud, bool binary);

}  // namespace graspmix::cloud_write
