// Forward kinematics (eq:fk_function) and configuration handling of a Hand.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "graspmix/core/se3.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

RowMatrixXd Hand::joint_limits() const {
  RowMatrixXd out(n_dofs(), 2);
  for (int d = 0; d < n_dofs(); ++d) {
    const JointInfo& j = joints_[static_cast<size_t>(dof_joint_[static_cast<size_t>(d)])];
    out(d, 0) = j.lower;
    out(d, 1) = j.upper;
  }
  return out;
}

int Hand::link_index(const std::string& link) const {
  auto it = link_index_.find(link);
  if (it == link_index_.end()) throw std::invalid_argument("link '" + link + "' is not a link of hand '" + name_ + "'");
  return it->second;
}

int Hand::dof_index(const std::string& joint) const {
  auto it = dof_index_.find(joint);
  if (it == dof_index_.end()) {
    throw std::invalid_argument("joint '" + joint + "' is not an independent joint of hand '" + name_ + "'");
  }
  return it->second;
}

Eigen::VectorXd Hand::joints_from_map(const std::map<std::string, double>& values) const {
  Eigen::VectorXd q = Eigen::VectorXd::Constant(n_dofs(), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::pair<const JointInfo*, double>> mimics;
  for (const auto& [name, value] : values) {
    auto it = joint_index_.find(name);
    if (it == joint_index_.end()) {
      throw std::invalid_argument("joints: unknown joint '" + name + "' (hand '" + name_ + "' has joints " + [&] {
        std::string s;
        for (const auto& n : joint_names_) s += (s.empty() ? "" : ", ") + n;
        return s;
      }() + ")");
    }
    if (!std::isfinite(value)) throw std::invalid_argument("joints: joint '" + name + "' has a non-finite value");
    const JointInfo& j = joints_[static_cast<size_t>(it->second)];
    if (j.type == JointType::Fixed)
      throw std::invalid_argument("joints: joint '" + name + "' is fixed and has no value");
    if (j.mimic) {
      mimics.emplace_back(&j, value);
    } else {
      q[j.dof] = value;
    }
  }
  for (int d = 0; d < n_dofs(); ++d) {
    if (std::isnan(q[d]))
      throw std::invalid_argument("joints: joint '" + joint_names_[static_cast<size_t>(d)] + "' is missing");
  }
  for (const auto& [j, value] : mimics) {
    const double expected = j->multiplier * q[j->dof] + j->offset;
    if (std::abs(value - expected) > 1e-9) {
      throw std::invalid_argument("joints: mimic joint '" + j->name + "' = " + std::to_string(value) +
                                  " disagrees with " + std::to_string(expected) + " from its master '" +
                                  joint_names_[static_cast<size_t>(j->dof)] + "'");
    }
  }
  return q;
}

std::map<std::string, double> Hand::joints_to_map(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  check_configuration(q);
  std::map<std::string, double> out;
  for (int d = 0; d < n_dofs(); ++d) out[joint_names_[static_cast<size_t>(d)]] = q[d];
  return out;
}

Eigen::VectorXd Hand::all_joint_values(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  check_configuration(q);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(joints_.size()));
  for (size_t i = 0; i < joints_.size(); ++i) {
    const JointInfo& j = joints_[i];
    if (j.dof >= 0) out[static_cast<Eigen::Index>(i)] = j.multiplier * q[j.dof] + j.offset;
  }
  return out;
}

void Hand::check_configuration(const Eigen::Ref<const Eigen::VectorXd>& q, const char* what) const {
  if (q.size() != n_dofs()) {
    std::string names;
    for (const auto& n : joint_names_) names += (names.empty() ? "" : ", ") + n;
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(n_dofs()) + " joint values (" +
                                names + "), got " + std::to_string(q.size()));
  }
  if (!q.allFinite()) throw std::invalid_argument(std::string(what) + ": joint values must be finite");
}

Eigen::VectorXd Hand::clamp(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  check_configuration(q);
  const RowMatrixXd lim = joint_limits();
  return q.cwiseMax(lim.col(0)).cwiseMin(lim.col(1));
}

bool Hand::within_limits(const Eigen::Ref<const Eigen::VectorXd>& q, double tolerance) const {
  check_configuration(q);
  const RowMatrixXd lim = joint_limits();
  for (int d = 0; d < n_dofs(); ++d) {
    if (q[d] < lim(d, 0) - tolerance || q[d] > lim(d, 1) + tolerance) return false;
  }
  return true;
}

void Hand::fk_into(const Eigen::Isometry3d& T_world_wrist, const double* q, Eigen::Isometry3d* out) const {
  out[0] = T_world_wrist;
  for (const JointInfo& j : joints_) {
    Eigen::Isometry3d T = out[j.parent_link] * j.T_parent_joint;
    apply_joint(j, q, T);
    out[j.child_link] = T;
  }
}

std::vector<Eigen::Isometry3d> Hand::fk(const Eigen::Isometry3d& T_world_wrist,
                                        const Eigen::Ref<const Eigen::VectorXd>& q) const {
  check_configuration(q);
  std::vector<Eigen::Isometry3d> out(links_.size());
  const Eigen::VectorXd qq = q;
  fk_into(T_world_wrist, qq.data(), out.data());
  return out;
}

Eigen::Index Hand::fk_each(
    const Eigen::Ref<const PoseArray>& T_world_wrist, const Eigen::Ref<const RowMatrixXd>& q,
    Eigen::Index parallel_from,
    const std::function<void(Eigen::Index, const Eigen::VectorXd&, const Eigen::Isometry3d*)>& visit) const {
  // Either side may be a single row, broadcast over the other.
  const Eigen::Index N = T_world_wrist.rows() == 1 ? q.rows() : T_world_wrist.rows();
  if (q.cols() != n_dofs()) {
    throw std::invalid_argument("joints: expected " + std::to_string(n_dofs()) + " columns (one per joint), got " +
                                std::to_string(q.cols()));
  }
  if (q.rows() != N && q.rows() != 1) {
    throw std::invalid_argument("joints: " + std::to_string(q.rows()) + " rows for " +
                                std::to_string(T_world_wrist.rows()) + " wrist poses");
  }
  require_finite(T_world_wrist, "T_world_wrist");
  require_finite(q, "joints");
  std::string error;
#pragma omp parallel if (N >= parallel_from)
  {
    std::vector<Eigen::Isometry3d> poses(links_.size());
    Eigen::VectorXd qi(n_dofs());
#pragma omp for schedule(dynamic, 64)
    for (Eigen::Index i = 0; i < N; ++i) {
      Eigen::Isometry3d W;
      try {
        W = pose_from_vector(T_world_wrist.row(T_world_wrist.rows() == 1 ? 0 : i).transpose());
      } catch (const std::invalid_argument& e) {
#pragma omp critical
        error = "T_world_wrist row " + std::to_string(i) + ": " + e.what();
        continue;
      }
      qi = q.row(q.rows() == 1 ? 0 : i).transpose();
      fk_into(W, qi.data(), poses.data());
      visit(i, qi, poses.data());
    }
  }
  if (!error.empty()) throw std::invalid_argument(error);
  return N;
}

RowMatrixXd Hand::fk_batch(const Eigen::Ref<const PoseArray>& T_world_wrist,
                           const Eigen::Ref<const RowMatrixXd>& q) const {
  const int L = n_links();
  RowMatrixXd out(std::max(T_world_wrist.rows(), q.rows()), 7 * L);
  // fk is a fraction of a microsecond per hand: only large batches are worth a thread team.
  const Eigen::Index N =
      fk_each(T_world_wrist, q, 2048, [&](Eigen::Index i, const Eigen::VectorXd&, const Eigen::Isometry3d* poses) {
        for (int l = 0; l < L; ++l) out.block<1, 7>(i, 7 * l) = pose_to_vector(poses[l]).transpose();
      });
  out.conservativeResize(N, Eigen::NoChange);
  return out;
}

namespace {

void append(TriangleMesh& out, const Vec3Array& V, const TriangleArray& F, const Eigen::Isometry3d& T) {
  const Eigen::Index v0 = out.vertices.rows(), f0 = out.triangles.rows();
  out.vertices.conservativeResize(v0 + V.rows(), 3);
  out.triangles.conservativeResize(f0 + F.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) out.vertices.row(v0 + i) = (T * V.row(i).transpose()).transpose();
  out.triangles.bottomRows(F.rows()) = F.array() + static_cast<int>(v0);
}

/// A tessellated solid of revolution about z: rings (z, r) from bottom to top, closed by the poles.
void revolve(const std::vector<std::pair<double, double>>& rings, int segments, Vec3Array& V, TriangleArray& F) {
  const int R = static_cast<int>(rings.size());
  V.resize(R * segments + 2, 3);
  for (int r = 0; r < R; ++r)
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * M_PI * s / segments;
      V.row(r * segments + s) << rings[r].second * std::cos(a), rings[r].second * std::sin(a), rings[r].first;
    }
  const int bottom = R * segments, top = bottom + 1;
  V.row(bottom) << 0, 0, rings.front().first;
  V.row(top) << 0, 0, rings.back().first;
  std::vector<Eigen::Vector3i> tris;
  for (int s = 0; s < segments; ++s) {
    const int t = (s + 1) % segments;
    tris.emplace_back(bottom, t, s);
    for (int r = 0; r + 1 < R; ++r) {
      const int a = r * segments + s, b = r * segments + t, c = (r + 1) * segments + s, d = (r + 1) * segments + t;
      tris.emplace_back(a, b, d);
      tris.emplace_back(a, d, c);
    }
    tris.emplace_back((R - 1) * segments + s, (R - 1) * segments + t, top);
  }
  F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i) F.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
}

}  // namespace

int Hand::checked_fingertip(const std::string& link, const std::string& what) const {
  const auto it = link_index_.find(link);
  if (it == link_index_.end())
    throw std::invalid_argument(what + ": fingertip '" + link + "' is not a link of the hand");
  bool moving = false;
  for (int l = it->second; l > 0 && !moving;) {
    const JointInfo& j = joints_[static_cast<size_t>(links_[static_cast<size_t>(l)].parent_joint)];
    moving = j.type != JointType::Fixed;
    l = j.parent_link;
  }
  if (!moving) throw std::invalid_argument(what + ": fingertip '" + link + "' is not moved by any joint");
  if (links_[static_cast<size_t>(it->second)].collisions.empty()) {
    throw std::invalid_argument(what + ": fingertip '" + link + "' has no collision geometry");
  }
  return it->second;
}

void Hand::set_grasp_axes(const Eigen::Vector3d& approach, const std::vector<std::string>& fingertips) {
  if (!approach.allFinite() || !(approach.norm() > 1e-12)) {
    throw std::invalid_argument("approach_axis must be three finite numbers, not all zero");
  }
  if (fingertips.empty()) throw std::invalid_argument("fingertips: name at least one link");
  std::vector<int> tips;
  for (const std::string& name : fingertips) tips.push_back(checked_fingertip(name, "hand '" + name_ + "'"));
  std::sort(tips.begin(), tips.end());
  tips.erase(std::unique(tips.begin(), tips.end()), tips.end());
  approach_axis_ = approach.normalized();
  fingertips_ = std::move(tips);
  grasp_axes_source_ = "set";
}

TriangleMesh Hand::collision_mesh(int link) const {
  if (link < 0 || link >= n_links())
    throw std::invalid_argument("link: index " + std::to_string(link) + " out of range");
  TriangleMesh out;
  out.vertices.resize(0, 3);
  out.triangles.resize(0, 3);
  for (const CollisionShape& s : links_[static_cast<size_t>(link)].collisions) {
    Vec3Array V;
    TriangleArray F;
    switch (s.type) {
      case ShapeType::Box: {
        V.resize(8, 3);
        for (int i = 0; i < 8; ++i)
          V.row(i) << ((i & 1) ? 0.5 : -0.5) * s.size.x(), ((i & 2) ? 0.5 : -0.5) * s.size.y(),
              ((i & 4) ? 0.5 : -0.5) * s.size.z();
        F.resize(12, 3);
        F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
        break;
      }
      case ShapeType::Cylinder:
        revolve({{-0.5 * s.size.y(), s.size.x()}, {0.5 * s.size.y(), s.size.x()}}, 32, V, F);
        break;
      case ShapeType::Sphere: {
        std::vector<std::pair<double, double>> rings;
        for (int k = 1; k < 12; ++k) {
          const double a = M_PI * k / 12 - M_PI / 2;
          rings.emplace_back(s.size.x() * std::sin(a), s.size.x() * std::cos(a));
        }
        revolve(rings, 24, V, F);
        // revolve() closes with poles at the end rings' heights; move them to the sphere's poles.
        V.row(V.rows() - 2) << 0, 0, -s.size.x();
        V.row(V.rows() - 1) << 0, 0, s.size.x();
        break;
      }
      case ShapeType::Mesh:
        if (!s.mesh) continue;
        V = s.mesh->vertices;
        F = s.mesh->triangles;
        break;
    }
    append(out, V, F, s.T_link_shape);
  }
  return out;
}

}  // namespace graspmix
