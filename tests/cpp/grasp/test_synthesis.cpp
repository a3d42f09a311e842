// The synthesiser on a synthetic box whose surface, frames and features are known exactly: learnt
// from a demonstrated top grasp of the WSG 50, it must give reproducible, correctly ranked grasps,
// annealing must never make a grasp worse, and the log-likelihood must be the sum of its experts.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <tuple>

#include <gtest/gtest.h>
#include <omp.h>

#include "grasp/synthetic_box.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/density/pose_mixture.hpp"
#include "graspmix/grasp/synthesis.hpp"

using namespace graspmix;
using graspmix::test::Box;
using graspmix::test::make_box;
using graspmix::test::top_grasp_synthesizer;
using graspmix::test::wsg50;
namespace fs = std::filesystem;

namespace {

const fs::path kRepo = GRASPMIX_SOURCE_DIR;  // set by CMakeLists.txt for the tests

struct Fixture {
  std::shared_ptr<const Hand> hand;
  Box box;
  std::unique_ptr<GraspSynthesizer> synth;
  std::unique_ptr<CollisionExpert> collision;
};

Fixture make_fixture() {
  Fixture f;
  f.hand = wsg50(kRepo.string());
  f.box = make_box();
  f.synth = top_grasp_synthesizer(f.hand, f.box);
  CollisionSettings collision;
  collision.beta = 1000.0;  // the value these tests were written with (the default is now 2000)
  f.collision = std::make_unique<CollisionExpert>(f.hand, f.box.points, Eigen::Vector4d(0, 0, 1, 0), collision);
  return f;
}

SynthesizerSettings small_settings(std::uint64_t seed) {
  SynthesizerSettings s;
  s.sampling.n_samples = 60;
  s.sampling.n_optimise = 5;
  s.annealing.iterations = 30;
  s.query.n_samples = 300;
  s.seed = seed;
  return s;
}

/// The box's query densities and n grasps drawn from them.
std::tuple<std::vector<QueryDensity>, PoseArray, RowMatrixXd> sampled(const Fixture& f, int n, std::mt19937_64& rng) {
  auto query = f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, rng);
  PoseArray w;
  RowMatrixXd q;
  f.synth->sample_grasps(query, n, rng, w, q);
  return {std::move(query), std::move(w), std::move(q)};
}

}  // namespace

TEST(Synthesis, ContactModelsForTheTouchingLinksOnly) {
  const Fixture f = make_fixture();
  std::vector<std::string> links;
  for (const auto& m : f.synth->contact_models()) links.push_back(m.link_name);
  // The fingers touch the sides; the palm hovers 6 mm above the top face, within the 1 cm cut-off.
  EXPECT_EQ(links, (std::vector<std::string>{"palm", "finger_left", "finger_right"}));
  EXPECT_EQ(f.synth->method(), "gmm");
}

TEST(Synthesis, SameSeedSameGraspsRankedBestFirstWithConsistentTerms) {
  const Fixture f = make_fixture();
  const std::vector<std::shared_ptr<const Expert>> experts{
      std::make_shared<KinematicFeasibilityExpert>(f.hand, Eigen::Vector4d(0, 0, 1, 0))};
  const SynthesisResult a = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, experts, small_settings(7));
  const SynthesisResult b = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, experts, small_settings(7));
  const SynthesisResult c = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, experts, small_settings(8));
  ASSERT_EQ(a.grasps.size(), 60u);
  for (size_t i = 0; i < a.grasps.size(); ++i) {
    EXPECT_TRUE(a.grasps[i].T_world_wrist.isApprox(b.grasps[i].T_world_wrist, 0.0));
    EXPECT_EQ(a.grasps[i].log_likelihood, b.grasps[i].log_likelihood);
    if (i > 0) {
      EXPECT_GE(a.grasps[i - 1].log_likelihood, a.grasps[i].log_likelihood);
    }
    const Grasp& g = a.grasps[i];
    if (std::isfinite(g.log_likelihood)) {
      const double sum = g.log_collision + g.log_config + g.log_pregrasp + g.log_contact.sum() + g.log_experts.sum();
      EXPECT_NEAR(g.log_likelihood, sum, 1e-9);
    }
  }
  EXPECT_FALSE(a.grasps[0].T_world_wrist.isApprox(c.grasps[0].T_world_wrist, 1e-12));
  int optimised = 0;
  for (const Grasp& g : a.grasps) optimised += g.optimised;
  EXPECT_EQ(optimised, 5);
  EXPECT_GT(a.timing.total, 0.0);
}

TEST(Synthesis, AnnealingNeverMakesAGraspWorse) {
  const Fixture f = make_fixture();
  std::mt19937_64 rng(3);
  auto [query, w, q] = sampled(f, 12, rng);
  const std::vector<std::shared_ptr<const Expert>> none;
  const Scoring scoring{query, *f.collision, none};
  const Eigen::VectorXd before = f.synth->evaluate(scoring, w, q).total;
  AnnealingSettings s;
  s.iterations = 40;
  f.synth->anneal(scoring, s, rng, w, q);
  const Eigen::VectorXd after = f.synth->evaluate(scoring, w, q).total;
  for (Eigen::Index i = 0; i < before.size(); ++i) EXPECT_GE(after[i], before[i]) << i;
  EXPECT_GT(after.sum(), before.sum());
}

TEST(Synthesis, SampledLinkPosesFollowTheQueryDensityThroughFk) {
  const Fixture f = make_fixture();
  std::mt19937_64 rng(4);
  const auto query = f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, rng);
  PoseArray w;
  RowMatrixXd q;
  f.synth->sample_grasps(query, 200, rng, w, q);
  const std::vector<std::shared_ptr<const Expert>> none;
  const Scoring unclear{query, *f.collision, none, false};
  // Each grasp puts one contact link where its query density has mass: the best link term of a
  // sampled grasp is far above that of grasps moved 20 cm away.
  const Evaluation e = f.synth->evaluate(unclear, w, q);
  PoseArray far = w;
  far.col(0).array() += 0.2;
  const Evaluation g = f.synth->evaluate(unclear, far, q);
  EXPECT_GT(e.log_contact.rowwise().maxCoeff().mean(), g.log_contact.rowwise().maxCoeff().mean() + 20.0);
}

/// A soft expert (log E <= 0: the wrist's height off 25 cm, 40 nats per m) that counts the grasps it scores;
/// `bounded` says whether it declares its bound (max_log_value 0) or not (+inf).
class CountingPenalty : public Expert {
 public:
  explicit CountingPenalty(bool bounded) : bounded_(bounded) {}
  std::string name() const override { return "height"; }
  Eigen::VectorXd log_value(const GraspBatch& b) const override {
    scored += b.wrists.rows();
    largest_batch = std::max(largest_batch, b.wrists.rows());
    return -40.0 * (b.wrists.col(2).array() - 0.25).abs();
  }
  double max_log_value() const override { return bounded_ ? 0.0 : std::numeric_limits<double>::infinity(); }
  // scores_in_parts: false (Expert's default): it counts, one thread at a time
  mutable Eigen::Index scored = 0;
  mutable Eigen::Index largest_batch = 0;

 private:
  bool bounded_;
};

TEST(Synthesis, AnnealingSkipsABoundedLastExpertOnlyWhereTheOutcomeIsDecided) {
  // The same synthesis with the last expert's bound declared and not: the same grasps, bit for bit (a proposal is
  // skipped only where its other terms and the bound already refuse it), with fewer grasps scored by the expert.
  const Fixture f = make_fixture();
  auto bounded = std::make_shared<CountingPenalty>(true), open = std::make_shared<CountingPenalty>(false);
  const auto kinematic = std::make_shared<KinematicFeasibilityExpert>(f.hand, Eigen::Vector4d(0, 0, 1, 0));
  SynthesizerSettings s = small_settings(5);
  s.annealing.iterations = 60;
  const SynthesisResult a = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, {kinematic, bounded}, s);
  const SynthesisResult b = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, {kinematic, open}, s);
  ASSERT_EQ(a.grasps.size(), b.grasps.size());
  for (std::size_t i = 0; i < a.grasps.size(); ++i) {
    EXPECT_EQ(a.grasps[i].T_world_wrist, b.grasps[i].T_world_wrist) << i;
    EXPECT_EQ(a.grasps[i].joints, b.grasps[i].joints) << i;
    EXPECT_EQ(a.grasps[i].log_likelihood, b.grasps[i].log_likelihood) << i;
    EXPECT_EQ(a.grasps[i].optimised, b.grasps[i].optimised) << i;
  }
  EXPECT_LT(bounded->scored, open->scored);
  EXPECT_GT(bounded->scored, 0);
}

TEST(Synthesis, OversamplingIsTheSearchOfMoreSamplesCutToNSamples) {
  // oversample k draws and ranks k * n_samples grasps with the random numbers of a synthesis of k * n_samples, anneals
  // the same best n_optimise, and returns the first n_samples of that synthesis's grasps, bit for bit.
  const Fixture f = make_fixture();
  const std::vector<std::shared_ptr<const Expert>> experts{
      std::make_shared<KinematicFeasibilityExpert>(f.hand, Eigen::Vector4d(0, 0, 1, 0))};
  SynthesizerSettings wide = small_settings(4), over = small_settings(4);
  wide.sampling.n_samples = 90;
  wide.sampling.oversample = 1;
  over.sampling.n_samples = 30;
  over.sampling.oversample = 3;
  const SynthesisResult a = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, experts, wide);
  const SynthesisResult b = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, experts, over);
  ASSERT_EQ(a.grasps.size(), 90u);
  ASSERT_EQ(b.grasps.size(), 30u);
  for (std::size_t i = 0; i < b.grasps.size(); ++i) {
    EXPECT_EQ(a.grasps[i].T_world_wrist, b.grasps[i].T_world_wrist) << i;
    EXPECT_EQ(a.grasps[i].joints, b.grasps[i].joints) << i;
    EXPECT_EQ(a.grasps[i].log_likelihood, b.grasps[i].log_likelihood) << i;
    EXPECT_EQ(a.grasps[i].optimised, b.grasps[i].optimised) << i;
  }
  EXPECT_EQ(a.evaluations, b.evaluations);
  // and it is a wider search than n_samples alone: another draw, no worse a best grasp on this box
  SynthesizerSettings narrow = over;
  narrow.sampling.oversample = 1;
  const SynthesisResult c = f.synth->synthesize(f.box.frames, f.box.features, *f.collision, experts, narrow);
  EXPECT_LT(c.evaluations, b.evaluations);
  EXPECT_NE(c.grasps.front().T_world_wrist, b.grasps.front().T_world_wrist);
}

TEST(Synthesis, PointWeightsSteerTheQueryDensities) {
  // Weight 0 on every face but the +x side: each link's query density then lies on +x faces' frames moved by
  // its contact model, so its mean position is the same as that of densities fitted on the +x face alone,
  // and far from the unweighted one's (which spans the box).
  const Fixture f = make_fixture();
  const Eigen::Index n = f.box.frames.rows();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < n; ++i)
    if (f.box.frames(i, 0) > 0.0299) {
      w[i] = 1.0;
      rows.push_back(i);
    }
  PoseArray face(static_cast<Eigen::Index>(rows.size()), 7);
  RowMatrixXd face_features(face.rows(), 2);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    face.row(static_cast<Eigen::Index>(j)) = f.box.frames.row(rows[j]);
    face_features.row(static_cast<Eigen::Index>(j)) = f.box.features.row(rows[j]);
  }
  std::mt19937_64 a(3), b(3), c(3);
  const auto weighted = f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, a, w);
  const auto alone = f.synth->query_densities(face, face_features, QuerySettings{}, b);
  const auto all = f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, c);
  std::mt19937_64 draw(5);
  for (std::size_t l = 0; l < weighted.size(); ++l) {
    const Eigen::Vector3d mw = weighted[l].density->sample(RowMatrixXd(2000, 0), draw).leftCols<3>().colwise().mean();
    const Eigen::Vector3d ma = alone[l].density->sample(RowMatrixXd(2000, 0), draw).leftCols<3>().colwise().mean();
    const Eigen::Vector3d mu = all[l].density->sample(RowMatrixXd(2000, 0), draw).leftCols<3>().colwise().mean();
    EXPECT_LT((mw - ma).norm(), 0.01) << l;
    EXPECT_GT((mw - mu).norm(), 0.02) << l;
  }
  // Uniform weights change nothing: the same draws as none.
  std::mt19937_64 d(3);
  const auto ones =
      f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, d, Eigen::VectorXd::Ones(n));
  std::mt19937_64 r1(1), r2(1);
  EXPECT_TRUE(ones[0].density->sample(RowMatrixXd(10, 0), r1).isApprox(all[0].density->sample(RowMatrixXd(10, 0), r2)));
  std::mt19937_64 e(1);
  EXPECT_THROW(f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, e, Eigen::VectorXd::Ones(3)),
               std::invalid_argument);
  EXPECT_THROW(f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, e, Eigen::VectorXd::Zero(n)),
               std::invalid_argument);
  EXPECT_THROW(f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, e, -Eigen::VectorXd::Ones(n)),
               std::invalid_argument);
}

TEST(Synthesis, BadInputThrows) {
  const Fixture f = make_fixture();
  EXPECT_THROW(f.synth->synthesize(PoseArray(0, 7), RowMatrixXd(0, 2), *f.collision, {}, small_settings(0)),
               std::invalid_argument);
  EXPECT_THROW(
      f.synth->synthesize(f.box.frames, RowMatrixXd::Zero(f.box.frames.rows(), 3), *f.collision, {}, small_settings(0)),
      std::invalid_argument);
  SynthesizerSettings s = small_settings(0);
  for (const int bad : {0, kMaxOversample + 1}) {
    s.sampling.oversample = bad;
    EXPECT_THROW(f.synth->synthesize(f.box.frames, f.box.features, *f.collision, {}, s), std::invalid_argument);
  }
  s.sampling.oversample = kMaxOversample;
  s.sampling.n_samples = std::numeric_limits<int>::max() / 2;
  EXPECT_THROW(f.synth->synthesize(f.box.frames, f.box.features, *f.collision, {}, s), std::invalid_argument);
  Eigen::VectorXd two(2);
  two << 0.0, 0.0;
  EXPECT_THROW(GraspSynthesizer(f.hand, f.synth->contact_models(), ConfigModel(two, two, RowMatrixXd::Zero(2, 2))),
               std::invalid_argument);
}

TEST(Synthesis, AnnealingOnSeveralThreadsGivesTheGraspsOfOne) {
  // anneal() draws its random numbers first and runs blocks of chains on threads of their own: 12 chains on 1, 2
  // and 3 threads end bit for bit alike. An expert that does not score in parts keeps them on one thread and sees
  // every chain in each batch.
  const Fixture f = make_fixture();
  std::mt19937_64 rng(9);
  const auto start = sampled(f, 12, rng);  // (no structured binding: the lambda below captures these)
  const std::vector<QueryDensity>& query = std::get<0>(start);
  const PoseArray& w0 = std::get<1>(start);
  const RowMatrixXd& q0 = std::get<2>(start);
  const auto kinematic = std::make_shared<KinematicFeasibilityExpert>(f.hand, Eigen::Vector4d(0, 0, 1, 0));
  AnnealingSettings s;
  s.iterations = 25;
  const auto annealed = [&](int threads, const std::vector<std::shared_ptr<const Expert>>& experts) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    PoseArray w = w0;
    RowMatrixXd q = q0;
    std::mt19937_64 r(11);
    const int evaluations = f.synth->anneal(Scoring{query, *f.collision, experts}, s, r, w, q);
    omp_set_num_threads(before);
    EXPECT_EQ(evaluations, 12 * 26);
    return std::make_tuple(w, q, r());  // the generator left where every thread count leaves it
  };
  const auto one = annealed(1, {kinematic});
  EXPECT_FALSE(std::get<0>(one).isApprox(w0, 1e-6)) << "the chains moved";
  for (const int threads : {2, 3}) {
    const auto many = annealed(threads, {kinematic});
    EXPECT_EQ(std::get<0>(many), std::get<0>(one)) << threads;
    EXPECT_EQ(std::get<1>(many), std::get<1>(one)) << threads;
    EXPECT_EQ(std::get<2>(many), std::get<2>(one)) << threads;
  }
  const auto counting = std::make_shared<CountingPenalty>(false);
  const auto serial = annealed(1, {counting, kinematic});  // first: it scores every grasp of a batch
  counting->largest_batch = 0;
  const auto kept = annealed(2, {counting, kinematic});
  EXPECT_EQ(std::get<0>(kept), std::get<0>(serial));
  EXPECT_EQ(counting->largest_batch, 12);
  // Joints of another row count than the wrists are refused before any block is cut from them.
  PoseArray w = w0;
  RowMatrixXd short_q = q0.topRows(11);
  std::mt19937_64 r(1);
  EXPECT_THROW(f.synth->anneal(Scoring{query, *f.collision, {kinematic}}, s, r, w, short_q), std::invalid_argument);
}

TEST(Synthesis, TheLinkFloorMixesEachContactTermWithAFlatDensity) {
  // Each link's contact term is log(Q_i(pose) + exp(floor)): against the query density's own log value (the same
  // densities: the floor is set after they are fitted), for grasps near the box and grasps moved far from it, where
  // the density is tiny and the term the floor's to the last bit. Unset, the term is log Q_i bit for bit.
  const Fixture f = make_fixture();
  std::mt19937_64 rng(11);
  auto [query, w, q] = sampled(f, 40, rng);
  PoseArray moved = w;
  moved.col(0).array() += 0.5;  // half a metre off: every link far from its density
  PoseArray both(2 * w.rows(), 7);
  both << w, moved;
  RowMatrixXd joints(2 * q.rows(), q.cols());
  joints << q, q;
  const std::vector<std::shared_ptr<const Expert>> none;
  std::vector<QueryDensity> unset = query;
  for (QueryDensity& d : unset) d.floor.reset();
  const Evaluation plain = f.synth->evaluate(Scoring{unset, *f.collision, none}, both, joints);
  constexpr double kFloor = -20.0;
  std::vector<QueryDensity> floored = query;
  for (QueryDensity& d : floored) d.floor = kFloor;
  const Evaluation e = f.synth->evaluate(Scoring{floored, *f.collision, none}, both, joints);
  const RowMatrixXd link_poses = f.hand->fk_batch(both, joints);
  int near = 0, far = 0;
  for (size_t l = 0; l < query.size(); ++l) {
    const Eigen::VectorXd log_q =
        query[l].density->log_density(link_poses.middleCols(7 * query[l].link, 7), RowMatrixXd(both.rows(), 0));
    for (Eigen::Index i = 0; i < both.rows(); ++i) {
      if (!std::isfinite(plain.log_contact(i, l))) continue;  // rejected by the kinematic limits: not scored
      EXPECT_EQ(plain.log_contact(i, l), log_q[i]);
      EXPECT_NEAR(e.log_contact(i, l), std::log(std::exp(log_q[i]) + std::exp(kFloor)), 1e-9);
      EXPECT_GE(e.log_contact(i, l), kFloor);
      EXPECT_GE(e.log_contact(i, l), log_q[i]);
      if (log_q[i] > 0.0) ++near;
      if (log_q[i] < kFloor - 40.0) {
        EXPECT_EQ(e.log_contact(i, l), kFloor);
        ++far;
      }
    }
  }
  EXPECT_GT(near, 10);
  EXPECT_GT(far, 10);
  // The default settings carry the floor into the densities; unset, none.
  std::mt19937_64 a(5), b(5);
  QuerySettings off;
  off.link_floor.reset();
  EXPECT_EQ(f.synth->query_densities(f.box.frames, f.box.features, QuerySettings{}, a).front().floor,
            QuerySettings{}.link_floor);
  EXPECT_FALSE(f.synth->query_densities(f.box.frames, f.box.features, off, b).front().floor.has_value());
  QuerySettings bad;
  bad.link_floor = std::numeric_limits<double>::infinity();
  EXPECT_THROW(f.synth->query_densities(f.box.frames, f.box.features, bad, a), std::invalid_argument);
}
