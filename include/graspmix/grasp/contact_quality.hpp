#pragma once
// The contact-quality expert: would the grasp hold? The hand closes from the grasp's pre-grasp until each
// finger meets the object's cloud, and the contacts found are scored by the antipodal test with Coulomb
// friction (Nguyen 1988: two contacts whose line lies inside both friction cones give force closure).
//
// Closing. For a grasp (wrist, q) with pre-grasp p = ConfigModel::pregrasps_for(q), the joints move along
//   q(t) = p + t (c - p),  t in [0, 1],
// c being every joint pushed to its limit in the closing direction sign(q - p), or, where q == p (a pre-grasp
// clamped at a joint limit), the demonstration's sign(h_g - h_e) (a joint it does not move stays); a joint
// without a finite limit there closes by max(|q - p|, |h_g - h_e|) past q. The finger links are the hand's
// fingertips (Hand::fingertips: the WSG 50's finger_left and finger_right, the xArm gripper's finger pads, not its
// knuckles). A finger's
// contact time t_f is the first t at which an object point lies within contact_tolerance of (or inside) its
// collision geometry:
//   * a link moved by prismatic joints alone whose shapes are boxes or meshes (parallel grippers) translates
//     linearly in t: t_f is found exactly per point, as the time the point enters the box grown by the
//     tolerance on every side (a slab test; this is the signed-distance rule on faces and up to
//     (sqrt(3) - 1) tolerance more generous at the box's corners), or the mesh's hull with every plane moved
//     out by the tolerance (the hull rule below; its proxy box keeps the points that need the planes);
//   * any other link: closing_steps even steps of the signed distance (collision.hpp's shape rule, meshes
//     as their hulls), then bisection in the step where the first point comes within the tolerance.
// Only the points in the bounding box of the link's swept region (a grid over the cloud) are visited.
// The contact patch is the points within 2 * contact_tolerance of the link at t_f (those the finger presses
// once it squeezes by one more tolerance); the contact point is their mean, the contact normal the principal
// axis of their normals (the normals' sign is not trusted), pointed back against the finger's motion.
//
// The measure, "antipodal friction-cone deviation". For two contacts c1, c2 with normal axes n1, n2:
//   d = unit(c2 - c1),  theta_i = acos(|n_i . d|)  (0 when the line of the grasp is along the normal),
//   log E = -concentration * sum_i max(0, theta_i - atan(friction)) - air_penalty * (fingers without contact)
//           - patch_penalty * sum_f max(0, 1 - |patch_f| / reference_f)  (fingers with contact),
// the last term charging a finger that presses on few points (an edge, a corner, a sharply curved spot);
// reference_f = min(patch_points, the patch finger f makes closing face-on onto a flat wall of the cloud's spacing),
// so a fingertip smaller than patch_points' area is not charged on a flat face (patch_reference()).
// With more than two contacts every pair is scored and the best pair counts (a pair inside its cones is
// enough to hold); the Ferrari-Canny epsilon is not implemented. With fewer than two contacts only the air
// and patch terms are charged. log E is finite and <= 0: a soft expert.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/grasp/experts.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

struct ContactQualitySettings {
  double friction = 0.5;  ///< Coulomb coefficient mu (> 0): the friction cone's half-angle is atan(mu)
  /// nats per radian beyond the friction cone, per contact. 10: 0.1 rad (6 degrees) outside costs one nat,
  /// a corner pinch (both contacts 45 degrees off the grasp line, 18 degrees outside a mu = 0.5 cone) about
  /// 6.4 nats, a weight comparable to the collision expert's (1 nat per 0.5 mm) and the contact terms.
  double concentration = 10.0;
  /// nats per finger that closes on nothing (on the observed and completed object). 40: such a grasp ranks below
  /// nearly every grasp whose fingers both touch. One view, GMM, both development sets (900 attempts), 5 / 10 / 20 /
  /// 40 lifted 82.7 / 84.0 / 85.0 / 85.6%, 80 on test60 as 40 (docs/one-view.md); it was 5, what 0.5 rad outside the
  /// cone costs.
  double air_penalty = 40.0;
  /// A finger whose contact patch (the cloud points its surface meets first, within the tolerance) holds fewer than
  /// patch_points points costs patch_penalty * (1 - its points / patch_points) nats: a pad that touches an edge, a
  /// corner or a strongly curved spot resists the object's turning about the grasp line far less than one pressed
  /// flat on a face, and such grasps were the commonest "not held". 30 points are 2.7 cm2 at the segmentation's
  /// 3 mm spacing (an eighth of the WSG 50's 30 x 73 mm pad). Chosen on the development sets (docs/one-view.md,
  /// "A finger on a small patch"): one view, GMM, test60 83.5 -> 88.2% (+44 / -16), clutter_dev 89.7 -> 90.7%;
  /// 0 points: off. A finger whose pad cannot press on patch_points points of a flat face is measured against what
  /// it can (ContactQualityExpert::patch_reference).
  double patch_points = 30.0;
  double patch_penalty = 20.0;
  double contact_tolerance = 1e-3;       ///< m: points within this of a link's surface are in contact (>= 0)
  int closing_steps = 16;                ///< steps of the closing motion before bisection (links that do not translate)
  std::string name = "contact_quality";  ///< the key of its term in a grasp's experts table
  /// Scene synthesis with other objects: a returned grasp whose finger, closing from the pre-grasp, meets another
  /// object's observed points (or a point the segmentation dropped that is not the target's) before the target's
  /// (scene_synthesis.hpp's target_side) is rejected (its "target_first" term -inf, ranked after the others). Of
  /// the neighbours lifted instead of a named object on the development scenes, every one had such a finger
  /// (docs/one-view.md, "The fingers meet the target first").
  bool target_first = true;
};

/// The contacts of N grasps, F finger links each (ContactQualityExpert::finger_links() order).
struct ContactQualityResult {
  std::vector<int> links;      ///< (F) the finger links (indices into Hand::link_names())
  RowMatrixXd t;               ///< (N, F) closing parameter of the first contact; NaN: the finger met nothing
  RowMatrixXd joints;          ///< (N, F * D) the configuration q(t_f) at each finger's contact (NaN: none)
  RowMatrixXd points;          ///< (N, F * 3) contact points (world; NaN: none)
  RowMatrixXd normals;         ///< (N, F * 3) contact normal axes, unit, pointing towards the finger (NaN: none)
  RowMatrixXd angles;          ///< (N, F) theta_f (rad) in the scored pair; NaN for fingers outside it
  Eigen::MatrixXi patch_size;  ///< (N, F) points in each contact patch (0: no contact)
  Eigen::VectorXd log_value;   ///< (N) log E
};

class ContactQualityExpert : public Expert {
 public:
  /// points, normals: (N, 3) the object's cloud and its surface normals (world frame; each normal is taken
  /// as an axis, its sign ignored). config: the configuration model whose pregrasps_for(q) opens each grasp.
  /// Throws std::invalid_argument for a null hand, a hand without finger links, a configuration model of
  /// another dimension, points and normals of different shapes, non-finite values, zero normals, or bad
  /// settings (friction <= 0, a negative concentration, penalty or tolerance, closing_steps < 1).
  ContactQualityExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& points,
                       const Eigen::Ref<const Vec3Array>& normals, ConfigModel config,
                       ContactQualitySettings settings = {});
  ~ContactQualityExpert() override;

  std::string name() const override { return settings_.name; }
  /// log E for every grasp (N). Parallel (OpenMP) over grasps.
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;
  bool scores_in_parts() const override { return true; }
  /// A cost is never negative: log E <= 0.
  double max_log_value() const override { return 0.0; }
  /// The contacts and angles behind log_value: wrists (N, 7), joints (N, D). Parallel (OpenMP).
  ContactQualityResult evaluate(const Eigen::Ref<const PoseArray>& wrists,
                                const Eigen::Ref<const RowMatrixXd>& joints) const;

  const Hand& hand() const { return *hand_; }
  const std::vector<int>& finger_links() const { return fingers_; }
  const ContactQualitySettings& settings() const { return settings_; }
  const ConfigModel& config() const { return config_; }
  Eigen::Index n_points() const;
  /// Per finger, the patch below which it is charged: patch_points, or fewer for a finger whose pad cannot press on
  /// that many: min(patch_points, flat_patches at the cloud's spacing, the median distance to a point's nearest
  /// neighbour; a denser cloud's counted on a 3 mm wall and scaled by the squared ratio of the spacings). At 3 mm the
  /// WSG 50's pads meet 286 points of a wall, the Panda's 60, the xArm's 159, the PR2 gripper's tips 7 (15 of the
  /// demonstration's box): only the PR2's reference is below 30.
  const std::vector<double>& patch_reference() const { return patch_reference_; }

  struct Index;  ///< the cloud's grid and normals (defined in src/)

 private:
  std::shared_ptr<const Hand> hand_;
  ConfigModel config_;
  ContactQualitySettings settings_;
  std::vector<int> fingers_;
  std::vector<bool> translating_;  ///< per finger: moved by prismatic joints only, box or mesh shapes only
  std::unique_ptr<const Index> index_;
  std::vector<double> patch_reference_;
  /// Per finger, the points of its patch on a flat wall of points `spacing` apart (at least 3 mm; finer counts
  /// scaled from it), as wide as the finger's outline, set up as the demonstration's
  /// box faces stand: the hand at the demonstrated grasp, the wall facing the line from the finger's middle to the
  /// fingers' centre (one finger: its motion) and touching its foremost point, the hand closed from the pre-grasp
  /// onto it; 0 for a finger without geometry or motion.
  std::vector<double> flat_patches(double spacing) const;
};

}  // namespace graspmix
