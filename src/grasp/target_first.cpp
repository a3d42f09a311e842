#include "grasp/target_first.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "core/uniform_grid.hpp"
#include "graspmix/grasp/scene_synthesis.hpp"

namespace graspmix {
namespace detail {

struct RadiusGrid::Impl {
  std::optional<UniformGrid> grid;
  double radius = 0;
};

RadiusGrid::RadiusGrid(const Vec3Array& P, double radius) {
  if (!(std::isfinite(radius) && radius > 0))
    throw std::invalid_argument("RadiusGrid: the radius must be a finite distance > 0 (m)");
  auto impl = std::make_shared<Impl>();
  impl->radius = radius;
  // padded by a radius: no point of P lies in a clamped cell (covering refuses points not finite)
  if (P.rows() > 0) impl->grid.emplace(UniformGrid::covering(P, radius, radius));
  impl_ = std::move(impl);
}

Eigen::Index RadiusGrid::nearest(const Eigen::Vector3d& p) const {
  if (!impl_->grid) return -1;
  const UniformGrid& g = *impl_->grid;
  const auto c = g.cell_of(p);
  auto c0 = c, c1 = c;
  for (std::size_t k = 0; k < 3; ++k) {
    c0[k] = std::max<std::int64_t>(c[k] - 1, 0);
    c1[k] = std::min<std::int64_t>(c[k] + 1, g.dims()[k] - 1);
  }
  double best = impl_->radius * impl_->radius;
  Eigen::Index row = -1;
  g.for_each_in_cells(c0, c1, [&](int j) {
    const double d = (g.point(j) - p).squaredNorm();
    if (d < best) {
      best = d;
      row = g.row(j);
    }
  });
  return row;
}

Eigen::VectorXd target_first(const ContactQualityExpert& target, const ContactQualityExpert& others,
                             const std::vector<Grasp>& grasps) {
  const auto n = static_cast<Eigen::Index>(grasps.size());
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  if (n == 0) return out;
  PoseArray w(n, 7);
  RowMatrixXd q(n, grasps.front().joints.size());
  for (Eigen::Index i = 0; i < n; ++i) {
    w.row(i) = grasps[static_cast<std::size_t>(i)].T_world_wrist.transpose();
    q.row(i) = grasps[static_cast<std::size_t>(i)].joints.transpose();
  }
  const RowMatrixXd t_target = target.evaluate(w, q).t, t_other = others.evaluate(w, q).t;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index f = 0; f < t_other.cols(); ++f)
      if (std::isfinite(t_other(i, f)) && !(t_target(i, f) <= t_other(i, f)))
        out[i] = -std::numeric_limits<double>::infinity();
  return out;
}

Eigen::VectorXi dropped_owners(const Segmentation& scene) {
  Eigen::VectorXi owners = Eigen::VectorXi::Constant(scene.dropped.rows(), -1);
  if (scene.dropped.rows() == 0) return owners;
  const RadiusGrid kept(scene.points, kDroppedOwnerRadius);
  for (Eigen::Index i = 0; i < scene.dropped.rows(); ++i) {
    const Eigen::Index j = kept.nearest(scene.dropped.row(i).transpose());
    if (j >= 0) owners[i] = scene.labels[j];
  }
  return owners;
}

Vec3Array dropped_not_of(const Segmentation& scene, const Eigen::VectorXi& owners, int target) {
  if (owners.size() != scene.dropped.rows())
    throw std::invalid_argument("dropped_not_of: one owner per dropped point is needed");
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < owners.size(); ++i)
    if (owners[i] != target) rows.push_back(i);
  return scene.dropped(rows, Eigen::all);
}

}  // namespace detail

Eigen::VectorXi target_side(const SurfaceCloud& surface, Eigen::Index n_observed, const Vec3Array& others,
                            double radius) {
  if (!(std::isfinite(radius) && radius > 0))
    throw std::invalid_argument("target_side: the radius must be a finite distance > 0 (m)");
  if (surface.indices.size() != surface.points.rows())
    throw std::invalid_argument("target_side: the surface needs one index per point");
  const bool any_completed = (surface.indices.array() >= n_observed).any();
  const detail::RadiusGrid near(any_completed ? others : Vec3Array(0, 3), radius);
  std::vector<int> rows;
  rows.reserve(static_cast<std::size_t>(surface.points.rows()));
  for (Eigen::Index r = 0; r < surface.points.rows(); ++r)
    if (surface.indices[r] < n_observed || near.nearest(surface.points.row(r).transpose()) < 0)
      rows.push_back(static_cast<int>(r));
  return Eigen::Map<const Eigen::VectorXi>(rows.data(), static_cast<Eigen::Index>(rows.size()));
}

}  // namespace graspmix
