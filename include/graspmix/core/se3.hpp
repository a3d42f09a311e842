#pragma once
// SE(3) helpers: the paper's quaternion log/exp maps (eq:log_map, eq:exp_map) in the half-angle
// convention, and pose composition and inversion, single and batched.
//
// Quaternions are [x, y, z, w]; a pose is [x, y, z, qx, qy, qz, qw].
#include <string>

#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// q with its sign chosen so that w >= 0 (q and -q are the same rotation).
Eigen::Quaterniond canonical(const Eigen::Quaterniond& q);

/// eq:log_map: log(q) = arccos(q_w) q_v / |q_v|, after canonicalising to w >= 0 so |log q| <= pi/2.
/// A rotation by angle theta about axis a maps to (theta / 2) a.
Eigen::Vector3d quat_log(const Eigen::Quaterniond& q);
/// eq:exp_map: exp(w) = [sin|w| w/|w|, cos|w|]; exp(0) = identity.
Eigen::Quaterniond quat_exp(const Eigen::Vector3d& w);

/// The quaternion [qx, qy, qz, qw] of row i of poses (N, 7), as it is (not normalised).
inline Eigen::Quaterniond row_quaternion(const Eigen::Ref<const PoseArray>& poses, Eigen::Index i) {
  return Eigen::Quaterniond(poses(i, 6), poses(i, 3), poses(i, 4), poses(i, 5));
}
/// A 7-vector pose to an isometry; throws std::invalid_argument if the quaternion is not finite or is zero.
Eigen::Isometry3d pose_from_vector(const Eigen::Ref<const Eigen::Matrix<double, 7, 1>>& pose);
/// An isometry to a 7-vector with the quaternion canonicalised to w >= 0.
Eigen::Matrix<double, 7, 1> pose_to_vector(const Eigen::Isometry3d& T);

// ---- batched forms over (N, 7) / (N, 4) / (N, 3) arrays; every row is checked -----------------
/// Row-wise log map of unit quaternions (rows are normalised; zero or non-finite rows throw).
Vec3Array batch_quat_log(const Eigen::Ref<const QuatArray>& q);
/// Row-wise exp map of rotation vectors (half-angle convention); rows come back with w >= 0 when |w| <= pi/2.
QuatArray batch_quat_exp(const Eigen::Ref<const Vec3Array>& w);
/// Row-wise a o b; either side may have one row, which is then broadcast.
PoseArray pose_multiply(const Eigen::Ref<const PoseArray>& a, const Eigen::Ref<const PoseArray>& b);
/// Row-wise inverse.
PoseArray pose_inverse(const Eigen::Ref<const PoseArray>& a);

/// Throws std::invalid_argument naming `what` if any entry of m is NaN or infinite.
void require_finite(const Eigen::Ref<const RowMatrixXd>& m, const char* what);
/// Throws std::invalid_argument naming `what` (and the value) unless v is finite.
void require_finite(double v, const std::string& what);

}  // namespace graspmix
