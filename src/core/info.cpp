#include "graspmix/core/info.hpp"

#include <LinearMath/btScalar.h>
#include <fcl/config.h>
#include <pcl/pcl_config.h>
#include <Eigen/Core>

namespace graspmix {

std::map<std::string, std::string> build_info() {
  std::map<std::string, std::string> v;
  v["graspmix"] = GRASPMIX_VERSION;
  v["eigen"] = std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
               std::to_string(EIGEN_MINOR_VERSION);
  v["pcl"] = PCL_VERSION_PRETTY;
  v["fcl"] = FCL_VERSION;
  v["octomap"] = GRASPMIX_OCTOMAP_VERSION;
  v["bullet"] = std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100) +
                (btIsDoublePrecision() ? " (double precision)" : " (single precision)");
  v["urdfdom"] = GRASPMIX_URDFDOM_VERSION;
  v["assimp"] = GRASPMIX_ASSIMP_VERSION;
#ifdef _OPENMP
  v["openmp"] = std::to_string(_OPENMP);
#else
  v["openmp"] = "off";
#endif
  return v;
}

}  // namespace graspmix
