// The top-down seeds on boxes whose geometry is known exactly: the hand straight down, closing across the box's
// narrow side, centred over it, the fingertips' far end at each depth below the top (never below the floor), at
// every configuration of the configuration model's line; an object wider than the hand opens also across its parts;
// and the synthesiser scores them with the drawn grasps.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include <gtest/gtest.h>

#include "grasp/synthetic_box.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "graspmix/grasp/topdown_seeds.hpp"

using namespace graspmix;
using graspmix::test::make_box;
using graspmix::test::stack_rows;
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

/// The free gap between the WSG 50's two fingertips along the line between their middles (their boxes' corners).
double free_gap(const std::vector<std::vector<Eigen::Vector3d>>& tips) {
  std::vector<Eigen::Vector3d> middle;
  lowest_and_middles(tips, middle);
  const Eigen::Vector3d c = (middle[1] - middle[0]).normalized();
  double first = -1e9, second = 1e9;
  for (const Eigen::Vector3d& x : tips[0]) first = std::max(first, c.dot(x));
  for (const Eigen::Vector3d& x : tips[1]) second = std::min(second, c.dot(x));
  return second - first;
}

TEST(TopdownSeeds, AnObjectWiderThanTheHandOpensIsSeededAcrossItsParts) {
  const auto hand = wsg50(kRepo.string());
  const auto synth = top_grasp_synthesizer(hand, make_box());
  const ConfigModel& config = synth->config_model();
  const RowMatrixXd& kernels = config.kernels();
  // One object of two bars, wider together than the WSG 50 opens (110 mm stroke): bar 1 along x, 160 x 30 mm, 50 mm
  // tall; bar 2 along y, 25 x 80 mm, 30 mm tall, 25 mm beyond bar 1's end and 25 mm to its side.
  const Vec3Array points =
      stack_rows({box_points(0.0, 0.0, 0.16, 0.03, 0.05), box_points(0.12, 0.08, 0.025, 0.08, 0.03)});
  const Eigen::Vector4d plane(0, 0, 1, 0);
  const SeedGrasps seeds = topdown_seeds(*hand, config, points, plane);
  // The whole object's seeds first (its top 50 mm: fingertips at 40, 25 and 10 mm), then each part's.
  const Eigen::Index whole = 3 * 2 * kernels.rows();
  ASSERT_GT(seeds.wrists.rows(), whole);
  // Each configuration's free gap (the hand at the origin).
  std::vector<double> gaps;
  for (Eigen::Index k = 0; k < kernels.rows(); ++k) {
    PoseArray w(1, 7);
    w.row(0) << 0, 0, 0, 0, 0, 0, 1;
    gaps.push_back(free_gap(fingertip_corners(*hand, w, kernels.middleRows(k, 1), 0)));
  }
  std::vector<Eigen::Vector3d> centres;  // the parts' (seeds within 5 mm of each other: one part)
  int on_bar[2] = {0, 0};
  for (Eigen::Index i = whole; i < seeds.wrists.rows(); ++i) {
    const Eigen::Isometry3d W = pose_from_vector(seeds.wrists.row(i).transpose());
    EXPECT_NEAR((W.linear() * hand->approach_axis()).z(), -1.0, 1e-9) << i;
    const auto tips = fingertip_corners(*hand, seeds.wrists, seeds.joints, i);
    std::vector<Eigen::Vector3d> middle;
    const double lowest = lowest_and_middles(tips, middle);
    // Closing across a bar, centred on its middle line (measured from the points: exact), the fingertips below
    // that bar's own top (bar 1: 40, 25, 10 mm; bar 2: 20, 10 mm); never across a corner.
    const Eigen::Vector3d across = (middle[1] - middle[0]).normalized(), centre = 0.5 * (middle[0] + middle[1]);
    const int bar = std::abs(across.y()) > 1.0 - 1e-9 ? 0 : std::abs(across.x()) > 1.0 - 1e-9 ? 1 : -1;
    ASSERT_GE(bar, 0) << i << ": " << across.transpose();
    ++on_bar[bar];
    const double width = bar == 0 ? 0.03 : 0.025;
    if (bar == 0) {
      EXPECT_NEAR(centre.y(), 0.0, 1e-6) << i;
      EXPECT_LE(std::abs(centre.x()), 0.08) << i;
      EXPECT_TRUE(std::abs(lowest - 0.04) < 1e-9 || std::abs(lowest - 0.025) < 1e-9 || std::abs(lowest - 0.01) < 1e-9)
          << lowest;
    } else {
      EXPECT_NEAR(centre.x(), 0.12, 1e-6) << i;
      EXPECT_NEAR(centre.y(), 0.08, 0.04 + 1e-9) << i;
      EXPECT_TRUE(std::abs(lowest - 0.02) < 1e-9 || std::abs(lowest - 0.01) < 1e-9) << lowest;
    }
    // The configurations whose gap spans the bar and at most kPartSeedSlack more.
    const Eigen::Index k = std::find_if(kernels.rowwise().begin(), kernels.rowwise().end(),
                                        [&](const auto& r) { return r.isApprox(seeds.joints.row(i), 0.0); }) -
                           kernels.rowwise().begin();
    ASSERT_LT(k, kernels.rows()) << i;
    EXPECT_GE(gaps[static_cast<size_t>(k)], width - 1e-9) << i;
    EXPECT_LE(gaps[static_cast<size_t>(k)], width + kPartSeedSlack + 1e-9) << i;
    if (std::none_of(centres.begin(), centres.end(),
                     [&](const Eigen::Vector3d& c) { return (c - centre).head<2>().norm() < 0.005; }))
      centres.push_back(centre);
  }
  // Both bars, the narrower first; at most kPartSeedCentres parts, kPartSeedSpacing apart.
  EXPECT_GT(on_bar[0], 0);
  EXPECT_GT(on_bar[1], 0);
  EXPECT_LE(centres.size(), static_cast<size_t>(kPartSeedCentres));
  for (size_t a = 0; a < centres.size(); ++a)
    for (size_t b = a + 1; b < centres.size(); ++b)
      EXPECT_GE((centres[a] - centres[b]).head<2>().norm(), kPartSeedSpacing - 1e-9) << a << " " << b;

  // Another object's points within kPartSeedIsolation of the footprint: no part seeds; farther: the same seeds.
  const Vec3Array near = box_points(0.12, 0.08 + 0.04 + 0.015 + 0.01, 0.02, 0.02, 0.02);  // 15 mm from bar 2's end
  EXPECT_EQ(topdown_seeds(*hand, config, points, plane, near).wrists.rows(), whole);
  const Vec3Array far = box_points(0.12, 0.08 + 0.04 + 0.025 + 0.01, 0.02, 0.02, 0.02);  // 25 mm from it
  const SeedGrasps apart = topdown_seeds(*hand, config, points, plane, far);
  EXPECT_TRUE(apart.wrists.isApprox(seeds.wrists, 0.0) && apart.joints.isApprox(seeds.joints, 0.0));
  // A stray point 30 m away: a footprint beyond kPartSeedMaxCells, no part seeds, and no hang.
  Vec3Array stray = stack_rows({points, box_points(30.0, 0.0, 0.003, 0.003, 0.003).topRows(1)});
  const SeedGrasps strayed = topdown_seeds(*hand, config, stray, plane);
  EXPECT_EQ(strayed.wrists.rows(), whole);
  // A point not finite: no seeds at all.
  stray(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(topdown_seeds(*hand, config, stray, plane).wrists.rows(), 0);
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
