// synthesize_scene on a depth image of two boxes on a table, ray-cast with known intrinsics (so every object's place
// is known exactly), with a WSG 50 model learnt from a top grasp of a synthetic box: the path in one call must equal
// its steps composed by hand (segmentation, completion, surface, experts, synthesiser) grasp for grasp, rank all
// targets' grasps together with log L the sum of its terms, choose targets by the exact geometry, make types'
// scores comparable by their reference, and name what is wrong with bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error_message.hpp"
#include "grasp/synthetic_box.hpp"
#include "grasp/target_first.hpp"
#include "graspmix/core/plane.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/density/pose_mixture.hpp"
#include "graspmix/grasp/scene_synthesis.hpp"
#include "graspmix/grasp/topdown_seeds.hpp"
#include "graspmix/perception/depth_scene.hpp"
#include "perception/raycast.hpp"

using namespace graspmix;
using namespace graspmix::test;
namespace fs = std::filesystem;

namespace {

const fs::path kRepo = GRASPMIX_SOURCE_DIR;
const PinholeCamera kCam(300.0, 300.0, 159.5, 119.5, 320, 240);
const Eigen::Isometry3d kPose = looking_at({0.05, -0.5, 0.45}, {0.0, 0.0, 0.03});
// Box A (7 x 7 x 8 cm) and box B (6 x 7 x 5 cm), 5 cm apart on the table z = 0.
const Eigen::Vector3d kA_lo(-0.09, -0.04, 0.0), kA_hi(-0.02, 0.03, 0.08);
const Eigen::Vector3d kB_lo(0.03, -0.02, 0.0), kB_hi(0.09, 0.05, 0.05);

double two_boxes(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return std::min(
      {hit_box(o, d, kA_lo, kA_hi), hit_box(o, d, kB_lo, kB_hi), hit_plane(o, d, Eigen::Vector3d::UnitZ(), 0.0)});
}

const DepthView& view() {
  static const DepthView v{render(kCam, kPose, two_boxes), kCam, kPose};
  return v;
}

/// The WSG 50's synthesiser learnt from a top grasp of the synthetic box (grasp/synthetic_box.hpp).
std::shared_ptr<const GraspSynthesizer> synthesizer() {
  static const std::shared_ptr<const GraspSynthesizer> synth = top_grasp_synthesizer(wsg50(kRepo.string()), make_box());
  return synth;
}

/// The library's defaults, with fewer samples so the test is quick.
SceneSynthesisSettings small_settings() {
  SceneSynthesisSettings s;
  s.synthesizer.sampling.n_samples = 40;
  s.synthesizer.sampling.n_optimise = 3;
  s.synthesizer.annealing.iterations = 20;
  s.synthesizer.query.n_samples = 200;
  s.synthesizer.seed = 3;
  return s;
}

std::vector<SceneGraspType> one_type() { return {{synthesizer(), "top", std::nullopt}}; }

/// The object whose centroid lies in the box [lo, hi].
int object_in(const Segmentation& scene, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  for (const auto& o : scene.objects)
    if ((o.centroid.array() >= lo.array()).all() && (o.centroid.array() <= hi.array()).all()) return o.index;
  return -1;
}

/// Equal element by element, NaN (a term not evaluated: an earlier expert rejected the grasp) equal to NaN.
bool same(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a.array() == b.array() || (a.array().isNaN() && b.array().isNaN())).all();
}

}  // namespace

TEST(SceneSynthesis, EqualsItsStepsComposedByHand) {
  const SceneSynthesisSettings s = small_settings();
  SceneRequest request;
  request.target.kind = Target::Kind::Index;
  request.target.index = 1;
  const SceneSynthesis out = synthesize_scene(view(), one_type(), s, request);

  // The same steps, one by one, as the header states them.
  const Segmentation scene = segment_depth(view().depth, kCam, kPose, s.segmentation);
  ASSERT_EQ(scene.objects.size(), 2u);
  const SceneCompletion done = complete_scene(scene, *s.completion);
  const Vec3Array viewpoints = Vec3Array(kPose.translation().transpose()).replicate(scene.points.rows(), 1);
  const auto plane = std::optional<Eigen::Vector4d>(scene.plane);
  const std::shared_ptr<const Hand> hand = synthesizer()->hand_ptr();
  std::vector<Vec3Array> parts{scene.points};
  Vec3Array others(0, 3);
  for (Eigen::Index i = 0; i < scene.points.rows(); ++i)
    if (scene.labels[i] != 1) {
      others.conservativeResize(others.rows() + 1, 3);
      others.row(others.rows() - 1) = scene.points.row(i);
    }
  for (int k = 0; k < 2; ++k) {
    const auto& c = done.completions[k];
    if (!c) continue;
    parts.push_back(c->points);
    if (k != 1) {
      others.conservativeResize(others.rows() + c->points.rows(), 3);
      others.bottomRows(c->points.rows()) = c->points;
    }
  }
  const Vec3Array solid = graspmix::test::stack_rows(parts);
  auto unseen = std::make_shared<OccupancyMap>(*scene.visibility, scene.points, plane, s.occupancy);
  const CollisionExpert collision(hand, solid, plane, s.collision, unseen);
  CollisionSettings clear = s.collision;
  clear.point_radius = s.approach->clearance;
  clear.model = CollisionModel::Surface;
  auto approach = std::make_shared<CollisionExpert>(hand, solid, plane, clear);
  CollisionSettings neighbours_settings = s.collision;
  neighbours_settings.model = CollisionModel::Surface;
  auto neighbours = std::make_shared<CollisionExpert>(hand, others, std::nullopt, neighbours_settings);
  const SurfaceCloud surface = object_surface(scene, viewpoints, done.completions, 1, s.features);
  const ConfigModel& config = synthesizer()->config_model();
  const std::vector<std::shared_ptr<const Expert>> experts{
      std::make_shared<KinematicFeasibilityExpert>(hand, orient_plane(scene.plane, scene.points, PlaneSide::Mean),
                                                   *s.kinematic),
      std::make_shared<CollisionFreeExpert>(neighbours, config, "clear_of_neighbours"),
      std::make_shared<ClearApproachExpert>(approach, config, *s.approach),
      std::make_shared<GraspDepthExpert>(hand, surface.points, *s.grasp_depth),
      std::make_shared<ContactQualityExpert>(hand, surface.points, surface.normals, config, *s.contact_quality)};
  const SeedGrasps seeds =
      topdown_seeds(*hand, config, surface.points, orient_plane(scene.plane, scene.points, PlaneSide::Mean));
  ASSERT_GT(seeds.wrists.rows(), 0);
  const SynthesisResult by_hand = synthesizer()->synthesize(
      surface.frames, surface.curvatures, collision, experts, s.synthesizer,
      query_weights(surface, scene.objects[1].rows.size(), s.synthesizer.query.completed_weight), &seeds);

  // Then the fingers must meet the target first (ContactQualitySettings::target_first): each grasp's fingers closed
  // by the contact quality's own motion on the target's side of its surface (target_side) and on the other object's
  // observed points with the points the segmentation dropped that are not the target's (the nearest kept point
  // within detail::kDroppedOwnerRadius another object's, or none).
  Vec3Array observed_others(0, 3);
  for (Eigen::Index i = 0; i < scene.points.rows(); ++i)
    if (scene.labels[i] != 1) {
      observed_others.conservativeResize(observed_others.rows() + 1, 3);
      observed_others.row(observed_others.rows() - 1) = scene.points.row(i);
    }
  Vec3Array met = observed_others;
  ASSERT_GT(scene.dropped.rows(), 0);  // the clean-up dropped points here: the test sees them used
  for (Eigen::Index i = 0; i < scene.dropped.rows(); ++i) {
    Eigen::Index owner = -1;
    double best = detail::kDroppedOwnerRadius;
    for (Eigen::Index j = 0; j < scene.points.rows(); ++j)
      if (const double d = (scene.points.row(j) - scene.dropped.row(i)).norm(); d < best) best = d, owner = j;
    if (owner >= 0 && scene.labels[owner] == 1) continue;
    met.conservativeResize(met.rows() + 1, 3);
    met.row(met.rows() - 1) = scene.dropped.row(i);
  }
  ContactQualitySettings closing_only = *s.contact_quality;
  closing_only.patch_points = 0;
  Vec3Array up(met.rows(), 3);
  up.rowwise() = Eigen::RowVector3d::UnitZ();
  const Eigen::VectorXi mine =
      target_side(surface, scene.objects[1].rows.size(), met, s.completion->observed_clearance);
  const ContactQualityExpert on_target(hand, surface.points(mine, Eigen::all), surface.normals(mine, Eigen::all),
                                       config, *s.contact_quality);
  const ContactQualityExpert on_others(hand, met, up, config, closing_only);
  std::vector<Grasp> expected = by_hand.grasps;
  const auto n_grasps = static_cast<Eigen::Index>(expected.size());
  PoseArray w(n_grasps, 7);
  RowMatrixXd q(n_grasps, hand->n_dofs());
  for (Eigen::Index i = 0; i < n_grasps; ++i) {
    w.row(i) = expected[static_cast<std::size_t>(i)].T_world_wrist.transpose();
    q.row(i) = expected[static_cast<std::size_t>(i)].joints.transpose();
  }
  const RowMatrixXd t_target = on_target.evaluate(w, q).t, t_other = on_others.evaluate(w, q).t;
  for (Eigen::Index i = 0; i < n_grasps; ++i) {
    double v = 0.0;
    for (Eigen::Index f = 0; f < t_other.cols(); ++f)
      if (std::isfinite(t_other(i, f)) && !(t_target(i, f) <= t_other(i, f)))
        v = -std::numeric_limits<double>::infinity();
    Grasp& g = expected[static_cast<std::size_t>(i)];
    g.log_experts.conservativeResize(g.log_experts.size() + 1);
    g.log_experts[g.log_experts.size() - 1] = v;
    g.log_likelihood += v;
  }
  std::stable_sort(expected.begin(), expected.end(),
                   [](const Grasp& a, const Grasp& b) { return a.log_likelihood > b.log_likelihood; });
  std::vector<std::string> names = by_hand.term_names();
  names.push_back(kTargetFirstTerm);

  EXPECT_EQ(out.targets, std::vector<int>{1});
  EXPECT_EQ(out.term_names.at(0), names);
  ASSERT_EQ(out.grasps.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(out.grasps[i].object, 1);
    EXPECT_EQ(out.grasps[i].grasp.T_world_wrist, expected[i].T_world_wrist) << i;
    EXPECT_EQ(out.grasps[i].grasp.joints, expected[i].joints) << i;
    EXPECT_TRUE(same(out.grasps[i].grasp.log_terms(), expected[i].log_terms())) << i;
    EXPECT_EQ(out.grasps[i].grasp.log_likelihood, expected[i].log_likelihood) << i;
  }
  ASSERT_TRUE(std::isfinite(expected[0].log_likelihood));  // the comparison covers scored grasps
  EXPECT_EQ(out.surfaces.at(0).points, surface.points);
}

TEST(SceneSynthesis, AllTargetsRankedTogetherWithLogLTheSumOfItsTerms) {
  const SceneSynthesis out = synthesize_scene(view(), one_type(), small_settings());
  ASSERT_EQ(out.scene.objects.size(), 2u);
  EXPECT_EQ(out.targets, (std::vector<int>{0, 1}));
  ASSERT_EQ(out.grasps.size(), 80u);  // 40 samples on each target
  std::set<int> objects;
  for (std::size_t i = 0; i < out.grasps.size(); ++i) {
    const Grasp& g = out.grasps[i].grasp;
    objects.insert(out.grasps[i].object);
    if (i > 0) {
      EXPECT_GE(out.grasps[i - 1].grasp.log_likelihood, g.log_likelihood);
    }
    if (std::isfinite(g.log_likelihood)) {
      EXPECT_NEAR(g.log_terms().sum(), g.log_likelihood, 1e-9);
    }
  }
  EXPECT_EQ(objects, (std::set<int>{0, 1}));
  const auto& names = out.term_names.at(0);
  EXPECT_NE(std::find(names.begin(), names.end(), "clear_of_neighbours"), names.end());
  EXPECT_EQ(names.back(), kTargetFirstTerm);      // two objects: the fingers must meet the target first
  EXPECT_TRUE(out.timing.occupancy.has_value());  // the surface model's map of unseen space
  // The stages are disjoint: their sum (the map of unseen space counted once, not again under features) is within
  // the total.
  EXPECT_GE(out.timing.total, out.timing.segmentation + *out.timing.occupancy + out.timing.features + out.timing.query +
                                  out.timing.sampling + out.timing.optimisation);
  // The best grasp's wrist is above the table and within reach of an object (the boxes' union, grown by the
  // WSG 50's 25 cm reach from wrist to fingertips).
  const Eigen::Vector3d wrist = out.grasps[0].grasp.T_world_wrist.head<3>();
  EXPECT_GT(wrist.z(), 0.0);
  EXPECT_TRUE((wrist.array() > kA_lo.array() - 0.25).all() && (wrist.array() < kB_hi.array() + 0.25).all());
}

TEST(SceneSynthesis, TargetsChosenByTheExactGeometry) {
  const Segmentation scene = segment_depth(view().depth, kCam, kPose);
  const int a = object_in(scene, kA_lo, kA_hi), b = object_in(scene, kB_lo, kB_hi);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  ASSERT_NE(a, b);
  const Vec3Array none(0, 3);
  Target t;
  t.kind = Target::Kind::Point;
  t.point = Eigen::Vector3d(0.06, 0.015, 0.06);  // 1 cm above box B's top
  EXPECT_EQ(select_targets(scene, none, t), std::vector<int>{b});
  t.point = Eigen::Vector3d(-0.055, -0.005, 0.09);  // 1 cm above box A's top
  EXPECT_EQ(select_targets(scene, none, t), std::vector<int>{a});
  t.point = Eigen::Vector3d(0.0, 0.3, 0.0);
  EXPECT_NE(error_message([&] { select_targets(scene, none, t); }).find("names no object"), std::string::npos);
  t.kind = Target::Kind::Nearest;
  t.camera = Eigen::Vector3d(0.4, 0.0, 0.05);  // beside box B
  EXPECT_EQ(select_targets(scene, none, t), std::vector<int>{b});
  t.camera = Eigen::Vector3d(-0.4, 0.0, 0.05);  // beside box A
  EXPECT_EQ(select_targets(scene, none, t), std::vector<int>{a});
  const Vec3Array one = Vec3Array(Eigen::RowVector3d(0.4, 0.0, 0.05));  // one viewpoint for every point
  t.camera.reset();
  EXPECT_EQ(select_targets(scene, one, t), std::vector<int>{b});
  EXPECT_NE(error_message([&] { select_targets(scene, Vec3Array::Zero(2, 3), t); }).find("2 viewpoints"),
            std::string::npos);
  Segmentation empty;
  EXPECT_EQ(select_targets(empty, none, Target{}), std::vector<int>{});
  EXPECT_NE(error_message([&] { select_targets(empty, none, t); }).find("no object"), std::string::npos);
  t.kind = Target::Kind::Largest;
  const int largest = scene.objects[0].n_points >= scene.objects[1].n_points ? 0 : 1;
  EXPECT_EQ(select_targets(scene, none, t), std::vector<int>{largest});
  t.kind = Target::Kind::Index;
  t.index = 2;
  EXPECT_NE(error_message([&] { select_targets(scene, none, t); }).find("no object 2"), std::string::npos);
}

TEST(SceneSynthesis, TypesScoredByTheirReference) {
  SceneRequest request;
  request.target.kind = Target::Kind::Index;
  request.target.index = 0;
  const SceneSynthesis one = synthesize_scene(view(), one_type(), small_settings(), request);
  const std::vector<SceneGraspType> two{{synthesizer(), "a", 1.5}, {synthesizer(), "b", -2.0}};
  const SceneSynthesis out = synthesize_scene(view(), two, small_settings(), request);
  ASSERT_EQ(out.grasps.size(), 2 * one.grasps.size());
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(out.term_names[k].back(), kTypeReferenceTerm);
    EXPECT_EQ(out.term_names[k].size(), one.term_names[0].size() + 1);
  }
  // Each type's grasps are the one type's, less its reference, ranked together.
  const double ref[2] = {1.5, -2.0};
  std::vector<double> expected;
  for (double r : ref)
    for (const auto& g : one.grasps) expected.push_back(g.grasp.log_likelihood - r);
  std::sort(expected.begin(), expected.end(), std::greater<>());
  for (std::size_t i = 0; i < out.grasps.size(); ++i) {
    const SceneGrasp& g = out.grasps[i];
    const Eigen::VectorXd terms = g.grasp.log_terms();
    EXPECT_EQ(terms[terms.size() - 1], -ref[g.type]);
    EXPECT_EQ(g.grasp.log_likelihood, expected[i]);
  }
}

TEST(SceneSynthesis, BadInputNamesWhatIsWrong) {
  EXPECT_NE(error_message([] { synthesize_scene(view(), {}, small_settings()); }).find("no grasp type"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              synthesize_scene(view(), {{nullptr, "x", std::nullopt}}, small_settings());
            }).find("'x' has no synthesiser"),
            std::string::npos);
  const Vec3Array S = kCam.back_project(view().depth);
  Vec3Array points(0, 3);
  for (Eigen::Index r = 0; r < S.rows(); ++r)
    if (S.row(r).allFinite()) {
      points.conservativeResize(points.rows() + 1, 3);
      points.row(points.rows() - 1) = (kPose * Eigen::Vector3d(S.row(r).transpose())).transpose();
    }
  SceneSynthesisSettings occupancy = small_settings();
  occupancy.collision.model = CollisionModel::Occupancy;
  SceneRequest table;  // known: without viewpoints the plane rule cannot tell the table from a wall
  table.plane = Eigen::Vector4d(0, 0, 1, 0);
  const std::string no_cameras =
      error_message([&] { synthesize_scene(CloudInput{points, Vec3Array(0, 3)}, one_type(), occupancy, table); });
  EXPECT_NE(no_cameras.find("needs the cameras' positions"), std::string::npos) << no_cameras;
  SceneSynthesisSettings no_kinematic = small_settings();
  no_kinematic.kinematic.reset();
  SceneRequest reach;
  reach.reachable = [](const PoseArray& w, const RowMatrixXd&) {
    return Eigen::Matrix<bool, Eigen::Dynamic, 1>::Constant(w.rows(), true);
  };
  EXPECT_NE(error_message([&] {
              synthesize_scene(view(), one_type(), no_kinematic, reach);
            }).find("reachable needs the kinematic expert"),
            std::string::npos);
  DepthView empty = view();
  empty.depth.setConstant(std::numeric_limits<double>::quiet_NaN());
  EXPECT_NE(error_message([&] { synthesize_scene(empty, one_type(), small_settings()); }), "no error");
}

TEST(SceneSynthesis, TheTargetsSideLeavesOutItsCompletedPointsAtANeighbour) {
  // Seeded random surface points (the first half observed, the rest completed) and other objects' points; the rows
  // kept against a brute-force distance test, and points exactly at the radius and just inside it.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  const Eigen::Index n = 400, n_observed = 200;
  SurfaceCloud surface;
  surface.points.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) surface.points.row(i) << u(rng), u(rng), u(rng);
  surface.indices = Eigen::VectorXi::LinSpaced(n, 0, static_cast<int>(n - 1));
  Vec3Array others(201, 3);
  for (Eigen::Index i = 0; i < 200; ++i) others.row(i) << u(rng), u(rng), u(rng);
  others.row(200) << 30.0, 0.0, 0.0;  // a stray point far off
  const double r = kTargetSideClearance;
  // completed rows 300 and 301: exactly at the radius from other point 0, and just inside it
  surface.points.row(300) = others.row(0) + Eigen::RowVector3d(r, 0, 0);
  surface.points.row(301) = others.row(0) + Eigen::RowVector3d(0, 0.999 * r, 0);
  std::vector<int> expected;
  for (Eigen::Index i = 0; i < n; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < others.rows(); ++j)
      nearest = std::min(nearest, (surface.points.row(i) - others.row(j)).norm());
    if (i < n_observed || nearest >= r) expected.push_back(static_cast<int>(i));
  }
  const Eigen::VectorXi kept = target_side(surface, n_observed, others);
  EXPECT_EQ(std::vector<int>(kept.data(), kept.data() + kept.size()), expected);
  EXPECT_TRUE(std::find(expected.begin(), expected.end(), 300) != expected.end());
  EXPECT_TRUE(std::find(expected.begin(), expected.end(), 301) == expected.end());
  EXPECT_LT(expected.size(), static_cast<std::size_t>(n - 10));  // some completed points were near: the test bites
  EXPECT_EQ(target_side(surface, n_observed, Vec3Array(0, 3)).size(), n);
  EXPECT_EQ(target_side(surface, n, others).size(), n);  // nothing completed
  EXPECT_THROW(target_side(surface, n_observed, others, 0.0), std::invalid_argument);
  SurfaceCloud bad = surface;
  bad.indices.resize(3);
  EXPECT_THROW(target_side(bad, n_observed, others), std::invalid_argument);
}
