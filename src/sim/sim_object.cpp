// Objects for the simulation: a one-link URDF with pybullet's <contact> extension read from the text.
#include <algorithm>
#include <fstream>
#include <limits>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "graspmix/sim/sim.hpp"

namespace graspmix {

SimObject SimObject::from_urdf(const std::string& path, const HandLoadSettings& settings) {
  SimObject obj;
  auto model = std::make_shared<Hand>(Hand::from_urdf(path, settings));
  const std::string what = "object URDF '" + path + "'";
  if (model->n_links() != 1) {
    throw std::invalid_argument(what + ": expected one link, got " + std::to_string(model->n_links()));
  }
  const LinkInfo& link = model->links().front();
  if (link.collisions.empty()) throw std::invalid_argument(what + ": the link has no collision geometry");
  obj.mass_ = link.has_inertial ? link.mass : 1.0;  // pybullet's default mass without <inertial>
  if (!(obj.mass_ > 0)) throw std::invalid_argument(what + ": the object needs a positive mass to be lifted");
  // urdfdom ignores pybullet's <contact> extension; read its lateral friction from the text.
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string xml = ss.str();
  auto contact_value = [&](const char* tag, double fallback) {
    const std::regex re(std::string(R"(<contact>[\s\S]*?<)") + tag + R"(\s+value\s*=\s*["']([^"']+)["'][\s\S]*?</contact>)");
    std::smatch m;
    if (!std::regex_search(xml, m, re)) return fallback;
    try {
      return std::stod(m[1].str());
    } catch (const std::exception&) {
      throw std::invalid_argument(what + ": <" + tag + "> is not a number");
    }
  };
  obj.friction_ = contact_value("lateral_friction", -1.0);
  obj.inertia_scaling_ = contact_value("inertia_scaling", 1.0);
  if (!(obj.inertia_scaling_ > 0)) throw std::invalid_argument(what + ": <inertia_scaling> must be positive");
  obj.model_ = std::move(model);
  return obj;
}

Eigen::Isometry3d SimObject::rest_pose(double x, double y, const Eigen::Quaterniond& q) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  const TriangleMesh mesh = model_->collision_mesh(0);
  double zmin = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    zmin = std::min(zmin, (T.linear() * mesh.vertices.row(i).transpose()).z());
  }
  T.translation() = Eigen::Vector3d(x, y, -zmin);
  return T;
}
}  // namespace graspmix
