#include "graspmix/core/se3.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace graspmix {

namespace {

Eigen::Quaterniond checked_quaternion(double x, double y, double z, double w, Eigen::Index row, const char* what) {
  Eigen::Quaterniond q(w, x, y, z);
  const double n = q.norm();
  if (!std::isfinite(n) || n < 1e-12) {
    throw std::invalid_argument(std::string(what) + ": row " + std::to_string(row) +
                                " is not a valid quaternion (zero, NaN or infinite)");
  }
  q.coeffs() /= n;
  return q;
}

}  // namespace

void require_finite(double v, const std::string& what) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << what << " is not finite (" << v << ")";
    throw std::invalid_argument(os.str());
  }
}

void require_finite(const Eigen::Ref<const RowMatrixXd>& m, const char* what) {
  if (!m.allFinite()) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (!m.row(i).allFinite()) {
        throw std::invalid_argument(std::string(what) + ": row " + std::to_string(i) +
                                    " contains NaN or infinite values");
      }
    }
  }
}

Eigen::Quaterniond canonical(const Eigen::Quaterniond& q) { return q.w() < 0.0 ? Eigen::Quaterniond(-q.coeffs()) : q; }

Eigen::Vector3d quat_log(const Eigen::Quaterniond& q_in) {
  const Eigen::Quaterniond q = canonical(q_in);
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return Eigen::Vector3d::Zero();
  // atan2 is accurate near both ends, where arccos(w) loses digits.
  return std::atan2(s, q.w()) * v / s;
}

Eigen::Quaterniond quat_exp(const Eigen::Vector3d& w) {
  // stableNorm scales before squaring: components up to DBL_MAX / sqrt(3) give a finite angle (norm() overflows
  // from about 1e154, and sin(inf) is NaN). sin and cos reduce any finite angle exactly.
  const double a = w.stableNorm();
  if (!std::isfinite(a)) throw std::invalid_argument("quat_exp: the rotation vector is not finite or too long");
  if (a < 1e-12) return Eigen::Quaterniond(1.0, w.x(), w.y(), w.z()).normalized();
  const Eigen::Vector3d v = std::sin(a) * (w / a);
  return Eigen::Quaterniond(std::cos(a), v.x(), v.y(), v.z()).normalized();
}

Eigen::Isometry3d pose_from_vector(const Eigen::Ref<const Eigen::Matrix<double, 7, 1>>& p) {
  if (!p.head<3>().allFinite()) throw std::invalid_argument("pose: position contains NaN or infinite values");
  const Eigen::Quaterniond q = checked_quaternion(p[3], p[4], p[5], p[6], 0, "pose");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = p.head<3>();
  return T;
}

Eigen::Matrix<double, 7, 1> pose_to_vector(const Eigen::Isometry3d& T) {
  Eigen::Matrix<double, 7, 1> out;
  const Eigen::Quaterniond q = canonical(Eigen::Quaterniond(T.linear()).normalized());
  out << T.translation(), q.x(), q.y(), q.z(), q.w();
  return out;
}

Vec3Array batch_quat_log(const Eigen::Ref<const QuatArray>& q) {
  Vec3Array out(q.rows(), 3);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    out.row(i) = quat_log(checked_quaternion(q(i, 0), q(i, 1), q(i, 2), q(i, 3), i, "quat_log")).transpose();
  }
  return out;
}

QuatArray batch_quat_exp(const Eigen::Ref<const Vec3Array>& w) {
  require_finite(w, "quat_exp");
  QuatArray out(w.rows(), 4);
  for (Eigen::Index i = 0; i < w.rows(); ++i) {
    const Eigen::Quaterniond q = quat_exp(Eigen::Vector3d(w.row(i).transpose()));
    out.row(i) << q.x(), q.y(), q.z(), q.w();
  }
  return out;
}

namespace {

struct RowPose {
  Eigen::Vector3d t;
  Eigen::Quaterniond q;
};

RowPose row_pose(const Eigen::Ref<const PoseArray>& a, Eigen::Index i, const char* what) {
  if (!a.row(i).head<3>().allFinite()) {
    throw std::invalid_argument(std::string(what) + ": row " + std::to_string(i) + " has a NaN or infinite position");
  }
  return {a.row(i).head<3>().transpose(), checked_quaternion(a(i, 3), a(i, 4), a(i, 5), a(i, 6), i, what)};
}

void write_row(PoseArray& out, Eigen::Index i, const Eigen::Vector3d& t, const Eigen::Quaterniond& q_in) {
  const Eigen::Quaterniond q = canonical(q_in.normalized());
  out.row(i) << t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w();
}

}  // namespace

PoseArray pose_multiply(const Eigen::Ref<const PoseArray>& a, const Eigen::Ref<const PoseArray>& b) {
  const Eigen::Index na = a.rows(), nb = b.rows();
  if (na != nb && na != 1 && nb != 1) {
    throw std::invalid_argument("pose_multiply: batch sizes " + std::to_string(na) + " and " + std::to_string(nb) +
                                " differ and neither is 1");
  }
  const Eigen::Index n = (na == 0 || nb == 0) ? 0 : std::max(na, nb);
  PoseArray out(n, 7);
  for (Eigen::Index i = 0; i < n; ++i) {
    const RowPose pa = row_pose(a, na == 1 ? 0 : i, "pose_multiply (first argument)");
    const RowPose pb = row_pose(b, nb == 1 ? 0 : i, "pose_multiply (second argument)");
    write_row(out, i, pa.t + pa.q * pb.t, pa.q * pb.q);
  }
  return out;
}

PoseArray pose_inverse(const Eigen::Ref<const PoseArray>& a) {
  PoseArray out(a.rows(), 7);
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const RowPose p = row_pose(a, i, "pose_inverse");
    const Eigen::Quaterniond qi = p.q.conjugate();
    write_row(out, i, -(qi * p.t), qi);
  }
  return out;
}

}  // namespace graspmix
