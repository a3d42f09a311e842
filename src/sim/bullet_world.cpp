// The Bullet world of one grasp execution (see bullet_world.hpp).
#include "bullet_world.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace graspmix::sim_detail {

btVector3 bt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }

btTransform bt(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), bt(Eigen::Vector3d(T.translation())));
}

Eigen::Isometry3d eig(const btTransform& T) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const btQuaternion q = T.getRotation();
  out.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  out.translation() = Eigen::Vector3d(T.getOrigin().x(), T.getOrigin().y(), T.getOrigin().z());
  return out;
}

World::World(const SimSettings& s) {
  config = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
  broadphase = std::make_unique<btDbvtBroadphase>();
  solver = std::make_unique<btMultiBodyConstraintSolver>();
  world = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(), config.get());
  world->setGravity(bt(s.gravity));
  // The solver settings pybullet's physics server uses.
  auto& info = world->getSolverInfo();
  info.m_numIterations = s.solver_iterations;
  info.m_erp2 = 0.08;  // contact error reduction
  info.m_frictionERP = 0.2;
  info.m_linearSlop = 0.00001;
  info.m_warmstartingFactor = 0.1;
  info.m_minimumSolverBatchSize = 0;
  info.m_leastSquaresResidualThreshold = 1e-7;
}

World::~World() {
  for (auto& c : constraints) world->removeMultiBodyConstraint(c.get());
  for (auto& b : bodies) world->removeMultiBody(b.get());
  for (auto& o : objects) world->removeCollisionObject(o.get());
}

namespace {

/// The parts of an OBJ file as pybullet's importer sees them: the vertices used by the faces of each
/// `o`/`g` group (faces before the first group form a part too), scaled. Empty for other formats or if
/// the file has fewer than two parts (then the whole mesh is one hull).
std::vector<std::vector<Eigen::Vector3d>> obj_parts(const std::string& file, const Eigen::Vector3d& scale) {
  std::vector<std::vector<Eigen::Vector3d>> parts;
  const auto dot = file.find_last_of('.');
  std::string ext = dot == std::string::npos ? std::string() : file.substr(dot + 1);
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext != "obj") return parts;
  std::ifstream in(file);
  if (!in) return parts;
  std::vector<Eigen::Vector3d> verts;
  std::vector<std::vector<int>> groups(1);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tok;
    if (!(ls >> tok)) continue;
    if (tok == "v") {
      Eigen::Vector3d v;
      ls >> v.x() >> v.y() >> v.z();
      verts.push_back(v.cwiseProduct(scale));
    } else if (tok == "o" || tok == "g") {
      if (!groups.back().empty()) groups.emplace_back();
    } else if (tok == "f") {
      std::string ref;
      while (ls >> ref) {
        int idx = std::atoi(ref.c_str());  // "i", "i/t", "i/t/n", "i//n"
        if (idx < 0) idx = static_cast<int>(verts.size()) + idx + 1;
        if (idx >= 1 && idx <= static_cast<int>(verts.size())) groups.back().push_back(idx - 1);
      }
    }
  }
  for (auto& g : groups) {
    if (g.empty()) continue;
    std::sort(g.begin(), g.end());
    g.erase(std::unique(g.begin(), g.end()), g.end());
    parts.emplace_back();
    for (int i : g) parts.back().push_back(verts[static_cast<size_t>(i)]);
  }
  if (parts.size() < 2) parts.clear();
  return parts;
}

}  // namespace

btCompoundShape* link_shape(World& w, const LinkInfo& link, const Eigen::Isometry3d& T_link_com) {
  if (link.collisions.empty()) return nullptr;
  auto* compound = w.own_shape(std::make_unique<btCompoundShape>());
  for (const auto& c : link.collisions) {
    btCollisionShape* child = nullptr;
    switch (c.type) {
      case ShapeType::Box:
        child = w.own_shape(std::make_unique<btBoxShape>(bt(Eigen::Vector3d(c.size * 0.5))));
        break;
      case ShapeType::Cylinder:
        child = w.own_shape(std::make_unique<btCylinderShapeZ>(btVector3(c.size.x(), c.size.x(), c.size.y() * 0.5)));
        break;
      case ShapeType::Sphere:
        child = w.own_shape(std::make_unique<btSphereShape>(c.size.x()));
        break;
      case ShapeType::Mesh: {
        if (!c.hull)
          throw std::invalid_argument("link '" + link.name + "': mesh '" + c.mesh_file + "' was read without geometry");
        // pybullet makes one convex hull per object/group of an OBJ file (a convex decomposition such as
        // pybullet_data's random_urdfs, six parts each); any other mesh is one hull.
        std::vector<std::vector<Eigen::Vector3d>> parts = obj_parts(c.mesh_file, c.size);
        if (parts.empty()) {
          parts.emplace_back();
          for (Eigen::Index i = 0; i < c.hull->vertices.rows(); ++i)
            parts.back().emplace_back(c.hull->vertices.row(i).transpose());
        }
        for (const auto& part : parts) {
          auto hull = std::make_unique<btConvexHullShape>();
          for (const auto& v : part) hull->addPoint(bt(v), false);
          hull->recalcLocalAabb();
          hull->optimizeConvexHull();
          hull->setMargin(kCollisionMargin);
          compound->addChildShape(bt(T_link_com.inverse() * c.T_link_shape), w.own_shape(std::move(hull)));
        }
        continue;
      }
    }
    child->setMargin(kCollisionMargin);
    compound->addChildShape(bt(T_link_com.inverse() * c.T_link_shape), child);
  }
  return compound;
}

btVector3 shape_inertia(btCollisionShape* shape, double mass) {
  btVector3 inertia(0, 0, 0);
  if (shape) shape->calculateLocalInertia(mass, inertia);
  for (int k = 0; k < 3; ++k) {
    if (!(inertia[k] > 0)) inertia[k] = mass * 1e-4;
  }
  return inertia;
}

btMultiBodyLinkCollider* add_collider(World& w, btMultiBody* mb, int link, btCollisionShape* shape, double friction) {
  auto col = std::make_unique<btMultiBodyLinkCollider>(mb, link);
  col->setCollisionShape(shape);
  col->setFriction(friction);
  col->setRestitution(0.0);
  col->setRollingFriction(0.0);
  col->setSpinningFriction(0.0);
  btMultiBodyLinkCollider* raw = col.get();
  w.world->addCollisionObject(raw, btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
  if (link < 0) {
    mb->setBaseCollider(raw);
  } else {
    mb->getLink(link).m_collider = raw;
  }
  w.objects.push_back(std::move(col));
  return raw;
}

void sync_transforms(btMultiBody* mb) {
  btAlignedObjectArray<btQuaternion> scratch_q;
  btAlignedObjectArray<btVector3> scratch_m;
  mb->forwardKinematics(scratch_q, scratch_m);
  mb->updateCollisionObjectWorldTransforms(scratch_q, scratch_m);
}

}  // namespace graspmix::sim_detail

namespace graspmix::sim_detail {

void add_static_box(World& w, const Eigen::Vector3d& center, const Eigen::Vector3d& half, double friction) {
  auto* shape = w.own_shape(std::make_unique<btBoxShape>(bt(half)));
  shape->setMargin(kCollisionMargin);
  auto box = std::make_unique<btCollisionObject>();
  box->setCollisionShape(shape);
  box->setWorldTransform(btTransform(btQuaternion::getIdentity(), bt(center)));
  box->setFriction(friction);
  box->setRestitution(0.0);
  w.world->addCollisionObject(box.get(), btBroadphaseProxy::StaticFilter,
                              btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
  w.objects.push_back(std::move(box));
}

const btCollisionObject* add_support(World& w, double friction) {
  add_static_box(w, Eigen::Vector3d(0, 0, -5), Eigen::Vector3d(100, 100, 5), friction);
  return w.objects.back().get();
}

btMultiBody* add_object(World& w, const SimObject& object, const Eigen::Isometry3d& T_world_object,
                        const SimSettings& s) {
  const LinkInfo& olink = object.model().links().front();
  const double omass = s.object_mass >= 0 ? s.object_mass : object.mass();
  if (!(omass > 0)) throw std::invalid_argument("SimSettings.object_mass must be positive");
  const double ofriction =
      s.object_friction >= 0 ? s.object_friction : (object.lateral_friction() >= 0 ? object.lateral_friction() : 0.5);
  btCompoundShape* oshape = link_shape(w, olink, olink.T_link_inertial);
  // pybullet scales the inertia computed from the shape by <contact><inertia_scaling> (random_urdfs use 3).
  w.bodies.push_back(
      std::make_unique<btMultiBody>(0, omass, shape_inertia(oshape, omass) * object.inertia_scaling(), false, false));
  btMultiBody* body = w.bodies.back().get();
  body->setBaseWorldTransform(bt(T_world_object * olink.T_link_inertial));
  body->finalizeMultiDof();
  w.world->addMultiBody(body);
  add_collider(w, body, -1, oshape, ofriction);
  sync_transforms(body);
  return body;
}

Eigen::Isometry3d object_pose(const btMultiBody* body, const SimObject& object) {
  return eig(body->getBaseWorldTransform()) * object.model().links().front().T_link_inertial.inverse();
}

}  // namespace graspmix::sim_detail
