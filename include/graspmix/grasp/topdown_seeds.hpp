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
/// An object wider than the hand's widest gap (the free gap between its fingertips' shapes along the closing line at
/// the most open configuration of the model's line) cannot be closed across as a whole: its parts with facing walls
/// are seeded too (on the development objects, flat blobs 10 cm wide, the xArm gripper, whose gap is 8.9 cm, got no
/// top-down grasp at all before; grasp/object_parts.hpp). The object's footprint on the table in cells of
/// kPartSeedCell m; along each of kPartSeedDirections directions, the chords of lines across it half a cell apart
/// (each ends where two cells in a row hold no point) no wider than the gap and a cell; each measured from the points
/// on three lines along it, its middle line and as far to either side as the fingertip is half wide: a part when the
/// middle line and a side line hold points and each side line that does ends within kPartSeedTaper m of the middle
/// line's ends (a corner's diagonal has an inner side line that runs on; a side line beyond the part's edge holds
/// none, the finger overhangs it), its width the extent of those lines, its middle between their ends, its top the
/// highest point under the fingers. Of the parts within the gap, the narrowest first, up to kPartSeedCentres whose
/// middles lie kPartSeedSpacing m apart, each seeded as the whole object is but under its own top and at the
/// configurations whose gap is at least its width and at most kPartSeedSlack m more (the narrowest wider one if
/// none). None when another object's observed point comes within kPartSeedIsolation m of the footprint (in clutter
/// a segment wider than the hand is most often two objects merged, its "parts" end at their boundary, and piles lost
/// objects to such seeds starting in collision), or when the footprint has more than kPartSeedMaxCells cells.
constexpr int kPartSeedDirections = 18;
constexpr int kPartSeedCentres = 8;
constexpr double kPartSeedCell = 0.005;
constexpr double kPartSeedTaper = 0.005;
constexpr double kPartSeedSpacing = 0.02;
constexpr double kPartSeedSlack = 0.03;
constexpr double kPartSeedIsolation = 0.02;
constexpr long kPartSeedMaxCells = 160000;

/// The top-down seeds of the object whose points (observed and completed, world frame) are given, on the table
/// `plane` [n, d] (n . x + d >= 0 above it; normalised here); `others`: the other objects' observed points (part
/// seeds only for an object none comes near). None for fewer than 3 points, a point not finite, or a hand without
/// fingertips.
SeedGrasps topdown_seeds(const Hand& hand, const ConfigModel& config, const Vec3Array& points,
                         const Eigen::Vector4d& plane, const Vec3Array& others = Vec3Array(0, 3));

}  // namespace graspmix
