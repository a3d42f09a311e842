// Reads a cloud file with graspmix's C++ API and prints what it holds: the smallest program that links the
// installed library (ctest builds it outside graspmix's tree with find_package(graspmix) in a C++-only project).
//
//   cloud_info CLOUD.pcd|.ply|.npy
//
// prints "<file>: N points (W x H, format), M invalid dropped" and, for an organised cloud, how many of its
// pixels hold a point; a bad file is one line on stderr and exit status 2.
#include <iostream>
#include <stdexcept>

#include "graspmix/perception/cloud_io.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: cloud_info CLOUD.pcd|.ply|.npy\n";
    return 2;
  }
  try {
    const graspmix::CloudData cloud = graspmix::load_cloud(argv[1]);
    std::cout << cloud.path << ": " << cloud.points.rows() << " points (" << cloud.width << " x " << cloud.height
              << ", " << cloud.format << "), " << cloud.n_invalid << " invalid dropped\n";
    if (cloud.height > 1) {
      std::cout << "organised: " << cloud.pixels.size() << " of " << graspmix::organized_grid(cloud).rows()
                << " pixels hold a point\n";
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }
  return 0;
}
