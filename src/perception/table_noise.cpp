#include "table_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

namespace graspmix::detail {

namespace {

/// Of the points near a plane, at least this fraction lies behind it when they are a table's (a plane fitted
/// 1.6 spreads off the table's centre still has it; a cloud cropped above its plane has none).
constexpr double kMinBehind = 0.05;
/// The fewer of the two sides' counts between 1 and 3 spreads of the centre is at least this fraction of the
/// other for a table's noise (equal for Gaussian noise, up to sampling; the bases of objects standing on the
/// table add to the side above). Below it the noise is not measured, and nothing is dropped for it.
constexpr double kMinSymmetry = 0.7;

double median(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::vector<double> within(const Eigen::VectorXd& h, double centre, double half) {
  std::vector<double> out;
  for (Eigen::Index r = 0; r < h.size(); ++r)
    if (std::abs(h[r] - centre) <= half) out.push_back(h[r]);
  return out;
}

bool symmetric(const Eigen::VectorXd& h, const TableNoise& t) {
  double above = 0, below = 0;
  for (Eigen::Index r = 0; r < h.size(); ++r) {
    const double z = (h[r] - t.centre) / t.spread;
    above += (z > 1 && z <= 3) ? 1 : 0;
    below += (z < -1 && z >= -3) ? 1 : 0;
  }
  return std::min(above, below) >= kMinSymmetry * std::max(above, below);
}

}  // namespace

TableNoise table_noise(const Eigen::VectorXd& h, double band) {
  std::vector<double> near = within(h, 0.0, band), dev;
  const auto behind = std::count_if(near.begin(), near.end(), [](double v) { return v < 0.0; });
  TableNoise t;
  if (near.size() < 3 || static_cast<double>(behind) < kMinBehind * static_cast<double>(near.size())) return t;
  for (int it = 0; it < 30 && near.size() >= 3; ++it) {
    const double c = median(near);
    dev.resize(near.size());
    for (std::size_t i = 0; i < near.size(); ++i) dev[i] = std::abs(near[i] - c);
    const double spread = 1.4826 * median(dev);
    const bool settled =
        it > 0 && std::abs(c - t.centre) <= 1e-3 * spread && std::abs(spread - t.spread) <= 1e-3 * spread;
    t.centre = c;
    t.spread = spread;
    if (settled || !(spread > 0)) break;
    near = within(h, c, 3.0 * spread);
  }
  t.known = !(t.spread > 0) || symmetric(h, t);
  return t;
}

namespace {

constexpr std::int64_t kCellSpan = std::int64_t{1} << 31;

std::int64_t pack(std::int64_t i, std::int64_t j) { return (i + kCellSpan / 2) * kCellSpan + (j + kCellSpan / 2); }

}  // namespace

TableNoiseMap::TableNoiseMap(const Vec3Array& sample, const Eigen::VectorXd& h, const Eigen::Vector4d& plane,
                             double band)
    : band_(band) {
  const Eigen::Vector3d n = plane.head<3>().normalized();
  u_ = n.unitOrthogonal();
  v_ = n.cross(u_);
  for (Eigen::Index r = 0; r < sample.rows(); ++r)
    if (std::abs(h[r]) <= kReach) heights_[key(sample.row(r).transpose())].push_back(h[r]);
}

std::int64_t TableNoiseMap::key(const Eigen::Vector3d& p) const {
  // Cells beyond +-2^29 (27,000 km of 5 cm cells) share the last one: no point of a scene is there, and the
  // packed key must not overflow.
  const auto cell = [](double x) {
    const double c = std::floor(x / kCell), lim = static_cast<double>(kCellSpan / 4);
    return static_cast<std::int64_t>(std::clamp(c, -lim, lim));
  };
  return pack(cell(p.dot(u_)), cell(p.dot(v_)));
}

const TableNoise& TableNoiseMap::at(const Eigen::Vector3d& p) {
  const std::int64_t k = key(p);
  if (const auto it = noise_.find(k); it != noise_.end()) return it->second;
  const std::int64_t i = k / kCellSpan, j = k % kCellSpan;
  std::vector<double> pooled;
  for (std::int64_t di = -1; di <= 1; ++di) {
    for (std::int64_t dj = -1; dj <= 1; ++dj) {
      if (const auto it = heights_.find((i + di) * kCellSpan + (j + dj)); it != heights_.end())
        pooled.insert(pooled.end(), it->second.begin(), it->second.end());
    }
  }
  TableNoise t;
  if (pooled.size() >= kMinPoints)
    t = table_noise(Eigen::Map<const Eigen::VectorXd>(pooled.data(), static_cast<Eigen::Index>(pooled.size())), band_);
  return noise_.emplace(k, t).first->second;
}

Eigen::VectorXd heights(const Vec3Array& P, const Eigen::Vector4d& plane) {
  return (P * plane.head<3>()).array() + plane[3];
}

AboveTableNoise::AboveTableNoise(const Vec3Array& P, const Eigen::Vector4d& plane, double band, const Vec3Array* sample)
    : P_(P), sample_(sample ? *sample : P), plane_(plane), band_(band), h_(heights(P, plane)) {
  hs_ = sample ? heights(*sample, plane) : h_;
  noise_ = table_noise(hs_, band);
}

bool AboveTableNoise::any(const std::vector<int>& rows) {
  if (!noise_.known) return !rows.empty();
  return std::any_of(rows.begin(), rows.end(), [&](int r) {
    if (noise_.holds(h_[r])) return false;
    if (!local_) local_.emplace(sample_, hs_, plane_, band_);
    const TableNoise& here = local_->at(P_.row(r).transpose());
    return !(here.known && here.holds(h_[r]));
  });
}

}  // namespace graspmix::detail
