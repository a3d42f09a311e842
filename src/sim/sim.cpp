// Grasp execution in Bullet (Featherstone multibodies), built the way pybullet builds the same URDFs so
// that both simulators agree (tests/python/test_sim.py compares them).
#include "graspmix/sim/sim.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

namespace graspmix {

namespace {

// pybullet's URDF importer gives every collision shape this margin.
constexpr double kCollisionMargin = 0.001;
// Links without mass (pure frames) still need some in a multibody.
constexpr double kMinLinkMass = 1e-3;

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

/// Everything one world owns, destroyed in the right order.
struct World {
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints;
  std::vector<std::unique_ptr<btMultiBody>> bodies;

  explicit World(const SimSettings& s) {
    config = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
    broadphase = std::make_unique<btDbvtBroadphase>();
    solver = std::make_unique<btMultiBodyConstraintSolver>();
    world = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(), config.get());
    world->setGravity(bt(s.gravity));
    // The solver settings pybullet's physics server uses.
    auto& info = world->getSolverInfo();
    info.m_numIterations = s.solver_iterations;
    info.m_erp2 = 0.08;         // contact error reduction
    info.m_frictionERP = 0.2;
    info.m_linearSlop = 0.00001;
    info.m_warmstartingFactor = 0.1;
    info.m_minimumSolverBatchSize = 0;
    info.m_leastSquaresResidualThreshold = 1e-7;
  }
  ~World() {
    for (auto& c : constraints) world->removeMultiBodyConstraint(c.get());
    for (auto& b : bodies) world->removeMultiBody(b.get());
    for (auto& o : objects) world->removeCollisionObject(o.get());
  }
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  template <class T>
  T* own_shape(std::unique_ptr<T> s) {
    T* raw = s.get();
    shapes.push_back(std::move(s));
    return raw;
  }
};

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

/// The collision shapes of one link as a compound in the link's centre-of-mass frame (T_link_com), or
/// nullptr if the link has none.
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
        if (!c.hull) throw std::invalid_argument("link '" + link.name + "': mesh '" + c.mesh_file + "' was read without geometry");
        // pybullet makes one convex hull per object/group of an OBJ file (a convex decomposition such as
        // pybullet_data's random_urdfs, six parts each); any other mesh is one hull.
        std::vector<std::vector<Eigen::Vector3d>> parts = obj_parts(c.mesh_file, c.size);
        if (parts.empty()) {
          parts.emplace_back();
          for (Eigen::Index i = 0; i < c.hull->vertices.rows(); ++i) parts.back().emplace_back(c.hull->vertices.row(i).transpose());
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

/// Mass and principal inertia as pybullet computes them by default: the URDF's mass at the URDF's
/// inertial frame, the inertia from the collision shape (its bounding box).
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

void check_settings(const SimSettings& s) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(std::string("SimSettings.") + name + " must be positive, got " + std::to_string(v));
  };
  auto nonneg = [](double v, const char* name) {
    if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument(std::string("SimSettings.") + name + " must be >= 0, got " + std::to_string(v));
  };
  positive(s.time_step, "time_step");
  if (s.solver_iterations < 1) throw std::invalid_argument("SimSettings.solver_iterations must be >= 1");
  nonneg(s.hand_friction, "hand_friction");
  nonneg(s.support_friction, "support_friction");
  positive(s.grip_force, "grip_force");
  positive(s.close_speed, "close_speed");
  nonneg(s.close_overshoot, "close_overshoot");
  nonneg(s.close_time, "close_time");
  positive(s.position_gain, "position_gain");
  nonneg(s.lift_height, "lift_height");
  positive(s.lift_speed, "lift_speed");
  positive(s.lift_force, "lift_force");
  nonneg(s.hold_time, "hold_time");
  nonneg(s.start_penetration, "start_penetration");
  nonneg(s.contact_distance, "contact_distance");
  nonneg(s.success_fraction, "success_fraction");
  if (!s.gravity.allFinite()) throw std::invalid_argument("SimSettings.gravity must be finite");
}

}  // namespace

const char* to_string(SimOutcome outcome) {
  switch (outcome) {
    case SimOutcome::Success: return "success";
    case SimOutcome::StartInCollision: return "start in collision";
    case SimOutcome::NoContact: return "no contact";
    case SimOutcome::NotHeld: return "not held";
  }
  return "?";
}

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

SimResult execute(const Hand& hand, const SimObject& object, const Eigen::Isometry3d& T_world_object,
                  const Eigen::Isometry3d& T_world_wrist, const Eigen::Ref<const Eigen::VectorXd>& pregrasp,
                  const Eigen::Ref<const Eigen::VectorXd>& grasp, const SimSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  check_settings(s);
  hand.check_configuration(pregrasp, "pregrasp_joints");
  hand.check_configuration(grasp, "grasp_joints");
  if (!T_world_wrist.matrix().allFinite()) throw std::invalid_argument("T_world_wrist must be finite");
  if (!T_world_object.matrix().allFinite()) throw std::invalid_argument("T_world_object must be finite");

  World w(s);
  const double dt = s.time_step;

  // ---- support: pybullet_data's plane.urdf, a 200 x 200 x 10 m box with its top at z = 0 ----
  auto* plane_shape = w.own_shape(std::make_unique<btBoxShape>(btVector3(100, 100, 5)));
  plane_shape->setMargin(kCollisionMargin);
  {
    auto plane = std::make_unique<btCollisionObject>();
    plane->setCollisionShape(plane_shape);
    plane->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, -5)));
    plane->setFriction(s.support_friction);
    plane->setRestitution(0.0);
    w.world->addCollisionObject(plane.get(), btBroadphaseProxy::StaticFilter,
                                btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
    w.objects.push_back(std::move(plane));
  }
  const btCollisionObject* plane_obj = w.objects.back().get();

  // ---- the object: a multibody with no links, like pybullet's import of a one-link URDF ----
  const LinkInfo& olink = object.model().links().front();
  const double omass = s.object_mass >= 0 ? s.object_mass : object.mass();
  if (!(omass > 0)) throw std::invalid_argument("SimSettings.object_mass must be positive");
  const double ofriction = s.object_friction >= 0 ? s.object_friction
                                                  : (object.lateral_friction() >= 0 ? object.lateral_friction() : 0.5);
  btCompoundShape* oshape = link_shape(w, olink, olink.T_link_inertial);
  // pybullet scales the inertia computed from the shape by <contact><inertia_scaling> (random_urdfs use 3).
  w.bodies.push_back(std::make_unique<btMultiBody>(0, omass, shape_inertia(oshape, omass) * object.inertia_scaling(),
                                                   false, false));
  btMultiBody* obody = w.bodies.back().get();
  obody->setBaseWorldTransform(bt(T_world_object * olink.T_link_inertial));
  obody->finalizeMultiDof();
  w.world->addMultiBody(obody);
  add_collider(w, obody, -1, oshape, ofriction);
  sync_transforms(obody);

  // ---- the hand: fixed base at the wrist, link 0 = the root link on the lift joint, then the tree ----
  const int L = hand.n_links();
  const auto& links = hand.links();
  const auto& joints = hand.joints();
  std::vector<btCompoundShape*> shapes(static_cast<size_t>(L));
  std::vector<double> masses(static_cast<size_t>(L));
  for (int i = 0; i < L; ++i) {
    const LinkInfo& li = links[static_cast<size_t>(i)];
    shapes[static_cast<size_t>(i)] = link_shape(w, li, li.T_link_inertial);
    masses[static_cast<size_t>(i)] = std::max(li.mass, kMinLinkMass);
  }
  w.bodies.push_back(std::make_unique<btMultiBody>(L, 0.0, btVector3(0, 0, 0), true, false));
  btMultiBody* hbody = w.bodies.back().get();
  hbody->setBaseWorldTransform(bt(T_world_wrist));
  hbody->setHasSelfCollision(false);  // pybullet's default for loadURDF
  auto setup = [&](int i, int parent, const Eigen::Isometry3d& T_parent_com, const Eigen::Isometry3d& T_parent_joint,
                   JointType type, const Eigen::Vector3d& axis) {
    const LinkInfo& li = links[static_cast<size_t>(i)];
    const btTransform offA = bt(T_parent_com.inverse() * T_parent_joint);  // joint frame in the parent's COM frame
    const btTransform offB = bt(li.T_link_inertial.inverse());             // link frame in its own COM frame
    const btQuaternion rot = offB.getRotation() * offA.getRotation().inverse();
    const btVector3 inertia = shape_inertia(shapes[static_cast<size_t>(i)], masses[static_cast<size_t>(i)]);
    const double m = masses[static_cast<size_t>(i)];
    switch (type) {
      case JointType::Fixed:
        hbody->setupFixed(i, m, inertia, parent, rot, offA.getOrigin(), -offB.getOrigin(), true);
        break;
      case JointType::Prismatic:
        hbody->setupPrismatic(i, m, inertia, parent, rot, quatRotate(offB.getRotation(), bt(axis)), offA.getOrigin(),
                              -offB.getOrigin(), true);
        break;
      case JointType::Revolute:
      case JointType::Continuous:
        hbody->setupRevolute(i, m, inertia, parent, rot, quatRotate(offB.getRotation(), bt(axis)), offA.getOrigin(),
                             -offB.getOrigin(), true);
        break;
    }
  };
  // The lift joint: world +z expressed in the wrist frame.
  const Eigen::Vector3d lift_axis = T_world_wrist.linear().transpose() * Eigen::Vector3d::UnitZ();
  setup(0, -1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), JointType::Prismatic, lift_axis);
  for (int i = 1; i < L; ++i) {
    const JointInfo& j = joints[static_cast<size_t>(links[static_cast<size_t>(i)].parent_joint)];
    setup(i, j.parent_link, links[static_cast<size_t>(j.parent_link)].T_link_inertial, j.T_parent_joint, j.type, j.axis);
  }
  hbody->finalizeMultiDof();
  w.world->addMultiBody(hbody);
  for (int i = 0; i < L; ++i) {
    if (shapes[static_cast<size_t>(i)]) add_collider(w, hbody, i, shapes[static_cast<size_t>(i)], s.hand_friction);
  }
  const Eigen::VectorXd q_start = hand.all_joint_values(pregrasp);
  const Eigen::VectorXd q_grasp = hand.all_joint_values(grasp);
  hbody->setJointPos(0, 0.0);
  for (int i = 1; i < L; ++i) {
    const int ji = links[static_cast<size_t>(i)].parent_joint;
    if (joints[static_cast<size_t>(ji)].type != JointType::Fixed) hbody->setJointPos(i, q_start[ji]);
  }
  sync_transforms(hbody);

  // Motors on every movable joint (velocity commands, force-limited) and the URDF limits.
  struct Drive {
    int link;
    double target;
    double speed;
    btMultiBodyJointMotor* motor;
  };
  std::vector<Drive> fingers;
  auto add_motor = [&](int link, double max_force) {
    auto motor = std::make_unique<btMultiBodyJointMotor>(hbody, link, 0.0, max_force * dt);
    btMultiBodyJointMotor* raw = motor.get();
    w.world->addMultiBodyConstraint(raw);
    w.constraints.push_back(std::move(motor));
    return raw;
  };
  btMultiBodyJointMotor* lift_motor = add_motor(0, s.lift_force);
  for (int i = 1; i < L; ++i) {
    const int ji = links[static_cast<size_t>(i)].parent_joint;
    const JointInfo& j = joints[static_cast<size_t>(ji)];
    if (j.type == JointType::Fixed) continue;
    double target = q_grasp[ji] + s.close_overshoot * (q_grasp[ji] - q_start[ji]);
    if (j.type != JointType::Continuous && std::isfinite(j.lower) && std::isfinite(j.upper) && j.lower <= j.upper) {
      target = std::clamp(target, j.lower, j.upper);
      auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(hbody, i, j.lower, j.upper);
      w.world->addMultiBodyConstraint(limit.get());
      w.constraints.push_back(std::move(limit));
    }
    // Fast enough to reach the grasp joints within half the closing time, whatever the joint's travel.
    const double speed = std::max(s.close_speed, 2.0 * std::abs(q_grasp[ji] - q_start[ji]) / std::max(s.close_time, dt));
    fingers.push_back({i, target, speed, add_motor(i, s.grip_force)});
  }

  SimResult r;
  auto scan_contacts = [&](double below, double* deepest) {
    // Hand-object contact points closer than `below`; deepest penetration of the hand into anything.
    int count = 0;
    btDispatcher* d = w.world->getDispatcher();
    for (int k = 0; k < d->getNumManifolds(); ++k) {
      const btPersistentManifold* man = d->getManifoldByIndexInternal(k);
      const auto* a = btMultiBodyLinkCollider::upcast(man->getBody0());
      const auto* b = btMultiBodyLinkCollider::upcast(man->getBody1());
      const bool a_hand = a && a->m_multiBody == hbody, b_hand = b && b->m_multiBody == hbody;
      if (a_hand == b_hand) continue;  // not a hand-something pair
      const btCollisionObject* other = a_hand ? man->getBody1() : man->getBody0();
      const auto* oc = a_hand ? b : a;
      const bool with_object = oc && oc->m_multiBody == obody;
      if (!with_object && other != plane_obj) continue;
      for (int p = 0; p < man->getNumContacts(); ++p) {
        const double dist = man->getContactPoint(p).getDistance();
        if (deepest) *deepest = std::max(*deepest, -dist);
        if (with_object && dist < below) ++count;
      }
    }
    return count;
  };
  auto finish = [&](SimOutcome o) {
    r.outcome = o;
    r.success = o == SimOutcome::Success;
    r.reason = to_string(o);
    r.T_world_object_final = eig(obody->getBaseWorldTransform()) * olink.T_link_inertial.inverse();
    r.simulated_time = r.steps * dt;
    r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };

  // 1. start in collision?
  w.world->performDiscreteCollisionDetection();
  double deepest = 0.0;
  scan_contacts(s.contact_distance, &deepest);
  r.start_penetration = std::max(0.0, deepest);
  if (deepest > s.start_penetration) return finish(SimOutcome::StartInCollision);

  const double z0 = obody->getBasePos().z();
  double lift_target = 0.0;
  auto step = [&]() {
    for (auto& f : fingers) {
      const double err = f.target - hbody->getJointPos(f.link);
      f.motor->setVelocityTarget(std::clamp(s.position_gain * err, -f.speed, f.speed));
    }
    const double err = lift_target - hbody->getJointPos(0);
    lift_motor->setVelocityTarget(std::clamp(s.position_gain * err, -s.lift_speed, s.lift_speed));
    w.world->stepSimulation(dt, 0, dt);
    ++r.steps;
  };
  auto n_steps = [&](double seconds) { return static_cast<int>(std::ceil(seconds / dt - 1e-9)); };

  // 2. close
  for (int k = 0, n = n_steps(s.close_time); k < n; ++k) step();
  r.contact_count = scan_contacts(s.contact_distance, nullptr);
  if (r.contact_count == 0) {
    r.lift_height = obody->getBasePos().z() - z0;
    return finish(SimOutcome::NoContact);
  }
  // 3. lift, 4. hold
  lift_target = s.lift_height;
  for (int k = 0, n = n_steps(s.lift_height / s.lift_speed + 0.1); k < n; ++k) step();
  for (int k = 0, n = n_steps(s.hold_time); k < n; ++k) step();
  r.contact_count = scan_contacts(s.contact_distance, nullptr);
  r.lift_height = obody->getBasePos().z() - z0;
  const bool held = r.contact_count > 0 && r.lift_height >= s.success_fraction * s.lift_height;
  return finish(held ? SimOutcome::Success : SimOutcome::NotHeld);
}

}  // namespace graspmix
