#pragma once
// Kopicki's frame jitter (docs/design.md, "Choices the paper leaves open"): where k1 ~ k2 the first
// principal direction is arbitrary, so the frame's heading about the normal carries no information.
// The surface features report the jitter's size per point (SurfaceCloud::frame_ambiguity) and the
// query densities rotate each sampled frame about its normal by a random angle of that size.

namespace graspmix {

/// The sharpness of Kopicki's code, used for SurfaceCloud::frame_ambiguity (QuerySettings::jitter_sharpness
/// defaults to the same value).
inline constexpr double kKopickiJitterSharpness = 100.0;

/// u * pi * exp(-sharpness * anisotropy^2), with anisotropy = (k1 - k2) / k1 in [0, 1]: u = 1 gives the
/// jitter's size, u uniform in [-1, 1] draws a jitter angle (rad).
double frame_jitter_angle(double anisotropy, double sharpness, double u = 1.0);

}  // namespace graspmix
