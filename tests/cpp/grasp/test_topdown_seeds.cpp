// The top-down seeds on boxes whose geometry is known exactly: the hand straight down, closing across the box's
// narrow side, centred over it, the fingertips' far end at each depth below the top (never below the floor), at
// every configuration of the configuration model's line; an object wider than the hand opens also across its parts;
// and the synthesiser scores them with the drawn grasps.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "grasp/synthetic_box.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "graspmix/grasp/topdown_seeds.hpp"

using namespace graspmix;
using graspmix::test::make_box;
using graspmix::test::top_grasp_synthesizer;
using graspmix::test::wsg50;
namespace fs = std::filesystem;

namespace {

const fs::path kRepo = GRASPMIX_SOURCE_DIR;

/// Points on the top and sides of the box centred at (cx, cy) on z = 0, sides sx x sy x sz, every 3 mm.
Vec3Array box_points(double cx, double cy, double sx, double sy, double sz) {
  std::vector<Eigen::Vector3d> p;
  for (double x = -sx / 2; x <= sx / 2 + 1e-9; x += 0.003)
    for (double y = -sy / 2; y <= sy / 2 + 1e-9; y += 0.003) p.emplace_back(cx + x, cy + y, sz);
  for (double z = 0.0; z <= sz + 1e-9; z += 0.003) {
    for (double x = -sx / 2; x <= sx / 2 + 1e-9; x += 0.003) {
      p.emplace_back(cx + x, cy - sy / 2, z);
      p.emplace_back(cx + x, cy + sy / 2, z);
    }
    for (double y = -sy / 2; y <= sy / 2 + 1e-9; y += 0.003) {
      p.emplace_back(cx - sx / 2, cy + y, z);
      p.emplace_back(cx + sx / 2, cy + y, z);
    }
  }
  Vec3Array out(static_cast<Eigen::Index>(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
  return out;
}

/// The world corners of the WSG 50's finger boxes (each fingertip's) at a seed.
std::vector<std::vector<Eigen::Vector3d>> fingertip_corners(const Hand& hand, const PoseArray& wrists,
                                                            const RowMatrixXd& joints, Eigen::Index row) {
  std::vector<Eigen::Isometry3d> links(static_cast<size_t>(hand.n_links()));
  hand.fk_into(pose_from_vector(wrists.row(row).transpose()), joints.row(row).data(), links.data());
  std::vector<std::vector<Eigen::Vector3d>> out;
  for (const int l : hand.fingertips()) {
    out.emplace_back();
    for (const CollisionShape& s : hand.links()[static_cast<size_t>(l)].collisions) {
      EXPECT_EQ(s.type, ShapeType::Box);
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d c(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
        out.back().push_back(links[static_cast<size_t>(l)] * (s.T_link_shape * c.cwiseProduct(s.size)));
      }
    }
  }
  return out;
}

/// The lowest z of a seed's fingertips, and each fingertip's middle (its corners' mean).
double lowest_and_middles(const std::vector<std::vector<Eigen::Vector3d>>& tips,
                          std::vector<Eigen::Vector3d>& middles) {
  double lowest = 1e9;
  middles.clear();
  for (const auto& corners : tips) {
    middles.emplace_back(Eigen::Vector3d::Zero());
    for (const Eigen::Vector3d& c : corners) {
      lowest = std::min(lowest, c.z());
      middles.back() += c / static_cast<double>(corners.size());
    }
  }
  return lowest;
}

}  // namespace

TEST(TopdownSeeds, StraightDownAcrossTheNarrowSideCentredAtEachDepth) {
  const auto hand = wsg50(kRepo.string());
  const auto synth = top_grasp_synthesizer(hand, make_box());
  const ConfigModel& config = synth->config_model();
  // A 60 x 100 x 140 mm box centred at (0.1, -0.05), the table z = 0 (its plane given upside down: normalised and
  // oriented by the caller, so the sign is the caller's; here n = +z).
  const Vec3Array points = box_points(0.1, -0.05, 0.06, 0.10, 0.14);
  const SeedGrasps seeds = topdown_seeds(*hand, config, points, Eigen::Vector4d(0, 0, 2, 0));
  const Eigen::Index per_height = 2 * config.kernels().rows();
  ASSERT_EQ(seeds.wrists.rows(), static_cast<Eigen::Index>(kTopdownSeedDepths.size()) * per_height);
  std::set<long> heights;
  for (Eigen::Index i = 0; i < seeds.wrists.rows(); ++i) {
    const Eigen::Isometry3d W = pose_from_vector(seeds.wrists.row(i).transpose());
    EXPECT_NEAR((W.linear() * hand->approach_axis()).z(), -1.0, 1e-9) << i;  // straight down
    EXPECT_EQ(seeds.joints.row(i), config.kernels().row(i % config.kernels().rows())) << i;
    std::vector<Eigen::Vector3d> middle;
    const double lowest = lowest_and_middles(fingertip_corners(*hand, seeds.wrists, seeds.joints, i), middle);
    ASSERT_EQ(middle.size(), 2u);
    const double depth = kTopdownSeedDepths[static_cast<size_t>(i / per_height)];
    EXPECT_NEAR(lowest, 0.14 - depth, 1e-9) << i;
    heights.insert(std::lround(lowest * 1e6));
    // The fingers face each other across x (the 60 mm side), centred over the box.
    const Eigen::Vector3d across = middle[1] - middle[0], centre = 0.5 * (middle[0] + middle[1]);
    EXPECT_NEAR(std::abs(across.normalized().x()), 1.0, 1e-9) << i;
    EXPECT_NEAR(centre.x(), 0.1, 1e-9) << i;
    EXPECT_NEAR(centre.y(), -0.05, 2e-3) << i;  // the centroid of the points across (their sampling: ~1 mm)
  }
  EXPECT_EQ(heights.size(), kTopdownSeedDepths.size());
  // A flat box, 28 mm tall: the deeper seeds stop at the floor, kTopdownSeedMinHeight, counted once.
  const SeedGrasps flat =
      topdown_seeds(*hand, config, box_points(0, 0, 0.09, 0.095, 0.028), Eigen::Vector4d(0, 0, 1, 0));
  EXPECT_EQ(flat.wrists.rows(), 2 * per_height);  // 18 mm, and 10 mm for 3, -12 and -32 mm
  for (Eigen::Index i = 0; i < flat.wrists.rows(); ++i) {
    std::vector<Eigen::Vector3d> middle;
    const double lowest = lowest_and_middles(fingertip_corners(*hand, flat.wrists, flat.joints, i), middle);
    EXPECT_NEAR(lowest, i < per_height ? 0.018 : kTopdownSeedMinHeight, 1e-9) << i;
  }
  // Too few points: none.
  EXPECT_EQ(topdown_seeds(*hand, config, points.topRows(2), Eigen::Vector4d(0, 0, 1, 0)).wrists.rows(), 0);
}

TEST(TopdownSeeds, AnObjectWiderThanTheHandOpensIsSeededAcrossItsParts) {
  const auto hand = wsg50(kRepo.string());
  const auto synth = top_grasp_synthesizer(hand, make_box());
  const ConfigModel& config = synth->config_model();
  // An L of two 30 mm bars, 30 mm tall, 200 mm long: no direction across it is narrower than ~140 mm, more than the
  // WSG 50 opens (110 mm stroke). Bar 1 along x (y in [-15, 15] mm), bar 2 along y (x in [70, 100] mm).
  const Vec3Array bar1 = box_points(0.0, 0.0, 0.2, 0.03, 0.03), bar2 = box_points(0.085, 0.115, 0.03, 0.2, 0.03);
  Vec3Array points(bar1.rows() + bar2.rows(), 3);
  points << bar1, bar2;
  const SeedGrasps seeds = topdown_seeds(*hand, config, points, Eigen::Vector4d(0, 0, 1, 0));
  // The whole object's seeds first (its top 30 mm: two heights, 20 and 10 mm), then each part's.
  const Eigen::Index whole = 2 * 2 * config.kernels().rows();
  ASSERT_GT(seeds.wrists.rows(), whole);
  std::vector<Eigen::Vector3d> centres;  // the parts' (seeds within 5 mm of each other: one part)
  for (Eigen::Index i = whole; i < seeds.wrists.rows(); ++i) {
    const Eigen::Isometry3d W = pose_from_vector(seeds.wrists.row(i).transpose());
    EXPECT_NEAR((W.linear() * hand->approach_axis()).z(), -1.0, 1e-9) << i;
    std::vector<Eigen::Vector3d> middle;
    const double lowest = lowest_and_middles(fingertip_corners(*hand, seeds.wrists, seeds.joints, i), middle);
    EXPECT_TRUE(std::abs(lowest - 0.02) < 1e-9 || std::abs(lowest - kTopdownSeedMinHeight) < 1e-9) << lowest;
    // Closing across a bar, centred on its middle line (the footprint's 5 mm cells): across bar 1 along y, across
    // bar 2 along x; never across a corner.
    const Eigen::Vector3d across = (middle[1] - middle[0]).normalized(), centre = 0.5 * (middle[0] + middle[1]);
    const bool on_bar1 = std::abs(across.y()) > std::cos(1e-6);
    const bool on_bar2 = std::abs(across.x()) > std::cos(1e-6);
    ASSERT_TRUE(on_bar1 || on_bar2) << i << ": " << across.transpose();
    if (on_bar1) {
      EXPECT_NEAR(centre.y(), 0.0, 0.004) << i;
      EXPECT_LE(std::abs(centre.x()), 0.1) << i;
    } else {
      EXPECT_NEAR(centre.x(), 0.085, 0.004) << i;
      EXPECT_GE(centre.y(), 0.015 - 0.004) << i;
    }
    // The configurations: at least as open as the bar is wide (the fingers' middles further apart than 30 mm).
    EXPECT_GT((middle[1] - middle[0]).norm(), 0.03) << i;
    if (std::none_of(centres.begin(), centres.end(),
                     [&](const Eigen::Vector3d& c) { return (c - centre).head<2>().norm() < 0.005; }))
      centres.push_back(centre);
  }
  // Several parts, kPartSeedSpacing apart, at most kPartSeedCentres.
  EXPECT_GE(centres.size(), 4u);
  EXPECT_LE(centres.size(), static_cast<size_t>(kPartSeedCentres));
}

TEST(TopdownSeeds, TheSynthesiserScoresThemWithTheDrawnGrasps) {
  const auto hand = wsg50(kRepo.string());
  const auto box = make_box();
  const auto synth = top_grasp_synthesizer(hand, box);
  CollisionSettings cs;
  cs.beta = 1000.0;
  const CollisionExpert collision(hand, box.points, Eigen::Vector4d(0, 0, 1, 0), cs);
  SynthesizerSettings s;
  s.sampling.n_samples = 40;
  s.sampling.optimise = false;
  s.query.n_samples = 300;
  s.seed = 3;
  const SeedGrasps seeds = topdown_seeds(*hand, synth->config_model(), box.points, Eigen::Vector4d(0, 0, 1, 0));
  const SynthesisResult plain = synth->synthesize(box.frames, box.features, collision, {}, s);
  const SynthesisResult seeded =
      synth->synthesize(box.frames, box.features, collision, {}, s, Eigen::VectorXd(), &seeds);
  ASSERT_EQ(seeded.grasps.size(), plain.grasps.size());  // the best n_samples of the drawn grasps and the seeds
  // Each seed is among the results with its own score (evaluate, the same scoring).
  std::mt19937_64 rng(s.seed);
  const auto query = synth->query_densities(box.frames, box.features, s.query, rng);
  const Evaluation e = synth->evaluate(Scoring{query, collision, {}}, seeds.wrists, seeds.joints);
  // The seeds kept are those that outrank the drawn grasps dropped: every seed better than the last grasp kept is
  // among them, with its own score.
  const double last = seeded.grasps.back().log_likelihood;
  int found = 0, better = 0;
  for (Eigen::Index i = 0; i < seeds.wrists.rows(); ++i) {
    better += e.total[i] > last;
    for (const Grasp& g : seeded.grasps) {
      if (g.T_world_wrist.isApprox(seeds.wrists.row(i).transpose(), 1e-12) &&
          g.joints.isApprox(seeds.joints.row(i).transpose(), 1e-12)) {
        EXPECT_NEAR(g.log_likelihood, e.total[i], 1e-9) << i;
        EXPECT_GE(g.log_likelihood, last) << i;
        ++found;
        break;
      }
    }
  }
  EXPECT_GT(better, 0);
  EXPECT_GE(found, better);
  // The box's own top grasp is among the seeds (its fingertips 4 cm down, the demonstrated opening): the best
  // seed is at least as good as the best drawn grasp, here better.
  EXPECT_GT(e.total.maxCoeff(), plain.grasps.front().log_likelihood);
}
