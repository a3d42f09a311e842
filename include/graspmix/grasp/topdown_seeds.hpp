#pragma once
// Top-down seeds: grasps a geometric rule proposes besides those the query densities draw, scored, ranked and
// annealed with them by the same product of experts (GraspSynthesizer::synthesize's `seeds`;
// SamplingSettings::topdown_seeds). The rule is the top-down baseline's (python/graspmix/clutter/topdown.py) for any
// hand: the hand comes straight down the table's normal along its approach axis and closes across the object's
// narrowest horizontal direction (its closing line: from the first fingertip's middle to the others', at the
// demonstrated grasp), centred between the object's extremes along that direction and at its centroid across it;
// the far end of its fingertips at each of kTopdownSeedDepths below the object's top, never lower than
// kTopdownSeedMinHeight above the table; turned both ways about the approach axis; at every configuration of the
// configuration model's line (ConfigModel::kernels(): the object may be wider or narrower than the demonstration's,
// and the scoring picks the opening). The hand's fingertips are placed as at the demonstrated grasp. A flat object (the
// development sets' 24-28 mm blobs) gives the query densities, learnt where a box's sides were, almost nothing to draw
// that clears the table; the rule's grasp is there to be scored.
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

/// m: the fingertips' far end below the object's top, one seed pair each.
inline const std::vector<double> kTopdownSeedDepths = {0.01, 0.025, 0.04, 0.06};
/// m: ... but never lower than this above the table (the segmentation's 5 mm clearance and 5 mm more).
constexpr double kTopdownSeedMinHeight = 0.01;
/// An object wider than the hand's widest gap (the free gap between its fingertips at the most open configuration
/// of the model's line) cannot be closed across as a whole: its parts with parallel walls are seeded too. Its
/// footprint on the table in cells of kPartSeedCell m; along 18 directions, chords whose neighbours as far to either
/// side as the fingertip is half wide end within kPartSeedTaper m of its ends; of those the hand's gap spans, the
/// narrowest first, up to kPartSeedCentres kPartSeedSpacing m apart, each at the configurations whose gap is at
/// least the part's width and at most kPartSeedSlack m more (on the development objects, flat blobs 10 cm wide, the
/// xArm gripper, opening 8.9 cm, got no top-down grasp at all before).
constexpr int kPartSeedCentres = 8;
constexpr double kPartSeedCell = 0.005;
constexpr double kPartSeedTaper = 0.01;
constexpr double kPartSeedSpacing = 0.02;
constexpr double kPartSeedSlack = 0.03;

/// The top-down seeds of the object whose points (observed and completed, world frame) are given, on the table
/// `plane` [n, d] (n . x + d >= 0 above it; normalised here). None for fewer than 3 points or a hand without
/// fingertips.
SeedGrasps topdown_seeds(const Hand& hand, const ConfigModel& config, const Vec3Array& points,
                         const Eigen::Vector4d& plane);

}  // namespace graspmix
