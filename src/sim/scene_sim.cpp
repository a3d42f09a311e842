// A scene settled in Bullet without a hand (scene_sim.hpp): the world of an execution, objects only.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "bullet_world.hpp"
#include "graspmix/sim/scene_sim.hpp"

namespace graspmix {

namespace {

using namespace sim_detail;

void check_walls(const SettleWalls& walls) {
  if (!walls.min.allFinite() || !walls.max.allFinite() || !(walls.max.x() > walls.min.x()) ||
      !(walls.max.y() > walls.min.y())) {
    throw std::invalid_argument("settle_scene: the walls' rectangle needs finite corners with max > min");
  }
  if (!std::isfinite(walls.height) || !(walls.height > 0)) {
    throw std::invalid_argument("settle_scene: the walls' height must be finite and > 0");
  }
}

/// Four 1 cm thick walls standing on the plane around the rectangle.
void add_walls(World& w, const SettleWalls& walls, double friction) {
  const double t = 0.005, h = walls.height / 2;
  const Eigen::Vector2d c = (walls.min + walls.max) / 2, half = (walls.max - walls.min) / 2;
  for (int side : {-1, 1}) {
    add_static_box(w, Eigen::Vector3d(c.x() + side * (half.x() + t), c.y(), h), Eigen::Vector3d(t, half.y() + 2 * t, h),
                   friction);
    add_static_box(w, Eigen::Vector3d(c.x(), c.y() + side * (half.y() + t), h), Eigen::Vector3d(half.x() + 2 * t, t, h),
                   friction);
  }
}

bool at_rest(const btMultiBody* b) {
  return b->getBaseVel().length() < kRestSpeed && b->getBaseOmega().length() < kRestSpin;
}

}  // namespace

SettleResult settle_scene(const std::vector<const SimObject*>& objects,
                          const std::vector<Eigen::Isometry3d>& T_world_objects, const SimSettings& s, double seconds,
                          const SettleWalls* walls) {
  check_settings(s);
  check_scene(objects, T_world_objects, "settle_scene");
  if (!std::isfinite(seconds) || seconds < 0 || seconds > kMaxSettleTime) {
    throw std::invalid_argument("settle_scene: seconds must be in [0, " + std::to_string(kMaxSettleTime) + "], got " +
                                std::to_string(seconds));
  }
  const double dt = s.time_step;
  const double n_steps = std::ceil(seconds / dt - 1e-9);
  if (n_steps > kMaxPhaseSteps) {
    throw std::invalid_argument("settle_scene: " + std::to_string(seconds) + " s takes more than " +
                                std::to_string(kMaxPhaseSteps) + " steps; use a larger time_step");
  }
  if (walls) check_walls(*walls);
  World w(s);
  add_support(w, s.support_friction);
  if (walls) add_walls(w, *walls, s.support_friction);
  std::vector<btMultiBody*> bodies;
  for (size_t i = 0; i < objects.size(); ++i) bodies.push_back(add_object(w, *objects[i], T_world_objects[i], s));
  SettleResult out;
  const int rest_steps = static_cast<int>(std::ceil(kRestTime / dt - 1e-9));
  int resting = 0;
  while (out.steps < static_cast<int>(n_steps) && resting < rest_steps) {
    w.world->stepSimulation(dt, 0, dt);
    ++out.steps;
    bool all = true;
    for (const btMultiBody* b : bodies) all = all && at_rest(b);
    resting = all ? resting + 1 : 0;
  }
  out.at_rest = resting >= rest_steps;
  out.simulated_time = out.steps * dt;
  for (size_t i = 0; i < bodies.size(); ++i) {
    out.T_world_objects.push_back(object_pose(bodies[i], *objects[i]));
    if (!out.T_world_objects.back().matrix().allFinite()) {
      throw std::invalid_argument("settle_scene: the simulation diverged (an object's pose is no longer finite)");
    }
  }
  return out;
}

}  // namespace graspmix
