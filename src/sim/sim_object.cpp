// Objects for the simulation: a one-link URDF with pybullet's <contact> extension read from the text.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <locale>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "graspmix/sim/sim.hpp"

namespace graspmix {

namespace {

/// The value attribute of <tag> inside the first <contact>...</contact> of the text, if there is one.
/// A plain search (std::regex recurses per character and overflows the stack on large files).
std::optional<double> contact_value(const std::string& xml, const std::string& tag, const std::string& what) {
  const std::size_t begin = xml.find("<contact>");
  if (begin == std::string::npos) return std::nullopt;
  const std::size_t end = xml.find("</contact>", begin);
  const std::size_t at = xml.find("<" + tag, begin);
  if (at == std::string::npos || (end != std::string::npos && at > end)) return std::nullopt;
  const std::size_t close = xml.find('>', at);
  const std::string element = xml.substr(at, close == std::string::npos ? std::string::npos : close - at);
  const std::size_t v = element.find("value");
  const std::size_t q = v == std::string::npos ? v : element.find_first_of("\"'", v);
  const std::size_t q_end = q == std::string::npos ? q : element.find(element[q], q + 1);
  if (q_end == std::string::npos) throw std::invalid_argument(what + ": <" + tag + "> has no value=\"...\"");
  const std::string text = element.substr(q + 1, q_end - q - 1);
  // The whole value must be one finite number (std::stod would take "0.5abc" as 0.5 and accept "nan").
  std::istringstream is(text);
  is.imbue(std::locale::classic());
  double value = 0;
  is >> value;
  if (is.fail() || !(is >> std::ws).eof() || !std::isfinite(value)) {
    throw std::invalid_argument(what + ": <" + tag + "> value '" + text + "' is not a finite number");
  }
  return value;
}

}  // namespace

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
  // urdfdom ignores pybullet's <contact> extension; read its lateral friction from the text (the text
  // passed Hand::from_urdf's structural check, so its <contact> element is closed).
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string xml = ss.str();
  const std::optional<double> friction = contact_value(xml, "lateral_friction", what);
  if (friction && *friction < 0) throw std::invalid_argument(what + ": <lateral_friction> must be >= 0");
  obj.friction_ = friction.value_or(-1.0);
  obj.inertia_scaling_ = contact_value(xml, "inertia_scaling", what).value_or(1.0);
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
