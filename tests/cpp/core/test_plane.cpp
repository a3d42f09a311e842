// orient_plane against hand-computed cases of each rule.
#include <gtest/gtest.h>

#include "graspmix/core/plane.hpp"

using namespace graspmix;

namespace {

Vec3Array heights(std::initializer_list<double> z) {
  Vec3Array P(static_cast<Eigen::Index>(z.size()), 3);
  Eigen::Index i = 0;
  for (const double v : z) {
    P.row(i) << 0.1 * static_cast<double>(i), -0.2, v;
    ++i;
  }
  return P;
}

const Eigen::Vector4d kUp(0, 0, 1, 0);  // z = 0, positive side z > 0

}  // namespace

TEST(OrientPlane, AllPointsAboveKeepsAndAllBelowFlipsForEveryRule) {
  for (PlaneSide rule : {PlaneSide::Majority, PlaneSide::Mean, PlaneSide::Median}) {
    EXPECT_EQ(orient_plane(kUp, heights({0.1, 0.2, 0.3}), rule), kUp);
    EXPECT_EQ(orient_plane(kUp, heights({-0.1, -0.2, -0.3}), rule), -kUp);
    EXPECT_EQ(orient_plane(-kUp, heights({0.1, 0.2, 0.3}), rule), kUp);
  }
}

TEST(OrientPlane, NoPointsKeepsThePlane) {
  const Eigen::Vector4d p(1, 2, 3, 4);
  EXPECT_EQ(orient_plane(p, Vec3Array(0, 3), PlaneSide::Majority), p);
  EXPECT_EQ(orient_plane(p, Vec3Array(0, 3), PlaneSide::Mean), p);
  EXPECT_EQ(orient_plane(p, Vec3Array(0, 3), PlaneSide::Median), p);
}

TEST(OrientPlane, TheRulesDifferWhereTheyShould) {
  // Three points just above, one far below: the majority and the median say above, the mean below.
  const Vec3Array P = heights({0.01, 0.01, 0.01, -1.0});
  EXPECT_EQ(orient_plane(kUp, P, PlaneSide::Majority), kUp);
  EXPECT_EQ(orient_plane(kUp, P, PlaneSide::Median), kUp);
  EXPECT_EQ(orient_plane(kUp, P, PlaneSide::Mean), -kUp);
  // Two far above, three just below: the mean says above, the majority and the median below.
  const Vec3Array Q = heights({1.0, 1.0, -0.01, -0.01, -0.01});
  EXPECT_EQ(orient_plane(kUp, Q, PlaneSide::Mean), kUp);
  EXPECT_EQ(orient_plane(kUp, Q, PlaneSide::Majority), -kUp);
  EXPECT_EQ(orient_plane(kUp, Q, PlaneSide::Median), -kUp);
}

TEST(OrientPlane, TiesKeepThePlane) {
  // Majority: points on the plane count as below, so one above and one on it tie.
  EXPECT_EQ(orient_plane(kUp, heights({0.5, 0.0}), PlaneSide::Majority), kUp);
  EXPECT_EQ(orient_plane(kUp, heights({0.0, 0.0, 0.5}), PlaneSide::Majority), -kUp);
  // Mean and median exactly zero.
  EXPECT_EQ(orient_plane(kUp, heights({0.25, -0.25}), PlaneSide::Mean), kUp);
  EXPECT_EQ(orient_plane(kUp, heights({0.25, -0.25}), PlaneSide::Median), kUp);
  EXPECT_EQ(orient_plane(kUp, heights({-1.0, 0.0, 2.0}), PlaneSide::Median), kUp);
}

TEST(OrientPlane, EvenMedianIsTheMeanOfTheTwoMiddleHeights) {
  // Middle heights -0.3 and 0.1: median -0.1 < 0.
  EXPECT_EQ(orient_plane(kUp, heights({5.0, 0.1, -0.3, -9.0}), PlaneSide::Median), -kUp);
  // Middle heights -0.1 and 0.3: median 0.1 > 0.
  EXPECT_EQ(orient_plane(kUp, heights({5.0, 0.3, -0.1, -9.0}), PlaneSide::Median), kUp);
}

TEST(OrientPlane, UsesTheFullPlaneEquationAndKeepsItsScale) {
  // 2x - 4 = 0 (x = 2): points at x = 3 are on the positive side; the plane is not normalised.
  const Eigen::Vector4d p(2, 0, 0, -4);
  Vec3Array P(2, 3);
  P << 3, 0, 0, 3, 1, 1;
  for (PlaneSide rule : {PlaneSide::Majority, PlaneSide::Mean, PlaneSide::Median}) {
    EXPECT_EQ(orient_plane(p, P, rule), p);
    EXPECT_EQ(orient_plane(-p, P, rule), p);
  }
}
