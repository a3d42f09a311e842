// A hand's grasp axes: the URDF's <graspmix> element (TinyXML, urdfdom's own parser, which skips the element)
// and the rules of hand.hpp that infer what it does not give.
#include "robot/hand_axes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <tinyxml.h>
#include <Eigen/Geometry>

namespace graspmix::detail {

namespace {

constexpr double kOutreach = 1e-3;  // m: a link outreaches another along the approach by more than this

std::vector<std::string> words(const char* text) {
  std::istringstream is(text ? text : "");
  std::vector<std::string> out;
  for (std::string w; is >> w;) out.push_back(w);
  return out;
}

Eigen::Vector3d axis_from_text(const char* text, const std::string& what) {
  const std::vector<std::string> w = words(text);
  Eigen::Vector3d a;
  bool ok = w.size() == 3;
  for (size_t i = 0; ok && i < 3; ++i) {
    char* end = nullptr;
    a[static_cast<Eigen::Index>(i)] = std::strtod(w[i].c_str(), &end);
    ok = end && *end == '\0' && std::isfinite(a[static_cast<Eigen::Index>(i)]);
  }
  if (!ok || !(a.norm() > 1e-12)) {
    throw std::invalid_argument(what + ": <" + kUrdfAxesElement +
                                "> approach_axis must be three finite numbers, not all zero, got '" +
                                (text ? text : "") + "'");
  }
  return a.normalized();
}

/// Each link's collision vertices at mid-range joints (continuous ones at 0), in the wrist frame; empty rows for a
/// link without geometry.
std::vector<Vec3Array> mid_range_vertices(const Hand& hand) {
  const RowMatrixXd lim = hand.joint_limits();
  Eigen::VectorXd q(hand.n_dofs());
  for (int d = 0; d < hand.n_dofs(); ++d) {
    q[d] = std::isfinite(lim(d, 0)) && std::isfinite(lim(d, 1)) ? 0.5 * (lim(d, 0) + lim(d, 1)) : 0.0;
  }
  const std::vector<Eigen::Isometry3d> poses = hand.fk(Eigen::Isometry3d::Identity(), q);
  std::vector<Vec3Array> out(static_cast<size_t>(hand.n_links()));
  for (int l = 0; l < hand.n_links(); ++l) {
    const TriangleMesh m = hand.collision_mesh(l);
    Vec3Array& V = out[static_cast<size_t>(l)];
    V.resize(m.vertices.rows(), 3);
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
      V.row(i) = (poses[static_cast<size_t>(l)] * m.vertices.row(i).transpose()).transpose();
    }
  }
  return out;
}

Eigen::Vector3d box_centre(const Vec3Array& V) {
  return 0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()).transpose();
}

/// The distal ends of the chains: links a joint moves, with collision geometry and no descendant with geometry.
std::vector<int> chain_ends(const Hand& hand, const std::vector<Vec3Array>& verts) {
  const int L = hand.n_links();
  std::vector<bool> moving(static_cast<size_t>(L), false), geometric_below(static_cast<size_t>(L), false);
  for (int l = 1; l < L; ++l) {  // parents before children
    const JointInfo& j = hand.joints()[static_cast<size_t>(hand.links()[static_cast<size_t>(l)].parent_joint)];
    moving[static_cast<size_t>(l)] = j.type != JointType::Fixed || moving[static_cast<size_t>(j.parent_link)];
  }
  for (int l = L - 1; l >= 1; --l) {  // children before parents
    const JointInfo& j = hand.joints()[static_cast<size_t>(hand.links()[static_cast<size_t>(l)].parent_joint)];
    if (verts[static_cast<size_t>(l)].rows() > 0 || geometric_below[static_cast<size_t>(l)]) {
      geometric_below[static_cast<size_t>(j.parent_link)] = true;
    }
  }
  std::vector<int> out;
  for (int l = 0; l < L; ++l) {
    const auto u = static_cast<size_t>(l);
    if (moving[u] && verts[u].rows() > 0 && !geometric_below[u]) out.push_back(l);
  }
  return out;
}

/// Of the candidates, those no other candidate on the same side of the approach outreaches along it.
std::vector<int> distal_per_finger(const std::vector<int>& candidates, const std::vector<Vec3Array>& verts,
                                   const Eigen::Vector3d& approach, double same_finger_deg) {
  const double cos_same = std::cos(same_finger_deg * M_PI / 180.0);
  std::vector<double> reach;
  std::vector<Eigen::Vector3d> side;
  for (const int l : candidates) {
    const Vec3Array& V = verts[static_cast<size_t>(l)];
    reach.push_back((V * approach).maxCoeff());
    const Eigen::Vector3d c = box_centre(V);
    const Eigen::Vector3d across = c - c.dot(approach) * approach;
    side.push_back(across.norm() > 1e-9 ? Eigen::Vector3d(across.normalized()) : Eigen::Vector3d::Zero());
  }
  std::vector<int> out;
  for (size_t a = 0; a < candidates.size(); ++a) {
    bool outreached = false;
    for (size_t b = 0; b < candidates.size() && !outreached; ++b) {
      outreached = b != a && reach[b] > reach[a] + kOutreach && side[a].dot(side[b]) > cos_same;
    }
    if (!outreached) out.push_back(candidates[a]);
  }
  return out;
}

/// The direction from the wrist to the mean of the links' box centres, snapped to the nearest wrist axis within
/// snap_deg; +z when the mean is at the wrist.
Eigen::Vector3d towards(const std::vector<int>& links, const std::vector<Vec3Array>& verts, double snap_deg) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const int l : links) mean += box_centre(verts[static_cast<size_t>(l)]);
  if (links.empty() || !(mean.norm() > 1e-9)) return Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d d = mean.normalized();
  Eigen::Index k = 0;
  d.cwiseAbs().maxCoeff(&k);
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  axis[k] = d[k] > 0 ? 1.0 : -1.0;
  return std::abs(d[k]) >= std::cos(snap_deg * M_PI / 180.0) ? axis : d;
}

}  // namespace

UrdfGraspAxes read_urdf_grasp_axes(const std::string& xml, const std::string& what) {
  UrdfGraspAxes out;
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  const TiXmlElement* root = doc.RootElement();
  const TiXmlElement* e = root ? root->FirstChildElement(kUrdfAxesElement) : nullptr;
  if (!e) return out;
  for (const TiXmlAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
    const std::string name = a->Name();
    if (name != "approach_axis" && name != "fingertips") {
      throw std::invalid_argument(what + ": <" + kUrdfAxesElement + "> has an unknown attribute '" + name +
                                  "' (approach_axis, fingertips)");
    }
  }
  if (const char* text = e->Attribute("approach_axis")) out.approach = axis_from_text(text, what);
  out.fingertips = words(e->Attribute("fingertips"));
  if (e->Attribute("fingertips") && out.fingertips.empty()) {
    throw std::invalid_argument(what + ": <" + kUrdfAxesElement + "> fingertips names no link");
  }
  return out;
}

GraspAxes infer_grasp_axes(const Hand& hand, const std::optional<Eigen::Vector3d>& approach,
                           const std::vector<int>& fingertips, const HandLoadSettings& settings) {
  const std::vector<Vec3Array> verts = mid_range_vertices(hand);
  GraspAxes out;
  out.fingertips = fingertips;
  if (fingertips.empty()) {
    const std::vector<int> ends = chain_ends(hand, verts);
    const Eigen::Vector3d first = approach ? *approach : towards(ends, verts, settings.approach_snap_deg);
    out.fingertips = distal_per_finger(ends, verts, first, settings.same_finger_deg);
  }
  out.approach = approach ? *approach : towards(out.fingertips, verts, settings.approach_snap_deg);
  return out;
}

GraspAxes grasp_axes_of(const Hand& hand, const std::string& xml, const std::string& what,
                        const HandLoadSettings& settings) {
  const UrdfGraspAxes given = read_urdf_grasp_axes(xml, what);
  std::vector<int> tips;
  for (const std::string& name : given.fingertips) tips.push_back(hand.checked_fingertip(name, what));
  std::sort(tips.begin(), tips.end());
  tips.erase(std::unique(tips.begin(), tips.end()), tips.end());
  GraspAxes out = infer_grasp_axes(hand, given.approach, tips, settings);
  out.given = given.approach.has_value() || !given.fingertips.empty();
  return out;
}

}  // namespace graspmix::detail
