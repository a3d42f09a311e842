// Kopicki's frame-jitter rule against its formula.
#include <cmath>

#include <gtest/gtest.h>

#include "graspmix/core/frame_jitter.hpp"

using namespace graspmix;

TEST(FrameJitter, MatchesTheFormula) {
  for (double a : {0.0, 0.01, 0.05, 0.1, 0.3, 1.0}) {
    for (double s : {0.0, 1.0, 100.0}) {
      EXPECT_DOUBLE_EQ(frame_jitter_angle(a, s), M_PI * std::exp(-s * a * a)) << a << " " << s;
      for (double u : {-1.0, -0.25, 0.5, 1.0})
        EXPECT_DOUBLE_EQ(frame_jitter_angle(a, s, u), u * M_PI * std::exp(-s * a * a));
    }
  }
}

TEST(FrameJitter, IsolatedPointsGetAFullTurnAndAnisotropicOnesNone) {
  EXPECT_DOUBLE_EQ(frame_jitter_angle(0.0, kKopickiJitterSharpness), M_PI);
  EXPECT_LT(frame_jitter_angle(1.0, kKopickiJitterSharpness), 1e-40);
  // Kopicki's sharpness halves the size at anisotropy sqrt(ln 2 / 100) ~ 0.083.
  EXPECT_NEAR(frame_jitter_angle(std::sqrt(std::log(2.0) / 100.0), kKopickiJitterSharpness), M_PI / 2, 1e-12);
}
