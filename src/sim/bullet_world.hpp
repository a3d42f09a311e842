#pragma once
// The Bullet world of one grasp execution, built the way pybullet builds the same URDFs: private to
// src/sim/ (Bullet types never reach a public header).
#include <memory>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include "graspmix/robot/hand.hpp"
#include "graspmix/sim/sim.hpp"

namespace graspmix::sim_detail {

// pybullet's URDF importer gives every collision shape this margin.
constexpr double kCollisionMargin = 0.001;
// Links without mass (pure frames) still need some in a multibody.
constexpr double kMinLinkMass = 1e-3;

btVector3 bt(const Eigen::Vector3d& v);
btTransform bt(const Eigen::Isometry3d& T);
Eigen::Isometry3d eig(const btTransform& T);

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

  explicit World(const SimSettings& s);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  template <class T>
  T* own_shape(std::unique_ptr<T> s) {
    T* raw = s.get();
    shapes.push_back(std::move(s));
    return raw;
  }
};

/// The collision shapes of one link as a compound in the link's centre-of-mass frame (T_link_com), or
/// nullptr if the link has none.
btCompoundShape* link_shape(World& w, const LinkInfo& link, const Eigen::Isometry3d& T_link_com);
/// Mass and principal inertia as pybullet computes them by default: the URDF's mass at the URDF's
/// inertial frame, the inertia from the collision shape (its bounding box).
btVector3 shape_inertia(btCollisionShape* shape, double mass);
btMultiBodyLinkCollider* add_collider(World& w, btMultiBody* mb, int link, btCollisionShape* shape, double friction);
void sync_transforms(btMultiBody* mb);

}  // namespace graspmix::sim_detail
