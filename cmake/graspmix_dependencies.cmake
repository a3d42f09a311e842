# Finds every system library graspmix links and wraps each in an interface target, so that
# src/ links graspmix::pcl, graspmix::fcl, ... and no dependency leaks into the public headers.
include(graspmix_find_dependencies)

# PCL's algorithms (filters, features, kd-trees, sample consensus, segmentation) are templates compiled
# here from PCL's headers (PCL_NO_PRECOMPILE) instead of linked from its precompiled libraries: those hold
# every point type's instantiation and took ~150 ms of relocations to load, in every process that imports
# graspmix, for the few classes graspmix uses. Linked: pcl_common and FLANN. Not pcl_io: the cloud files are
# read and written by graspmix itself (src/perception/cloud_check*.cpp), since pcl_io brought VTK and OpenNI into
# every process and MPI C into every program that finds graspmix.
add_library(graspmix_pcl INTERFACE)
target_include_directories(graspmix_pcl SYSTEM INTERFACE ${PCL_INCLUDE_DIRS})
target_link_libraries(graspmix_pcl INTERFACE ${PCL_COMMON_LIBRARIES} FLANN::FLANN)
target_compile_definitions(graspmix_pcl INTERFACE ${PCL_DEFINITIONS} PCL_NO_PRECOMPILE)
add_library(graspmix::pcl ALIAS graspmix_pcl)

# LZF, the compression of binary_compressed PCD files: Debian's liblzf (its decoder checks every reference).
add_library(graspmix_lzf INTERFACE)
target_link_libraries(graspmix_lzf INTERFACE liblzf::liblzf)
add_library(graspmix::lzf ALIAS graspmix_lzf)

add_library(graspmix_fcl INTERFACE)
target_link_libraries(graspmix_fcl INTERFACE fcl)
add_library(graspmix::fcl ALIAS graspmix_fcl)

add_library(graspmix_octomap INTERFACE)
target_include_directories(graspmix_octomap SYSTEM INTERFACE ${OCTOMAP_INCLUDE_DIRS})
target_link_libraries(graspmix_octomap INTERFACE ${OCTOMAP_LIBRARIES})
add_library(graspmix::octomap ALIAS graspmix_octomap)

add_library(graspmix_bullet INTERFACE)
target_include_directories(graspmix_bullet SYSTEM INTERFACE ${BULLET_ROOT_DIR}/${BULLET_INCLUDE_DIR})
target_compile_definitions(graspmix_bullet INTERFACE BT_USE_DOUBLE_PRECISION)
set(_graspmix_bullet_libs "")
foreach(lib ${BULLET_LIBRARIES})
  find_library(_graspmix_lib_${lib} NAMES ${lib} PATHS ${BULLET_ROOT_DIR}/${BULLET_LIBRARY_DIRS} REQUIRED)
  list(APPEND _graspmix_bullet_libs ${_graspmix_lib_${lib}})
endforeach()
target_link_libraries(graspmix_bullet INTERFACE ${_graspmix_bullet_libs})
add_library(graspmix::bullet ALIAS graspmix_bullet)

# urdfdom's CMake config carries no version; its pkg-config file does.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(GRASPMIX_URDFDOM_PC QUIET urdfdom)
endif()
add_library(graspmix_urdfdom INTERFACE)
target_include_directories(graspmix_urdfdom SYSTEM INTERFACE ${urdfdom_INCLUDE_DIRS})
target_link_libraries(graspmix_urdfdom INTERFACE ${urdfdom_LIBRARIES})
# TinyXML, urdfdom's own parser, reads the <graspmix> element of a hand's URDF that urdfdom skips.
find_path(GRASPMIX_TINYXML_INCLUDE_DIR tinyxml.h REQUIRED)
find_library(GRASPMIX_TINYXML_LIBRARY tinyxml REQUIRED)
target_include_directories(graspmix_urdfdom SYSTEM INTERFACE ${GRASPMIX_TINYXML_INCLUDE_DIR})
target_link_libraries(graspmix_urdfdom INTERFACE ${GRASPMIX_TINYXML_LIBRARY})
add_library(graspmix::urdfdom ALIAS graspmix_urdfdom)

add_library(graspmix_assimp INTERFACE)
target_link_libraries(graspmix_assimp INTERFACE assimp::assimp)
add_library(graspmix::assimp ALIAS graspmix_assimp)

add_library(graspmix_qhull INTERFACE)
target_link_libraries(graspmix_qhull INTERFACE Qhull::qhullcpp Qhull::qhull_r)
add_library(graspmix::qhull ALIAS graspmix_qhull)

set(GRASPMIX_DEP_VERSIONS
  "GRASPMIX_PCL_VERSION=\"${PCL_VERSION}\""
  "GRASPMIX_FCL_VERSION=\"${fcl_VERSION}\""
  "GRASPMIX_OCTOMAP_VERSION=\"${OCTOMAP_VERSION}\""
  "GRASPMIX_BULLET_VERSION=\"${BULLET_VERSION_STRING}\""
  "GRASPMIX_URDFDOM_VERSION=\"${GRASPMIX_URDFDOM_PC_VERSION}\""
  "GRASPMIX_ASSIMP_VERSION=\"${assimp_VERSION}\"")
