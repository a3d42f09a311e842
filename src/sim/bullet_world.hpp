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
#include "graspmix/sim/scene_sim.hpp"
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

/// Every setting finite and in range, every phase bounded (sim.cpp); std::invalid_argument names the setting.
void check_settings(const SimSettings& s);
/// At least one object, as many poses, none null or non-finite; `what` names the caller in the message.
void check_scene(const std::vector<const SimObject*>& objects, const std::vector<Eigen::Isometry3d>& T_world_objects,
                 const char* what);

/// pybullet_data's plane.urdf: a 200 x 200 x 10 m static box with its top at z = 0.
const btCollisionObject* add_support(World& w, double friction);
/// A static box (walls of a settling), centre `center`, half extents `half`.
void add_static_box(World& w, const Eigen::Vector3d& center, const Eigen::Vector3d& half, double friction);
/// The object as a multibody with no links, like pybullet's import of a one-link URDF, its link frame at
/// T_world_object (mass and friction from the settings, else the URDF).
btMultiBody* add_object(World& w, const SimObject& object, const Eigen::Isometry3d& T_world_object,
                        const SimSettings& s);
/// The object's link frame from its body's (centre-of-mass) frame.
Eigen::Isometry3d object_pose(const btMultiBody* body, const SimObject& object);

}  // namespace graspmix::sim_detail
