#pragma once
// Versions of graspmix and of every library it was built against, for bug reports.
#include <map>
#include <string>

namespace graspmix {

/// name -> version: graspmix, eigen, pcl, fcl, bullet, urdfdom, assimp, openmp.
std::map<std::string, std::string> build_info();

}  // namespace graspmix
