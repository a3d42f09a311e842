#pragma once
// Array types shared across graspmix: batches are row-major (N, d) as they arrive from numpy.
#include <Eigen/Core>

namespace graspmix {

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
/// A batch of poses, one [x, y, z, qx, qy, qz, qw] per row.
using PoseArray = Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>;
/// A batch of 3-vectors (points, normals, rotation vectors), one per row.
using Vec3Array = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// A batch of quaternions, one [qx, qy, qz, qw] per row.
using QuatArray = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

}  // namespace graspmix
