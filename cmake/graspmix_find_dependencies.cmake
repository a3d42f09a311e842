# Finds every system library graspmix links. Included by graspmix_dependencies.cmake when building and by
# the installed graspmixConfig.cmake when a program links the installed library (one list for both).

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(OpenMP REQUIRED COMPONENTS CXX)

# PCL's config still declares very old policy versions; CMake >= 4 refuses those by default.
if(NOT DEFINED CMAKE_POLICY_VERSION_MINIMUM)
  set(CMAKE_POLICY_VERSION_MINIMUM 3.5)
endif()
# QUIET: PCL's config finds VTK for pcl_2d (a part graspmix does not use), and VTK's config then reports an MPI C
# it does not need unless pcl_io is linked, which graspmix is not: a C++-only program needs no C for it.
find_package(PCL 1.10 REQUIRED QUIET COMPONENTS common filters features kdtree search sample_consensus segmentation)
# binary_compressed PCD files are LZF: Debian's liblzf.
find_package(liblzf REQUIRED CONFIG)
find_package(fcl 0.6 REQUIRED)
# Occupancy maps of what the cameras saw (ray insertion): OctoMap, which Debian's FCL is built with too.
find_package(octomap 1.9 REQUIRED)
# Bullet in double precision, as pybullet is built, so that both simulate the same numbers.
find_package(Bullet REQUIRED CONFIGS BulletConfig-float64.cmake)
find_package(urdfdom REQUIRED)
# Mesh loading (STL/OBJ collision geometry of hands and objects) goes through assimp.
find_package(assimp REQUIRED)
# Convex hulls of mesh collision geometry (hands, objects): qhull, which PCL depends on already.
find_package(Qhull REQUIRED CONFIG)
