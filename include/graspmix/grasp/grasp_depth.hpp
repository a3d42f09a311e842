#pragma once
// The grasp-depth expert: does the object reach far enough back between the fingers? A grasp whose fingertips
// catch only the object's last few millimetres (a rim pinched from above, a flat object taken by its top edge)
// slips out when lifted: on 800 development attempts at a named object in packed scenes (one view, GMM) half of
// the executed grasps whose fingertips reached less than 10 mm below the object's top were not held, against 3-5%
// of those reaching 15 mm or more (docs/one-view.md, "Grasps that do not hold, replayed").
//
// The measure. At a grasp (wrist W, joints q) with approach a (Hand::approach_axis in the world), the fingertip
// links (Hand::fingertips) bound by their collision shapes' corners (grasp/shape_bounds.hpp): their far end along
// the approach, reach = max a . corner, and the middle of each fingertip's corners. Between the fingers lies the
// cylinder about the line through the middles' mean along a, of radius rho = half the distance from the first
// fingertip's middle to the mean of the others' (at least min_radius). The grasp's depth is how far back from the
// fingertips' far end the object's points inside that cylinder reach:
//   depth = max over points p inside the cylinder of (reach - a . p)   (0 when none is inside),
//   log E = -penalty * max(0, min_depth - depth).
// A point beyond the fingertips counts negative, so fingertips above the whole object are charged more than
// min_depth * penalty; fingers with no point between them at all (beside the object) are charged min_depth *
// penalty, less than fingertips hovering above it: such a grasp of air is the contact quality's to refuse (its air
// penalty, 40 nats a finger). The points are the target's observed and completed surface (scene_synthesis.hpp). log E
// is finite and <= 0: a soft expert.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/experts.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

struct GraspDepthSettings {
  /// m: how far back from the fingertips' far end the object's points between the fingers must reach. 20 mm: chosen
  /// on the development objects (named object in packed scenes and single objects, one view, GMM; 10, 15, 20 mm
  /// tried: docs/one-view.md); a flat object 30 mm tall still allows it with the fingertips 10 mm above the table.
  double min_depth = 0.02;
  /// nats per metre short of min_depth: 1000, one nat per millimetre, so a grasp 10 mm short costs what 5 mm of
  /// collision depth or half a contact-quality patch charge costs.
  double penalty = 1000.0;
  /// m: the radius of the cylinder between the fingers is at least this (a single fingertip, fingers closed).
  double min_radius = 0.01;
  std::string name = "grasp_depth";  ///< the key of its term in a grasp's experts table
};

class GraspDepthExpert : public Expert {
 public:
  /// points: (N, 3) the object's surface (world frame). Throws std::invalid_argument for a null hand, a hand
  /// without fingertips or a fingertip without collision geometry, no points or non-finite ones, or bad settings
  /// (negative or non-finite min_depth, penalty or min_radius).
  GraspDepthExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& points,
                   GraspDepthSettings settings = {});

  std::string name() const override { return settings_.name; }
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;
  bool scores_in_parts() const override { return true; }
  double max_log_value() const override { return 0.0; }
  /// The depth (m) of every grasp, capped at min_depth (the search stops at the first point that reaches it).
  /// Parallel (OpenMP) over grasps. Throws std::invalid_argument for joints not (N, n_dofs), non-finite wrists or
  /// joints, or a wrist that is no pose.
  Eigen::VectorXd depths(const Eigen::Ref<const PoseArray>& wrists, const Eigen::Ref<const RowMatrixXd>& joints) const;

  const GraspDepthSettings& settings() const { return settings_; }
  const Hand& hand() const { return *hand_; }

 private:
  std::shared_ptr<const Hand> hand_;
  GraspDepthSettings settings_;
  Vec3Array points_;  ///< the object's points in a fixed shuffled order (a deep point is found early)
  std::vector<int> tips_;
  std::vector<std::vector<Eigen::Vector3d>> corners_;  ///< per fingertip, its shapes' corners in the link frame
};

}  // namespace graspmix
