// Reading hands: URDF with urdfdom, meshes with assimp, convex hulls of meshes with qhull.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <console_bridge/console.h>
#include <libqhullcpp/Qhull.h>
#include <libqhullcpp/QhullError.h>
#include <libqhullcpp/QhullFacetList.h>
#include <libqhullcpp/QhullVertexSet.h>
#include <urdf_parser/urdf_parser.h>
#include <assimp/Importer.hpp>

#include "graspmix/core/se3.hpp"
#include "graspmix/robot/hand.hpp"
#include "robot/hand_axes.hpp"
#include "robot/hull_proxy.hpp"
#include "robot/urdf_text.hpp"

namespace fs = std::filesystem;

namespace graspmix {

namespace {

/// Collects urdfdom's console_bridge messages during one parse, so that its complaint ends up in our
/// exception instead of on stderr.
class CapturedLog : public console_bridge::OutputHandler {
 public:
  CapturedLog() { console_bridge::useOutputHandler(this); }
  ~CapturedLog() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors_ += (errors_.empty() ? "" : "; ") + text;
  }
  const std::string& errors() const { return errors_; }

 private:
  std::string errors_;
};

/// A number as %g, for messages.
std::string number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

/// An <origin> as a transform; `where` names its element for the error of a non-finite or too distant one.
Eigen::Isometry3d to_isometry(const urdf::Pose& p, const std::string& where) {
  const Eigen::Vector3d t(p.position.x, p.position.y, p.position.z);
  Eigen::Quaterniond q(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
  if (!t.allFinite() || !q.coeffs().allFinite()) throw std::invalid_argument(where + ": <origin> is not finite");
  if (t.cwiseAbs().maxCoeff() > kMaxUrdfLength) {
    throw std::invalid_argument(where + ": <origin> xyz is more than " + number(kMaxUrdfLength) + " m away");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = t;
  if (q.norm() < 1e-12) q = Eigen::Quaterniond::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

bool has_prefix(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

/// The convex hull of a mesh's vertices as outward half-spaces and oriented triangles.
void convex_hull(const TriangleMesh& mesh, const std::string& what, RowMatrixXd& planes, TriangleMesh& hull,
                 std::vector<int>& tri_plane) {
  std::vector<double> coords(mesh.vertices.data(), mesh.vertices.data() + mesh.vertices.size());
  const int n = static_cast<int>(mesh.vertices.rows());
  orgQhull::Qhull qh;
  try {
    qh.runQhull("", 3, n, coords.data(), "Qt");
  } catch (const orgQhull::QhullError&) {
    // Flat or degenerate input: joggle it into a full-dimensional hull.
    try {
      qh.runQhull("", 3, n, coords.data(), "QJ");
    } catch (const orgQhull::QhullError& e) {
      throw std::invalid_argument(what + ": cannot compute the convex hull of the mesh (" + e.what() + ")");
    }
  }
  std::vector<Eigen::Vector4d> pl;
  std::vector<Eigen::Vector3i> tris;
  std::vector<size_t> tri_facet;  // each triangle's entry of pl
  std::map<int, int> vertex_index;
  std::vector<Eigen::Vector3d> verts;
  for (const orgQhull::QhullFacet& f : qh.facetList()) {
    if (!f.isGood()) continue;
    const orgQhull::QhullHyperplane h = f.hyperplane();
    const Eigen::Vector3d nrm(h.coordinates()[0], h.coordinates()[1], h.coordinates()[2]);
    // qhull: n . x + offset <= 0 inside.
    pl.emplace_back(nrm.x(), nrm.y(), nrm.z(), -h.offset());
    std::vector<int> ids;
    for (const orgQhull::QhullVertex& v : f.vertices()) {
      const orgQhull::QhullPoint p = v.point();
      const int id = p.id();
      auto it = vertex_index.find(id);
      if (it == vertex_index.end()) {
        it = vertex_index.emplace(id, static_cast<int>(verts.size())).first;
        verts.emplace_back(p[0], p[1], p[2]);
      }
      ids.push_back(it->second);
    }
    if (ids.size() != 3) continue;
    const Eigen::Vector3d c = (verts[ids[1]] - verts[ids[0]]).cross(verts[ids[2]] - verts[ids[0]]);
    if (c.dot(nrm) < 0) std::swap(ids[1], ids[2]);
    tris.emplace_back(ids[0], ids[1], ids[2]);
    tri_facet.push_back(pl.size() - 1);
  }
  // Coplanar facets of a triangulated hull repeat one plane: keep each plane once (it is the hot loop).
  std::vector<Eigen::Vector4d> unique;
  std::vector<int> facet_plane;  // each entry of pl's row in unique
  for (const auto& p : pl) {
    int seen = -1;
    for (size_t u = 0; u < unique.size() && seen < 0; ++u) {
      if ((unique[u] - p).cwiseAbs().maxCoeff() < 1e-12) seen = static_cast<int>(u);
    }
    if (seen < 0) {
      seen = static_cast<int>(unique.size());
      unique.push_back(p);
    }
    facet_plane.push_back(seen);
  }
  tri_plane.clear();
  for (const size_t f : tri_facet) tri_plane.push_back(facet_plane[f]);
  planes.resize(static_cast<Eigen::Index>(unique.size()), 4);
  for (size_t i = 0; i < unique.size(); ++i) planes.row(static_cast<Eigen::Index>(i)) = unique[i].transpose();
  hull.vertices.resize(static_cast<Eigen::Index>(verts.size()), 3);
  for (size_t i = 0; i < verts.size(); ++i) hull.vertices.row(static_cast<Eigen::Index>(i)) = verts[i].transpose();
  hull.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i) hull.triangles.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
}

/// urdfdom's model of the text; its complaints end up in the exception.
urdf::ModelInterfaceSharedPtr parse_urdf(const std::string& xml, const std::string& what) {
  // Truncated or mismatched XML would reach urdfdom as a partial document, and deep nesting would
  // exhaust TinyXML's recursion: both are refused before parsing.
  detail::check_urdf_text(xml, what);
  // console_bridge's output handler is process-wide: one parse at a time.
  static std::mutex parse_mutex;
  const std::lock_guard<std::mutex> lock(parse_mutex);
  CapturedLog log;
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  // urdfdom logs an error and goes on for a malformed link (it ignores parseLink's result): a bad
  // <box>, scale or <inertial> then silently drops the rest of that link. Any error it logs is fatal.
  if (!model || !log.errors().empty()) {
    throw std::invalid_argument(what + ": not a valid URDF" +
                                (log.errors().empty() ? std::string() : " (" + log.errors() + ")"));
  }
  return model;
}

/// A mesh collision element: its file found, and (with load_meshes) its triangles and convex hull read.
void read_mesh(const urdf::Mesh& m, const std::string& where, const std::string& base_dir,
               const HandLoadSettings& settings, CollisionShape& s) {
  s.type = ShapeType::Mesh;
  s.size = Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z);
  if (!s.size.allFinite() || !(s.size.cwiseAbs().minCoeff() > 0)) {
    throw std::invalid_argument(where + ": mesh scale must be finite and non-zero, got [" + number(s.size.x()) + " " +
                                number(s.size.y()) + " " + number(s.size.z()) + "]");
  }
  try {
    s.mesh_file = Hand::resolve_mesh_path(m.filename, base_dir, settings.package_dirs);
    if (settings.load_meshes) {
      auto mesh = std::make_shared<TriangleMesh>(Hand::load_mesh(s.mesh_file, s.size));
      auto planes = std::make_shared<RowMatrixXd>();
      auto hull = std::make_shared<TriangleMesh>();
      std::vector<int> tri_plane;
      convex_hull(*mesh, "mesh '" + s.mesh_file + "'", *planes, *hull, tri_plane);
      detail::fit_hull_proxy(*planes, *hull, tri_plane, s);
      s.mesh = mesh;
      s.hull_planes = planes;
      s.hull = hull;
    }
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
}

/// One collision element of a link, or nothing for a geometry type without a shape here.
std::optional<CollisionShape> read_collision(const urdf::Collision& col, const std::string& where,
                                             const std::string& base_dir, const HandLoadSettings& settings) {
  CollisionShape s;
  s.T_link_shape = to_isometry(col.origin, where);
  switch (col.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(*col.geometry);
      s.type = ShapeType::Box;
      s.size = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(*col.geometry);
      s.type = ShapeType::Cylinder;
      s.size = Eigen::Vector3d(c.radius, c.length, 0.0);
      break;
    }
    case urdf::Geometry::SPHERE: {
      const auto& c = static_cast<const urdf::Sphere&>(*col.geometry);
      s.type = ShapeType::Sphere;
      s.size = Eigen::Vector3d(c.radius, 0.0, 0.0);
      break;
    }
    case urdf::Geometry::MESH:
      read_mesh(static_cast<const urdf::Mesh&>(*col.geometry), where, base_dir, settings, s);
      break;
    default:
      return std::nullopt;
  }
  if (s.type != ShapeType::Mesh) {
    const int n = s.type == ShapeType::Box ? 3 : s.type == ShapeType::Cylinder ? 2 : 1;
    const char* kind = s.type == ShapeType::Box        ? "box size"
                       : s.type == ShapeType::Cylinder ? "cylinder radius and length"
                                                       : "sphere radius";
    for (int k = 0; k < n; ++k) {
      if (!(s.size[k] > 0) || !(s.size[k] <= kMaxUrdfLength)) {
        std::string got;
        for (int a = 0; a < n; ++a) got += (a ? " " : "") + number(s.size[a]);
        throw std::invalid_argument(where + ": " + kind + " must be positive, finite and at most " +
                                    number(kMaxUrdfLength) + " m, got [" + got + "]");
      }
    }
  }
  return s;
}

LinkInfo read_link(const urdf::Link& link, int parent_joint, const std::string& what, const std::string& base_dir,
                   const HandLoadSettings& settings) {
  LinkInfo info;
  info.name = link.name;
  info.parent_joint = parent_joint;
  if (link.inertial) {
    const auto& in = *link.inertial;
    info.has_inertial = true;
    const std::string where = what + ": link '" + link.name + "' <inertial>";
    info.mass = in.mass;
    require_finite(in.mass, where + " mass");
    if (in.mass < 0) throw std::invalid_argument(where + ": negative mass " + number(in.mass));
    info.T_link_inertial = to_isometry(in.origin, where);
    info.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    if (!info.inertia.allFinite()) throw std::invalid_argument(where + ": the inertia is not finite");
  }
  for (size_t c = 0; c < link.collision_array.size(); ++c) {
    const auto& col = link.collision_array[c];
    if (!col || !col->geometry) continue;
    const std::string where = what + ": link '" + link.name + "' <collision> " + std::to_string(c + 1) + " of " +
                              std::to_string(link.collision_array.size());
    std::optional<CollisionShape> s = read_collision(*col, where, base_dir, settings);
    if (s) info.collisions.push_back(std::move(*s));
  }
  return info;
}

JointInfo read_joint(const urdf::Joint& j, int parent_link, const std::string& what) {
  JointInfo ji;
  ji.name = j.name;
  ji.parent_link = parent_link;
  const std::string where = what + ": joint '" + j.name + "'";
  ji.T_parent_joint = to_isometry(j.parent_to_joint_origin_transform, where);
  switch (j.type) {
    case urdf::Joint::FIXED:
      ji.type = JointType::Fixed;
      break;
    case urdf::Joint::REVOLUTE:
      ji.type = JointType::Revolute;
      break;
    case urdf::Joint::CONTINUOUS:
      ji.type = JointType::Continuous;
      break;
    case urdf::Joint::PRISMATIC:
      ji.type = JointType::Prismatic;
      break;
    default:
      throw std::invalid_argument(what + ": joint '" + j.name +
                                  "' has an unsupported type (only fixed, revolute, continuous, prismatic)");
  }
  if (ji.type == JointType::Fixed) return ji;
  const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  if (!axis.allFinite()) throw std::invalid_argument(where + ": <axis> is not finite");
  if (!(axis.norm() > 1e-12)) throw std::invalid_argument(where + " has a zero axis");
  ji.axis = axis.normalized();
  if (ji.type == JointType::Continuous || !j.limits) {
    ji.lower = -std::numeric_limits<double>::infinity();
    ji.upper = std::numeric_limits<double>::infinity();
  } else {
    ji.lower = j.limits->lower;
    ji.upper = j.limits->upper;
    require_finite(ji.lower, where + ": <limit> lower");
    require_finite(ji.upper, where + ": <limit> upper");
    // pybullet reads lower > upper as "no limit"; here it is a mistake (a joint without limits is continuous).
    if (ji.lower > ji.upper) {
      throw std::invalid_argument(where + ": <limit> lower " + number(ji.lower) + " > upper " + number(ji.upper));
    }
  }
  if (j.mimic) {
    ji.mimic = true;
    ji.multiplier = j.mimic->multiplier;
    ji.offset = j.mimic->offset;
    require_finite(ji.multiplier, where + ": <mimic> multiplier");
    require_finite(ji.offset, where + ": <mimic> offset");
  }
  return ji;
}

/// A mimic joint resolved to the degree of freedom at the end of its chain of mimics, with the chain's
/// multiplier and offset folded into one.
void resolve_mimic(JointInfo& j, const std::vector<JointInfo>& joints, const std::map<std::string, int>& joint_index,
                   const urdf::ModelInterface& model, const std::string& what) {
  double mult = j.multiplier, off = j.offset;
  std::string master = model.getJoint(j.name)->mimic->joint_name;
  for (size_t hops = 0;; ++hops) {
    auto it = joint_index.find(master);
    if (it == joint_index.end()) {
      throw std::invalid_argument(what + ": joint '" + j.name + "' mimics an unknown joint '" + master + "'");
    }
    const JointInfo& m = joints[static_cast<size_t>(it->second)];
    if (m.type == JointType::Fixed) {
      throw std::invalid_argument(what + ": joint '" + j.name + "' mimics the fixed joint '" + master + "'");
    }
    if (hops > joints.size()) {
      throw std::invalid_argument(what + ": joint '" + j.name + "' is part of a cycle of mimic joints");
    }
    if (!m.mimic) {
      j.dof = m.dof;
      break;
    }
    // value = mult * (m.mult * next + m.off) + off
    const auto mj = model.getJoint(master);
    off += mult * mj->mimic->offset;
    mult *= mj->mimic->multiplier;
    master = mj->mimic->joint_name;
  }
  if (!std::isfinite(mult) || !std::isfinite(off)) {
    throw std::invalid_argument(what + ": joint '" + j.name +
                                "': its chain of mimics multiplies to a non-finite value");
  }
  j.multiplier = mult;
  j.offset = off;
}

}  // namespace

std::string Hand::resolve_mesh_path(const std::string& filename, const std::string& base_dir,
                                    const std::vector<std::string>& package_dirs) {
  std::vector<fs::path> tries;
  std::string name = filename;
  if (has_prefix(name, "file://")) name = name.substr(7);
  if (has_prefix(name, "package://")) {
    const std::string rest = name.substr(10);
    const auto slash = rest.find('/');
    const std::string pkg = slash == std::string::npos ? std::string() : rest.substr(0, slash);
    const std::string tail = slash == std::string::npos ? rest : rest.substr(slash + 1);
    // pybullet_data style: package://meshes/x.obj next to the URDF; ROS style: package://pkg/meshes/x.obj
    // with the URDF somewhere inside pkg.
    tries.push_back(fs::path(base_dir) / rest);
    for (fs::path dir = fs::absolute(fs::path(base_dir)); !dir.empty(); dir = dir.parent_path()) {
      if (!pkg.empty() && dir.filename() == pkg) tries.push_back(dir / tail);
      tries.push_back(dir / rest);
      if (dir == dir.parent_path()) break;
    }
    for (const auto& d : package_dirs) {
      tries.push_back(fs::path(d) / rest);
      if (!pkg.empty()) tries.push_back(fs::path(d) / tail);
    }
  } else {
    const fs::path p(name);
    tries.push_back(p.is_absolute() ? p : fs::path(base_dir) / p);
  }
  for (const auto& t : tries) {
    std::error_code ec;
    if (fs::is_regular_file(t, ec)) return t.lexically_normal().string();
  }
  std::string msg = "mesh '" + filename + "' not found (tried";
  for (size_t i = 0; i < tries.size() && i < 6; ++i) msg += (i ? ", " : " ") + tries[i].string();
  throw std::invalid_argument(msg + ")");
}

TriangleMesh Hand::load_mesh(const std::string& path, const Eigen::Vector3d& scale) {
  Assimp::Importer importer;
  // Pre-transforming flattens any node hierarchy (e.g. OBJ groups) into the file's frame.
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                     aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene) throw std::invalid_argument("mesh '" + path + "': " + importer.GetErrorString());
  std::vector<Eigen::Vector3d> verts;
  std::vector<Eigen::Vector3i> tris;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(verts.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      verts.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no volume
      tris.emplace_back(base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                        base + static_cast<int>(face.mIndices[2]));
    }
  }
  if (tris.empty()) throw std::invalid_argument("mesh '" + path + "': no triangles");
  for (const Eigen::Vector3d& v : verts) {
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxUrdfLength) {
      throw std::invalid_argument("mesh '" + path + "': a vertex (scaled) is not finite or more than " +
                                  number(kMaxUrdfLength) + " m from the origin");
    }
  }
  TriangleMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(verts.size()), 3);
  for (size_t i = 0; i < verts.size(); ++i) out.vertices.row(static_cast<Eigen::Index>(i)) = verts[i].transpose();
  out.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t i = 0; i < tris.size(); ++i) out.triangles.row(static_cast<Eigen::Index>(i)) = tris[i].transpose();
  // A negative scale mirrors the mesh; keep the triangles' winding outward.
  if (scale.prod() < 0) out.triangles.col(1).swap(out.triangles.col(2));
  return out;
}

Hand Hand::from_urdf(const std::string& path, const HandLoadSettings& settings) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw std::invalid_argument("URDF file '" + path + "' does not exist");
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("URDF file '" + path + "' cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  return from_urdf_string(ss.str(), fs::absolute(fs::path(path)).parent_path().string(), settings, path);
}

Hand Hand::from_urdf_string(const std::string& xml, const std::string& base_dir, const HandLoadSettings& settings,
                            const std::string& source) {
  const std::string what = "URDF '" + source + "'";
  const urdf::ModelInterfaceSharedPtr model = parse_urdf(xml, what);
  if (!model->getRoot()) throw std::invalid_argument(what + ": no links");

  Hand hand;
  hand.name_ = model->getName();
  hand.source_ = source;
  // Depth-first from the root so that parents come before children; urdfdom keeps children sorted
  // by joint name, which makes the order deterministic. An explicit stack, not recursion: the depth
  // of the tree is the user's.
  struct Frame {
    urdf::LinkConstSharedPtr link;
    int index;          // into links_
    size_t next_child;  // into link->child_links
  };
  auto enter = [&](const urdf::LinkConstSharedPtr& link, int parent_joint) {
    const int li = static_cast<int>(hand.links_.size());
    hand.links_.push_back(read_link(*link, parent_joint, what, base_dir, settings));
    hand.link_names_.push_back(link->name);
    hand.link_index_[link->name] = li;
    return Frame{link, li, 0};
  };
  std::vector<Frame> stack{enter(model->getRoot(), -1)};
  while (!stack.empty()) {
    Frame& top = stack.back();
    if (top.next_child == top.link->child_links.size()) {
      stack.pop_back();
      continue;
    }
    const urdf::LinkConstSharedPtr child = top.link->child_links[top.next_child++];
    JointInfo ji = read_joint(*child->parent_joint, top.index, what);
    const int ji_index = static_cast<int>(hand.joints_.size());
    ji.child_link = static_cast<int>(hand.links_.size());
    hand.joint_index_[ji.name] = ji_index;
    hand.joints_.push_back(std::move(ji));
    stack.push_back(enter(child, ji_index));  // `top` is not used after this
  }

  // Independent joints get a degree of freedom; mimics are resolved to one (chains followed).
  for (size_t i = 0; i < hand.joints_.size(); ++i) {
    JointInfo& j = hand.joints_[i];
    if (j.type == JointType::Fixed || j.mimic) continue;
    j.dof = static_cast<int>(hand.joint_names_.size());
    hand.dof_index_[j.name] = j.dof;
    hand.dof_joint_.push_back(static_cast<int>(i));
    hand.joint_names_.push_back(j.name);
  }
  for (JointInfo& j : hand.joints_) {
    if (j.mimic) resolve_mimic(j, hand.joints_, hand.joint_index_, *model, what);
  }
  const detail::GraspAxes axes = detail::grasp_axes_of(hand, xml, what, settings);
  hand.approach_axis_ = axes.approach;
  hand.fingertips_ = axes.fingertips;
  if (axes.given) hand.grasp_axes_source_ = "urdf";
  return hand;
}

}  // namespace graspmix
