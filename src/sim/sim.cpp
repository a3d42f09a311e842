// Grasp execution in Bullet (Featherstone multibodies), built the way pybullet builds the same URDFs so
// that both simulators agree (tests/python/test_sim.py compares them).
#include "graspmix/sim/sim.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>

#include "bullet_world.hpp"

namespace graspmix {

namespace {

using namespace sim_detail;

std::string number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

[[noreturn]] void bad_setting(const char* name, const std::string& rule, double v) {
  throw std::invalid_argument(std::string("SimSettings.") + name + " must be " + rule + ", got " + number(v));
}

/// Seconds the lift phase runs: the travel at lift_speed plus 0.1 s to settle.
double lift_time(const SimSettings& s) { return s.lift_height / s.lift_speed + 0.1; }

/// Physics steps of a phase of `seconds`, rounded up to whole steps (a double: check_settings bounds it
/// before anything casts it to int).
double phase_steps(double seconds, double dt) { return std::ceil(seconds / dt - 1e-9); }

}  // namespace

namespace sim_detail {

/// Every setting finite and in its range, and every phase within kMaxPhaseTime and kMaxPhaseSteps, so
/// that its step count fits an int and a run ends in bounded time (an overflowing count would skip a
/// phase and report its outcome anyway).
void check_settings(const SimSettings& s) {
  auto in_range = [](double v, const char* name, double lo, double hi, bool lo_open) {
    if (!std::isfinite(v) || v > hi || (lo_open ? !(v > lo) : !(v >= lo))) {
      bad_setting(name, std::string(lo_open ? "> " : ">= ") + number(lo) + " and <= " + number(hi), v);
    }
  };
  const double inf = std::numeric_limits<double>::max();
  in_range(s.time_step, "time_step", 0, kMaxTimeStep, true);
  if (s.solver_iterations < 1 || s.solver_iterations > kMaxSolverIterations) {
    bad_setting("solver_iterations", "in 1.." + std::to_string(kMaxSolverIterations), s.solver_iterations);
  }
  in_range(s.hand_friction, "hand_friction", 0, inf, false);
  in_range(s.support_friction, "support_friction", 0, inf, false);
  if (!std::isfinite(s.object_friction)) bad_setting("object_friction", "finite (< 0: the URDF's)", s.object_friction);
  if (!std::isfinite(s.object_mass)) bad_setting("object_mass", "finite (< 0: the URDF's)", s.object_mass);
  in_range(s.grip_force, "grip_force", 0, kMaxForce, true);
  in_range(s.close_speed, "close_speed", 0, inf, true);
  in_range(s.close_overshoot, "close_overshoot", 0, inf, false);
  in_range(s.position_gain, "position_gain", 0, inf, true);
  in_range(s.lift_height, "lift_height", 0, kMaxLiftHeight, false);
  in_range(s.lift_speed, "lift_speed", 0, inf, true);
  in_range(s.lift_force, "lift_force", 0, kMaxForce, true);
  in_range(s.start_penetration, "start_penetration", 0, inf, false);
  in_range(s.contact_distance, "contact_distance", 0, inf, false);
  in_range(s.success_fraction, "success_fraction", 0, 1, false);
  if (!s.gravity.allFinite()) throw std::invalid_argument("SimSettings.gravity must be finite");
  // name, the setting's seconds (bounded), the phase's seconds (stepped)
  const std::tuple<const char*, double, double> phases[] = {
      {"close_time", s.close_time, s.close_time},
      {"hold_time", s.hold_time, s.hold_time},
      {"lift_height / lift_speed", lift_time(s) - 0.1, lift_time(s)}};
  for (const auto& [name, seconds, run] : phases) {
    in_range(seconds, name, 0, kMaxPhaseTime, false);
    if (phase_steps(run, s.time_step) > kMaxPhaseSteps) {
      throw std::invalid_argument(std::string("SimSettings: ") + name + " = " + number(seconds) +
                                  " s takes more than " + std::to_string(kMaxPhaseSteps) + " steps of time_step " +
                                  number(s.time_step) + " s; use a larger time_step or a shorter phase");
    }
  }
}

void check_scene(const std::vector<const SimObject*>& objects, const std::vector<Eigen::Isometry3d>& T_world_objects,
                 const char* what) {
  if (objects.empty()) throw std::invalid_argument(std::string(what) + ": the scene has no object");
  if (objects.size() != T_world_objects.size()) {
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(objects.size()) + " objects but " +
                                std::to_string(T_world_objects.size()) + " poses");
  }
  for (size_t i = 0; i < objects.size(); ++i) {
    if (!objects[i]) throw std::invalid_argument(std::string(what) + ": object " + std::to_string(i) + " is null");
    if (!T_world_objects[i].matrix().allFinite()) {
      throw std::invalid_argument(std::string(what) + ": the pose of object " + std::to_string(i) + " is not finite");
    }
  }
}

}  // namespace sim_detail

namespace {

using namespace sim_detail;

/// One grasp execution: the world (support, objects, hand with its motors) and the protocol run in it.
/// Bodies, colliders and constraints are added in a fixed order, which Bullet's results depend on.
class Execution {
 public:
  Execution(const Hand& hand, const std::vector<const SimObject*>& objects, const SimSettings& s)
      : hand_(hand), objects_(objects), s_(s), w_(s), dt_(s.time_step) {}

  /// Adds the support, the objects and the hand at its pre-grasp configuration, then the hand's motors.
  void build(const std::vector<Eigen::Isometry3d>& T_world_objects, const Eigen::Isometry3d& T_world_wrist,
             const Eigen::Ref<const Eigen::VectorXd>& pregrasp, const Eigen::Ref<const Eigen::VectorXd>& grasp) {
    plane_ = add_support(w_, s_.support_friction);
    for (size_t i = 0; i < objects_.size(); ++i) {
      bodies_.push_back(add_object(w_, *objects_[i], T_world_objects[i], s_));
      start_.push_back(T_world_objects[i].translation());
    }
    const Eigen::VectorXd q_start = hand_.all_joint_values(pregrasp);
    const Eigen::VectorXd q_grasp = hand_.all_joint_values(grasp);
    add_hand(T_world_wrist, q_start);
    add_drives(q_start, q_grasp, closing_speeds(hand_, pregrasp, grasp, s_));
  }

  /// The paper's protocol: 1. start in collision? 2. close, 3. lift, 4. hold; then which objects rose in
  /// the hand.
  SceneSimResult run(std::chrono::steady_clock::time_point t0) {
    SceneSimResult out;
    SimResult& r = out.result;
    std::vector<int> per_object(bodies_.size(), 0);
    w_.world->performDiscreteCollisionDetection();
    double deepest = 0.0;
    scan_contacts(s_.contact_distance, &deepest, per_object);
    r.start_penetration = std::max(0.0, deepest);
    std::vector<double> z0;
    for (const btMultiBody* b : bodies_) z0.push_back(b->getBasePos().z());
    if (deepest > s_.start_penetration) return finish(out, z0, SimOutcome::StartInCollision, t0);

    steps(r, s_.close_time);
    r.contact_count = scan_contacts(s_.contact_distance, nullptr, per_object);
    if (r.contact_count == 0) return finish(out, z0, SimOutcome::NoContact, t0);
    lift_target_ = s_.lift_height;
    steps(r, lift_time(s_));
    steps(r, s_.hold_time);
    r.contact_count = scan_contacts(s_.contact_distance, nullptr, per_object);
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const double rise = bodies_[i]->getBasePos().z() - z0[i];
      if (per_object[i] > 0 && rise >= s_.success_fraction * s_.lift_height) out.lifted.push_back(static_cast<int>(i));
    }
    const SimOutcome o = out.lifted.empty()       ? SimOutcome::NotHeld
                         : out.lifted.size() == 1 ? SimOutcome::Success
                                                  : SimOutcome::TwoObjectsLifted;
    return finish(out, z0, o, t0);
  }

 private:
  struct Drive {
    int link;
    double target;
    double speed;
    btMultiBodyJointMotor* motor;
  };

  /// Fixed base at the wrist, link 0 = the root link on the lift joint (world +z), then the tree.
  void add_hand(const Eigen::Isometry3d& T_world_wrist, const Eigen::VectorXd& q_start) {
    const int L = hand_.n_links();
    const auto& links = hand_.links();
    const auto& joints = hand_.joints();
    shapes_.resize(static_cast<size_t>(L));
    masses_.resize(static_cast<size_t>(L));
    for (int i = 0; i < L; ++i) {
      const LinkInfo& li = links[static_cast<size_t>(i)];
      shapes_[static_cast<size_t>(i)] = link_shape(w_, li, li.T_link_inertial);
      masses_[static_cast<size_t>(i)] = std::max(li.mass, kMinLinkMass);
    }
    w_.bodies.push_back(std::make_unique<btMultiBody>(L, 0.0, btVector3(0, 0, 0), true, false));
    hand_body_ = w_.bodies.back().get();
    hand_body_->setBaseWorldTransform(bt(T_world_wrist));
    hand_body_->setHasSelfCollision(false);  // pybullet's default for loadURDF
    // The lift joint: world +z expressed in the wrist frame.
    const Eigen::Vector3d lift_axis = T_world_wrist.linear().transpose() * Eigen::Vector3d::UnitZ();
    setup_link(0, -1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), JointType::Prismatic, lift_axis);
    for (int i = 1; i < L; ++i) {
      const JointInfo& j = joints[static_cast<size_t>(links[static_cast<size_t>(i)].parent_joint)];
      setup_link(i, j.parent_link, links[static_cast<size_t>(j.parent_link)].T_link_inertial, j.T_parent_joint, j.type,
                 j.axis);
    }
    hand_body_->finalizeMultiDof();
    w_.world->addMultiBody(hand_body_);
    for (int i = 0; i < L; ++i) {
      if (shapes_[static_cast<size_t>(i)])
        add_collider(w_, hand_body_, i, shapes_[static_cast<size_t>(i)], s_.hand_friction);
    }
    hand_body_->setJointPos(0, 0.0);
    for (int i = 1; i < L; ++i) {
      const int ji = links[static_cast<size_t>(i)].parent_joint;
      if (joints[static_cast<size_t>(ji)].type != JointType::Fixed) hand_body_->setJointPos(i, q_start[ji]);
    }
    sync_transforms(hand_body_);
  }

  void setup_link(int i, int parent, const Eigen::Isometry3d& T_parent_com, const Eigen::Isometry3d& T_parent_joint,
                  JointType type, const Eigen::Vector3d& axis) {
    const LinkInfo& li = hand_.links()[static_cast<size_t>(i)];
    const btTransform offA = bt(T_parent_com.inverse() * T_parent_joint);  // joint frame in the parent's COM frame
    const btTransform offB = bt(li.T_link_inertial.inverse());             // link frame in its own COM frame
    const btQuaternion rot = offB.getRotation() * offA.getRotation().inverse();
    const btVector3 inertia = shape_inertia(shapes_[static_cast<size_t>(i)], masses_[static_cast<size_t>(i)]);
    const double m = masses_[static_cast<size_t>(i)];
    switch (type) {
      case JointType::Fixed:
        hand_body_->setupFixed(i, m, inertia, parent, rot, offA.getOrigin(), -offB.getOrigin(), true);
        break;
      case JointType::Prismatic:
        hand_body_->setupPrismatic(i, m, inertia, parent, rot, quatRotate(offB.getRotation(), bt(axis)),
                                   offA.getOrigin(), -offB.getOrigin(), true);
        break;
      case JointType::Revolute:
      case JointType::Continuous:
        hand_body_->setupRevolute(i, m, inertia, parent, rot, quatRotate(offB.getRotation(), bt(axis)),
                                  offA.getOrigin(), -offB.getOrigin(), true);
        break;
    }
  }

  /// Motors on every movable joint (velocity commands, force-limited) and the URDF limits.
  void add_drives(const Eigen::VectorXd& q_start, const Eigen::VectorXd& q_grasp, const Eigen::VectorXd& speeds) {
    const auto& links = hand_.links();
    const auto& joints = hand_.joints();
    lift_motor_ = add_motor(0, s_.lift_force);
    for (int i = 1; i < hand_.n_links(); ++i) {
      const int ji = links[static_cast<size_t>(i)].parent_joint;
      const JointInfo& j = joints[static_cast<size_t>(ji)];
      if (j.type == JointType::Fixed) continue;
      double target = q_grasp[ji] + s_.close_overshoot * (q_grasp[ji] - q_start[ji]);
      if (j.type != JointType::Continuous && std::isfinite(j.lower) && std::isfinite(j.upper) && j.lower <= j.upper) {
        target = std::clamp(target, j.lower, j.upper);
        auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(hand_body_, i, j.lower, j.upper);
        w_.world->addMultiBodyConstraint(limit.get());
        w_.constraints.push_back(std::move(limit));
      }
      fingers_.push_back({i, target, speeds[ji], add_motor(i, s_.grip_force)});
    }
  }

  btMultiBodyJointMotor* add_motor(int link, double max_force) {
    auto motor = std::make_unique<btMultiBodyJointMotor>(hand_body_, link, 0.0, max_force * dt_);
    btMultiBodyJointMotor* raw = motor.get();
    w_.world->addMultiBodyConstraint(raw);
    w_.constraints.push_back(std::move(motor));
    return raw;
  }

  /// Hand-object contact points closer than `below` (in all, and per object in `per_object`); deepest
  /// penetration of the hand into anything.
  int scan_contacts(double below, double* deepest, std::vector<int>& per_object) const {
    std::fill(per_object.begin(), per_object.end(), 0);
    int count = 0;
    btDispatcher* d = w_.world->getDispatcher();
    for (int k = 0; k < d->getNumManifolds(); ++k) {
      const btPersistentManifold* man = d->getManifoldByIndexInternal(k);
      const auto* a = btMultiBodyLinkCollider::upcast(man->getBody0());
      const auto* b = btMultiBodyLinkCollider::upcast(man->getBody1());
      const bool a_hand = a && a->m_multiBody == hand_body_, b_hand = b && b->m_multiBody == hand_body_;
      if (a_hand == b_hand) continue;  // not a hand-something pair
      const btCollisionObject* other = a_hand ? man->getBody1() : man->getBody0();
      const auto* oc = a_hand ? b : a;
      const auto it = oc ? std::find(bodies_.begin(), bodies_.end(), oc->m_multiBody) : bodies_.end();
      const bool with_object = it != bodies_.end();
      if (!with_object && other != plane_) continue;
      for (int p = 0; p < man->getNumContacts(); ++p) {
        const double dist = man->getContactPoint(p).getDistance();
        if (deepest) *deepest = std::max(*deepest, -dist);
        if (with_object && dist < below) {
          ++count;
          ++per_object[static_cast<size_t>(it - bodies_.begin())];
        }
      }
    }
    return count;
  }

  /// Steps for `seconds` (rounded up to whole steps), the motors driving towards their targets.
  void steps(SimResult& r, double seconds) {
    for (int k = 0, n = static_cast<int>(phase_steps(seconds, dt_)); k < n; ++k) {
      for (auto& f : fingers_) {
        const double err = f.target - hand_body_->getJointPos(f.link);
        f.motor->setVelocityTarget(std::clamp(s_.position_gain * err, -f.speed, f.speed));
      }
      const double err = lift_target_ - hand_body_->getJointPos(0);
      lift_motor_->setVelocityTarget(std::clamp(s_.position_gain * err, -s_.lift_speed, s_.lift_speed));
      w_.world->stepSimulation(dt_, 0, dt_);
      ++r.steps;
    }
  }

  /// The outcome, every object's final pose, rise and displacement; lift_height and the final pose of the
  /// result are those of the object that rose most (the first of equals).
  SceneSimResult finish(SceneSimResult& out, const std::vector<double>& z0, SimOutcome o,
                        std::chrono::steady_clock::time_point t0) const {
    SimResult& r = out.result;
    r.outcome = o;
    r.success = o == SimOutcome::Success;
    r.reason = to_string(o);
    size_t top = 0;
    for (size_t i = 0; i < bodies_.size(); ++i) {
      out.T_world_objects.push_back(object_pose(bodies_[i], *objects_[i]));
      // A blown-up simulation would otherwise be reported as "not held".
      if (!out.T_world_objects.back().matrix().allFinite()) {
        throw std::invalid_argument(
            "execute: the simulation diverged (an object's pose is no longer finite); check the forces, gains and "
            "time_step of SimSettings and the masses in the URDFs");
      }
      out.rise.push_back(bodies_[i]->getBasePos().z() - z0[i]);
      out.moved.push_back((out.T_world_objects.back().translation() - start_[i]).norm());
      if (out.rise[i] > out.rise[top]) top = i;
    }
    // The start check ends before anything moves: no rise is measured.
    r.lift_height = o == SimOutcome::StartInCollision ? 0.0 : out.rise[top];
    r.T_world_object_final = out.T_world_objects[top];
    r.simulated_time = r.steps * dt_;
    r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  }

  const Hand& hand_;
  const std::vector<const SimObject*>& objects_;
  const SimSettings& s_;
  World w_;
  const double dt_;
  const btCollisionObject* plane_ = nullptr;
  std::vector<btMultiBody*> bodies_;
  std::vector<Eigen::Vector3d> start_;  ///< link origins at the start
  btMultiBody* hand_body_ = nullptr;
  std::vector<btCompoundShape*> shapes_;
  std::vector<double> masses_;
  btMultiBodyJointMotor* lift_motor_ = nullptr;
  std::vector<Drive> fingers_;
  double lift_target_ = 0.0;
};

}  // namespace

Eigen::VectorXd closing_speeds(const Hand& hand, const Eigen::Ref<const Eigen::VectorXd>& pregrasp,
                               const Eigen::Ref<const Eigen::VectorXd>& grasp, const SimSettings& s) {
  check_settings(s);
  hand.check_configuration(pregrasp, "pregrasp_joints");
  hand.check_configuration(grasp, "grasp_joints");
  // Each fingertip link's point: the centre of the box around its collision vertices, in the link frame.
  std::vector<std::pair<int, Eigen::Vector3d>> tips;
  for (int l : hand.fingertips()) {
    const TriangleMesh m = hand.collision_mesh(l);
    if (m.vertices.rows() == 0) continue;
    tips.emplace_back(l, 0.5 * (m.vertices.colwise().minCoeff() + m.vertices.colwise().maxCoeff()).transpose());
  }
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  Eigen::VectorXd dof_speed(hand.n_dofs());
  for (int d = 0; d < hand.n_dofs(); ++d) {
    // The fingertips' speed per unit joint speed, by central differences of the forward kinematics (exact to
    // O(h^2) for a revolute joint's circle; a mimic linkage moves with its master).
    const double h = 1e-6;
    Eigen::VectorXd qp = pregrasp, qm = pregrasp;
    qp[d] += h;
    qm[d] -= h;
    const std::vector<Eigen::Isometry3d> Pp = hand.fk(I, qp), Pm = hand.fk(I, qm);
    double rate = 0.0;
    for (const auto& [l, c] : tips) {
      rate = std::max(rate, (Pp[static_cast<size_t>(l)] * c - Pm[static_cast<size_t>(l)] * c).norm() / (2.0 * h));
    }
    const double tip_limited = rate > 1e-9 ? s.close_speed / rate : s.close_speed;
    // Fast enough to reach the grasp joints within half the closing time, whatever the joint's travel.
    dof_speed[d] = std::max(tip_limited, 2.0 * std::abs(grasp[d] - pregrasp[d]) / std::max(s.close_time, s.time_step));
  }
  const auto& joints = hand.joints();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(joints.size()));
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].dof >= 0)
      out[static_cast<Eigen::Index>(j)] = std::abs(joints[j].multiplier) * dof_speed[joints[j].dof];
  }
  return out;
}

const char* to_string(SimOutcome outcome) {
  switch (outcome) {
    case SimOutcome::Success:
      return "success";
    case SimOutcome::StartInCollision:
      return "start in collision";
    case SimOutcome::NoContact:
      return "no contact";
    case SimOutcome::NotHeld:
      return "not held";
    case SimOutcome::TwoObjectsLifted:
      return "two objects lifted";
  }
  return "?";
}

SceneSimResult execute_scene(const Hand& hand, const std::vector<const SimObject*>& objects,
                             const std::vector<Eigen::Isometry3d>& T_world_objects,
                             const Eigen::Isometry3d& T_world_wrist, const Eigen::Ref<const Eigen::VectorXd>& pregrasp,
                             const Eigen::Ref<const Eigen::VectorXd>& grasp, const SimSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  check_settings(s);
  check_scene(objects, T_world_objects, "execute_scene");
  hand.check_configuration(pregrasp, "pregrasp_joints");
  hand.check_configuration(grasp, "grasp_joints");
  if (!T_world_wrist.matrix().allFinite()) throw std::invalid_argument("T_world_wrist must be finite");
  Execution run(hand, objects, s);
  run.build(T_world_objects, T_world_wrist, pregrasp, grasp);
  return run.run(t0);
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
  const std::vector<const SimObject*> objects{&object};
  Execution run(hand, objects, s);
  run.build({T_world_object}, T_world_wrist, pregrasp, grasp);
  return run.run(t0).result;
}

}  // namespace graspmix
