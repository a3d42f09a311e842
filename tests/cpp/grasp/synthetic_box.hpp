#pragma once
// A test helper: a box whose surface, frames and curvature features are known exactly, and the WSG 50's GMM
// synthesiser learnt from a top grasp of it.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "graspmix/core/se3.hpp"
#include "graspmix/core/types.hpp"
#include "graspmix/density/pose_mixture.hpp"
#include "graspmix/grasp/synthesis.hpp"

namespace graspmix::test {

/// Points every 3 mm on the top and side faces of a 60 x 100 x 140 mm box standing on z = 0, with
/// frames (z = outward normal) and features [k1, k2] = [0.02, 0] within 6 mm of an edge, else 0.
struct Box {
  PoseArray frames;
  RowMatrixXd features;
  Vec3Array points;
};

inline Box make_box() {
  const Eigen::Vector3d half(0.03, 0.05, 0.07), centre(0, 0, 0.07);
  std::vector<Eigen::Matrix<double, 7, 1>> fr;
  std::vector<Eigen::Vector2d> ft;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      if (axis == 2 && sign < 0) continue;  // the bottom rests on the table
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (double a = -half[u]; a <= half[u] + 1e-9; a += 0.003) {
        for (double b = -half[v]; b <= half[v] + 1e-9; b += 0.003) {
          Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
          p[axis] = sign * half[axis];
          p[u] = a;
          p[v] = b;
          n[axis] = sign;
          Eigen::Vector3d x = Eigen::Vector3d::Zero();
          x[u] = 1.0;
          Eigen::Matrix3d R;
          R << x, n.cross(x), n;
          const Eigen::Quaterniond q = canonical(Eigen::Quaterniond(R));
          Eigen::Matrix<double, 7, 1> f;
          f << p + centre, q.x(), q.y(), q.z(), q.w();
          fr.push_back(f);
          const bool edge = half[u] - std::abs(a) < 0.006 || half[v] - std::abs(b) < 0.006;
          ft.emplace_back(edge ? 0.02 : 0.0, 0.0);
        }
      }
    }
  }
  Box box;
  box.frames.resize(fr.size(), 7);
  box.features.resize(ft.size(), 2);
  for (size_t i = 0; i < fr.size(); ++i) {
    box.frames.row(i) = fr[i].transpose();
    box.features.row(i) = ft[i].transpose();
  }
  box.points = box.frames.leftCols<3>();
  return box;
}

/// The WSG 50 (data/hands/wsg50.urdf under `repo`).
inline std::shared_ptr<const Hand> wsg50(const std::string& repo) {
  return std::make_shared<Hand>(Hand::from_urdf(repo + "/data/hands/wsg50.urdf"));
}

/// The synthesiser (GMM, 2 components) learnt from the WSG 50's top grasp of `box`: the wrist 21.85 cm above the
/// table, palm z down, the jaws closing from 5 cm to 3.05 cm.
inline std::unique_ptr<GraspSynthesizer> top_grasp_synthesizer(const std::shared_ptr<const Hand>& hand,
                                                               const Box& box) {
  Eigen::Matrix<double, 7, 1> w;
  w << 0, 0, 0.2185, 1, 0, 0, 0;
  Eigen::VectorXd grasp(1), pre(1);
  grasp << 0.0305;
  pre << 0.05;
  auto models = learn_contact_models(*hand, pose_from_vector(w), grasp, box.frames, box.features, [] {
    GmmSettings s;
    s.n_components = 2;
    return std::make_shared<PoseMixture>(s);
  });
  return std::make_unique<GraspSynthesizer>(hand, std::move(models), ConfigModel(pre, grasp, hand->joint_limits()));
}

/// The rows of several point arrays, one after the other.
inline Vec3Array stack_rows(const std::vector<Vec3Array>& parts) {
  Eigen::Index n = 0;
  for (const Vec3Array& p : parts) n += p.rows();
  Vec3Array out(n, 3);
  n = 0;
  for (const Vec3Array& p : parts) {
    out.middleRows(n, p.rows()) = p;
    n += p.rows();
  }
  return out;
}

}  // namespace graspmix::test
