#include "graspmix/grasp/contact_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "core/uniform_grid.hpp"
#include "grasp/collision_geometry.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void check_settings(const ContactQualitySettings& s) {
  const std::string w = "ContactQualitySettings: ";
  if (!(s.friction > 0.0) || !std::isfinite(s.friction))
    throw std::invalid_argument(w + "friction must be finite and > 0");
  if (!(s.concentration >= 0.0) || !std::isfinite(s.concentration)) {
    throw std::invalid_argument(w + "concentration must be finite and >= 0");
  }
  if (!(s.air_penalty >= 0.0) || !std::isfinite(s.air_penalty)) {
    throw std::invalid_argument(w + "air_penalty must be finite and >= 0");
  }
  if (!(s.contact_tolerance >= 0.0) || !std::isfinite(s.contact_tolerance)) {
    throw std::invalid_argument(w + "contact_tolerance must be finite and >= 0");
  }
  if (s.closing_steps < 1) throw std::invalid_argument(w + "closing_steps must be >= 1");
}

/// The grid over the cloud's box: cells 1.5 times the side of one point's share of the box (a surface cloud
/// then has several per cell; finer grids were slower on the bench's 2k-point mug, the columns' overhead
/// outweighing the points they skip), at most 4 million cells.
detail::UniformGrid cloud_grid(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector3d& lo,
                               const Eigen::Vector3d& hi) {
  using Grid = detail::UniformGrid;
  if (P.rows() == 0) return Grid(P, Eigen::Vector3d::Zero(), 1.0, {1, 1, 1}, Grid::Layout::Dense);
  const Eigen::Vector3d ext = (hi - lo).cwiseMax(1e-6);
  const Eigen::Vector3d thick = ext.cwiseMax(0.05 * ext.maxCoeff());
  double h = std::max(std::cbrt(thick.prod() / static_cast<double>(P.rows())) * 1.5, 1e-4 * ext.maxCoeff());
  auto dims_for = [&](double hh) { return ((ext / hh).array().floor().cast<int>() + 1).matrix().eval(); };
  Eigen::Vector3i dims = dims_for(h);
  while (static_cast<double>(dims[0]) * dims[1] * dims[2] > 4e6) dims = dims_for(h *= 1.5);
  return Grid(P, lo, h, {dims[0], dims[1], dims[2]}, Grid::Layout::Dense);
}

}  // namespace

struct ContactQualityExpert::Index {
  Index(const Eigen::Ref<const Vec3Array>& points, const Eigen::Ref<const Vec3Array>& normals)
      : lo(points.rows() > 0 ? Eigen::Vector3d(points.colwise().minCoeff().transpose()) : Eigen::Vector3d::Zero()),
        hi(points.rows() > 0 ? Eigen::Vector3d(points.colwise().maxCoeff().transpose()) : Eigen::Vector3d::Zero()),
        grid(cloud_grid(points, lo, hi)),
        normals(static_cast<size_t>(points.rows())) {
    for (int i = 0; i < grid.size(); ++i) this->normals[static_cast<size_t>(i)] = normals.row(grid.row(i)).normalized();
  }
  Eigen::Vector3d lo, hi;  ///< the cloud's bounding box
  detail::UniformGrid grid;
  std::vector<Eigen::Vector3d> normals;  ///< unit, in the grid's canonical order
};

namespace {

/// One finger's first contact.
struct Contact {
  double t = kNaN;
  int patch = 0;  ///< points in the patch (0: no contact)
  Eigen::Vector3d point = Eigen::Vector3d::Constant(kNaN), normal = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector3d motion = Eigen::Vector3d::Zero();  ///< the contact point's displacement from t = 0 to t = 1
};

/// Per-thread storage reused across grasps.
struct Scratch {
  std::vector<Eigen::Isometry3d> poses0, poses1, poses;
  Eigen::VectorXd q;
  std::vector<int> cand;
  struct Entry {
    int i;
    double lo, hi;
  };
  std::vector<Entry> entries;
};

/// A box of a translating link: a point x of the link frame at t = 0 is at Rt x + b - t e in the box's frame.
struct Slab {
  Eigen::Matrix3d Rt;
  Eigen::Vector3d b, inv, half;  ///< inv = 1 / e per axis, 0 where the box does not move along it
};

/// The times in [0, 1] at which the point `a` (box frame, t = 0) lies within the box grown by g2: [lo2, hi2]
/// (false when none), and the first time it lies within the box grown by g1 <= g2 (in1; inf when never).
inline bool slab_times(const Slab& sl, const Eigen::Vector3d& a, double g1, double g2, double& lo2, double& hi2,
                       double& in1) {
  lo2 = 0.0;
  hi2 = 1.0;
  double lo1 = 0.0, hi1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (sl.inv[k] == 0.0) {
      const double d = std::abs(a[k]) - sl.half[k];
      if (d > g2) return false;
      if (d > g1) hi1 = -1.0;
      continue;
    }
    const double c = a[k] * sl.inv[k], w = std::abs(sl.half[k] * sl.inv[k]), g = std::abs(sl.inv[k]);
    lo2 = std::max(lo2, c - w - g2 * g);
    hi2 = std::min(hi2, c + w + g2 * g);
    lo1 = std::max(lo1, c - w - g1 * g);
    hi1 = std::min(hi1, c + w + g1 * g);
  }
  in1 = lo1 <= hi1 ? lo1 : kInf;
  return lo2 <= hi2;
}

/// The cells of the grid under the box [lo, hi]; false when it misses the cloud's box.
bool cells_under(const ContactQualityExpert::Index& ix, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                 detail::UniformGrid::Cell& c0, detail::UniformGrid::Cell& c1) {
  if (ix.grid.size() == 0 || (lo.array() > ix.hi.array()).any() || (hi.array() < ix.lo.array()).any()) return false;
  c0 = ix.grid.cell_of(lo);
  c1 = ix.grid.cell_of(hi);
  return true;
}

/// The contact point (the patch's mean) and normal axis (the principal axis of its normals, pointed against
/// the motion) of the patch of canonical positions `patch`.
void patch_contact(const ContactQualityExpert::Index& ix, const std::vector<int>& patch, Contact& c) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (const int i : patch) {
    sum += ix.grid.point(i);
    M.noalias() += ix.normals[static_cast<size_t>(i)] * ix.normals[static_cast<size_t>(i)].transpose();
  }
  c.patch = static_cast<int>(patch.size());
  c.point = sum / static_cast<double>(patch.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(M);
  c.normal = eig.eigenvectors().col(2).normalized();  // eigenvalues ascending
  if (c.normal.dot(c.motion) > 0.0) c.normal = -c.normal;
}

/// The first contact of a link moved by prismatic joints alone, whose shapes are boxes: it translates by
/// D = A1 - A0 over t in [0, 1], so each point's entry time into a grown box is one slab test. The sweep is
/// cut into chunks half as long as the link is thick along it, visited in order until one holds a contact;
/// only the grid's cells that can meet a chunk's swept box (in the link's frame) are visited.
Contact translating_contact(const ContactQualityExpert::Index& ix, const LinkInfo& link, const Eigen::Isometry3d& A0,
                            const Eigen::Isometry3d& A1, double tol, Scratch& s) {
  Contact c;
  c.motion = A1.translation() - A0.translation();
  const Eigen::Matrix3d Rt = A0.linear().transpose();
  const Eigen::Vector3d o = A0.translation(), e = Rt * c.motion;  // the displacement in the link frame
  // The boxes in their frames; lo, hi bound them grown by 2 tol in the link frame.
  Slab slabs[8];
  const int n_shapes = static_cast<int>(std::min<size_t>(link.collisions.size(), 8));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (int k = 0; k < n_shapes; ++k) {
    const CollisionShape& sh = link.collisions[static_cast<size_t>(k)];
    Slab& sl = slabs[k];
    sl.Rt = sh.T_link_shape.linear().transpose();
    sl.b = -sl.Rt * sh.T_link_shape.translation();
    const Eigen::Vector3d es = sl.Rt * e;
    for (int a = 0; a < 3; ++a) sl.inv[a] = std::abs(es[a]) > 1e-12 * e.norm() ? 1.0 / es[a] : 0.0;
    sl.half = 0.5 * sh.size;
    const Eigen::Vector3d ext = sh.T_link_shape.linear().cwiseAbs() * (sl.half.array() + 2.0 * tol).matrix();
    lo = lo.cwiseMin(sh.T_link_shape.translation() - ext);
    hi = hi.cwiseMax(sh.T_link_shape.translation() + ext);
  }
  const double thick = (hi - lo).dot(e.cwiseAbs()) / std::max(e.norm(), 1e-300);
  const int chunks = std::clamp(static_cast<int>(std::ceil(e.norm() / (0.5 * thick))), 1, 32);
  double first = kInf;
  for (int j = 0; j < chunks && !(first <= 1.0); ++j) {
    const double ta = static_cast<double>(j) / chunks, tb = static_cast<double>(j + 1) / chunks;
    const Eigen::Vector3d slo = (lo + ta * e).cwiseMin(lo + tb * e), shi = (hi + ta * e).cwiseMax(hi + tb * e);
    const Eigen::Vector3d mid = 0.5 * (slo + shi), half = 0.5 * (shi - slo), centre = A0 * mid;
    const Eigen::Vector3d ext = A0.linear().cwiseAbs() * half;
    detail::UniformGrid::Cell c0, c1;
    if (!cells_under(ix, centre - ext, centre + ext, c0, c1)) continue;
    const detail::BoxColumns columns(ix.lo, ix.grid.cell_size(), centre, A0.linear(), half, 0.0);
    s.entries.clear();
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x) {
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y) {
        std::int64_t z0, z1;
        if (!columns.column(x, y, c0[2], c1[2], z0, z1)) continue;
        const auto [b, end] = ix.grid.z_run(x, y, z0, z1);
        for (Eigen::Index i = b; i < end; ++i) {
          const Eigen::Vector3d a = Rt * (ix.grid.point(static_cast<int>(i)) - o);
          if (((a - mid).cwiseAbs() - half).maxCoeff() > 0.0) continue;
          for (int k = 0; k < n_shapes; ++k) {
            double lo2, hi2, in1;
            if (!slab_times(slabs[k], slabs[k].Rt * a + slabs[k].b, tol, 2.0 * tol, lo2, hi2, in1)) continue;
            first = std::min(first, in1);
            if (lo2 <= std::min(first, tb)) s.entries.push_back({static_cast<int>(i), lo2, hi2});
          }
        }
      }
    }
    if (first > tb) first = kInf;  // entries after this chunk are found again, in order, by a later one
  }
  if (!(first <= 1.0)) return c;
  c.t = first;
  s.cand.clear();
  for (const Scratch::Entry& en : s.entries) {
    if (en.lo <= first && first <= en.hi && (s.cand.empty() || s.cand.back() != en.i)) s.cand.push_back(en.i);
  }
  patch_contact(ix, s.cand, c);
  return c;
}

/// The smallest signed distance from the candidates to the link posed at A (its shapes' rule).
double min_distance(const ContactQualityExpert::Index& ix, const LinkInfo& link, const Eigen::Isometry3d& A,
                    const std::vector<int>& cand) {
  double best = kInf;
  for (const CollisionShape& sh : link.collisions) {
    const Eigen::Isometry3d inv = (A * sh.T_link_shape).inverse();
    for (const int i : cand) best = std::min(best, detail::signed_distance(sh, inv * ix.grid.point(i)));
  }
  return best;
}

/// The world box of a shape posed at T (its local box: boxes exactly, cylinders, spheres, mesh hulls bounded).
void shape_box(const CollisionShape& sh, const Eigen::Isometry3d& T, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  Eigen::Vector3d half = Eigen::Vector3d::Zero(), centre = Eigen::Vector3d::Zero();
  switch (sh.type) {
    case ShapeType::Box:
      half = 0.5 * sh.size;
      break;
    case ShapeType::Cylinder:
      half = Eigen::Vector3d(sh.size.x(), sh.size.x(), 0.5 * sh.size.y());
      break;
    case ShapeType::Sphere:
      half = Eigen::Vector3d::Constant(sh.size.x());
      break;
    case ShapeType::Mesh: {
      const Vec3Array& V = sh.hull->vertices;
      const Eigen::Vector3d vlo = V.colwise().minCoeff().transpose(), vhi = V.colwise().maxCoeff().transpose();
      centre = 0.5 * (vlo + vhi);
      half = 0.5 * (vhi - vlo);
      break;
    }
  }
  const Eigen::Vector3d c = T * centre, ext = T.linear().cwiseAbs() * half;
  lo = lo.cwiseMin(c - ext);
  hi = hi.cwiseMax(c + ext);
}

/// The first contact of any other link: closing_steps steps of the signed distance over the points under
/// the swept box, then bisection in the first step that comes within the tolerance.
Contact stepped_contact(const Hand& hand, const ContactQualityExpert::Index& ix, int l, const Eigen::Isometry3d& W,
                        const Eigen::VectorXd& p, const Eigen::VectorXd& cl, double tol, int steps, Scratch& s) {
  const LinkInfo& link = hand.links()[static_cast<size_t>(l)];
  auto pose_at = [&](double t) {
    s.q = p + t * (cl - p);
    hand.fk_into(W, s.q.data(), s.poses.data());
    return s.poses[static_cast<size_t>(l)];
  };
  std::vector<Eigen::Isometry3d> A(static_cast<size_t>(steps) + 1);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  double stride = 0.0;  // how far a point of the link's boxes moves in one step, at most
  for (int k = 0; k <= steps; ++k) {
    A[static_cast<size_t>(k)] = pose_at(static_cast<double>(k) / steps);
    for (const CollisionShape& sh : link.collisions) shape_box(sh, A[static_cast<size_t>(k)] * sh.T_link_shape, lo, hi);
    if (k > 0) {
      Eigen::Vector3d blo = Eigen::Vector3d::Constant(kInf), bhi = -blo;
      for (const CollisionShape& sh : link.collisions) shape_box(sh, sh.T_link_shape, blo, bhi);
      const Eigen::Isometry3d step = A[static_cast<size_t>(k) - 1].inverse() * A[static_cast<size_t>(k)];
      const double reach = std::max(blo.norm(), bhi.norm());
      stride =
          std::max(stride, step.translation().norm() + (step.linear() - Eigen::Matrix3d::Identity()).norm() * reach);
    }
  }
  Contact c;
  c.motion = A.back().translation() - A.front().translation();
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(2.0 * tol + stride);
  detail::UniformGrid::Cell c0, c1;
  if (!cells_under(ix, lo - grow, hi + grow, c0, c1)) return c;
  s.cand.clear();
  ix.grid.for_each_in_cells(c0, c1, [&](int i) { s.cand.push_back(i); });
  int k = 0;
  while (k <= steps && min_distance(ix, link, A[static_cast<size_t>(k)], s.cand) > tol) ++k;
  if (k > steps) return c;
  double a = k == 0 ? 0.0 : static_cast<double>(k - 1) / steps, b = static_cast<double>(k) / steps;
  for (int it = 0; k > 0 && it < 30 && b - a > 1e-9; ++it) {
    const double m = 0.5 * (a + b);
    (min_distance(ix, link, pose_at(m), s.cand) > tol ? a : b) = m;
  }
  c.t = b;
  const Eigen::Isometry3d At = pose_at(b);
  std::vector<int> patch;
  for (const CollisionShape& sh : link.collisions) {
    const Eigen::Isometry3d inv = (At * sh.T_link_shape).inverse();
    for (const int i : s.cand)
      if (detail::signed_distance(sh, inv * ix.grid.point(i)) <= 2.0 * tol) patch.push_back(i);
  }
  std::sort(patch.begin(), patch.end());
  patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
  // The contact point's own displacement over the closing (for the normal's orientation).
  const Eigen::Vector3d x = At.inverse() * ix.grid.point(patch.front());
  c.motion = A.back() * x - A.front() * x;
  patch_contact(ix, patch, c);
  return c;
}

/// The fully closed configuration: each joint at its limit in the direction sign(q - p).
Eigen::VectorXd closed_configuration(const Eigen::VectorXd& p, const Eigen::VectorXd& q, const RowMatrixXd& limits) {
  Eigen::VectorXd c = q;
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    if (q[j] == p[j]) continue;
    const double lim = limits(j, q[j] > p[j] ? 1 : 0);
    c[j] = std::isfinite(lim) ? lim : q[j] + (q[j] - p[j]);
  }
  return c;
}

/// log E of the contacts; the angles of the scored pair into `angles` (NaN elsewhere).
double score(const std::vector<Contact>& contacts, const ContactQualitySettings& s, double* angles) {
  const double cone = std::atan(s.friction);
  const int F = static_cast<int>(contacts.size());
  int air = 0;
  for (int f = 0; f < F; ++f) {
    angles[f] = kNaN;
    if (contacts[static_cast<size_t>(f)].patch == 0) ++air;
  }
  double best = kInf;
  int ba = -1, bb = -1;
  double best_th[2] = {kNaN, kNaN};
  for (int a = 0; a < F; ++a) {
    const Contact& ca = contacts[static_cast<size_t>(a)];
    if (ca.patch == 0) continue;
    for (int b = a + 1; b < F; ++b) {
      const Contact& cb = contacts[static_cast<size_t>(b)];
      if (cb.patch == 0) continue;
      Eigen::Vector3d d = cb.point - ca.point;
      // Contacts on one spot (a sheet thinner than the tolerance): the line of the grasp is the closing.
      if (d.norm() < 1e-9) d = ca.motion;
      if (!(d.norm() > 0.0)) d = ca.normal;
      d.normalize();
      const double ta = std::acos(std::min(1.0, std::abs(ca.normal.dot(d))));
      const double tb = std::acos(std::min(1.0, std::abs(cb.normal.dot(d))));
      const double cost = std::max(0.0, ta - cone) + std::max(0.0, tb - cone);
      if (cost < best) {
        best = cost;
        ba = a;
        bb = b;
        best_th[0] = ta;
        best_th[1] = tb;
      }
    }
  }
  double cost = s.air_penalty * air;
  if (ba >= 0) {
    angles[ba] = best_th[0];
    angles[bb] = best_th[1];
    cost += s.concentration * best;
  }
  return cost > 0.0 ? -cost : 0.0;  // never -0
}

}  // namespace

ContactQualityExpert::ContactQualityExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& points,
                                           const Eigen::Ref<const Vec3Array>& normals, ConfigModel config,
                                           ContactQualitySettings settings)
    : hand_(std::move(hand)), config_(std::move(config)), settings_(std::move(settings)) {
  if (!hand_) throw std::invalid_argument("ContactQualityExpert: no hand");
  check_settings(settings_);
  if (config_.dim() != hand_->n_dofs()) {
    throw std::invalid_argument("ContactQualityExpert: the configuration model has " + std::to_string(config_.dim()) +
                                " joints, the hand " + std::to_string(hand_->n_dofs()));
  }
  if (normals.rows() != points.rows()) {
    throw std::invalid_argument("ContactQualityExpert: normals must be (" + std::to_string(points.rows()) +
                                ", 3) like points, got (" + std::to_string(normals.rows()) + ", 3)");
  }
  require_finite(points, "ContactQualityExpert: points");
  require_finite(normals, "ContactQualityExpert: normals");
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    if (!(normals.row(i).norm() > 1e-12)) {
      throw std::invalid_argument("ContactQualityExpert: normals row " + std::to_string(i) + " is zero");
    }
  }
  // Finger links: collision geometry, and a movable joint between them and the wrist.
  for (int l = 0; l < hand_->n_links(); ++l) {
    const LinkInfo& link = hand_->links()[static_cast<size_t>(l)];
    if (link.collisions.empty()) continue;
    bool moves = false, prismatic_only = true;
    for (int j = link.parent_joint; j >= 0;) {
      const JointInfo& joint = hand_->joints()[static_cast<size_t>(j)];
      if (joint.dof >= 0) moves = true;
      if (joint.dof >= 0 && joint.type != JointType::Prismatic) prismatic_only = false;
      j = hand_->links()[static_cast<size_t>(joint.parent_link)].parent_joint;
    }
    if (!moves) continue;
    const bool boxes =
        link.collisions.size() <= 8 && std::all_of(link.collisions.begin(), link.collisions.end(),
                                                   [](const CollisionShape& s) { return s.type == ShapeType::Box; });
    for (const CollisionShape& s : link.collisions) {
      if (s.type == ShapeType::Mesh && !s.hull) {
        throw std::invalid_argument("ContactQualityExpert: link '" + link.name + "' has a mesh read without geometry");
      }
    }
    fingers_.push_back(l);
    translating_.push_back(prismatic_only && boxes);
  }
  if (fingers_.empty()) throw std::invalid_argument("ContactQualityExpert: the hand has no moving link with geometry");
  index_ = std::make_unique<const Index>(points, normals);
}

ContactQualityExpert::~ContactQualityExpert() = default;

Eigen::Index ContactQualityExpert::n_points() const { return index_->grid.size(); }

ContactQualityResult ContactQualityExpert::evaluate(const Eigen::Ref<const PoseArray>& wrists,
                                                    const Eigen::Ref<const RowMatrixXd>& joints) const {
  const Eigen::Index n = wrists.rows();
  const int D = hand_->n_dofs(), F = static_cast<int>(fingers_.size()), L = hand_->n_links();
  if (joints.rows() != n || joints.cols() != D) {
    throw std::invalid_argument(settings_.name + " expert: joints must be (" + std::to_string(n) + ", " +
                                std::to_string(D) + "), got (" + std::to_string(joints.rows()) + ", " +
                                std::to_string(joints.cols()) + ")");
  }
  require_finite(wrists, "wrists");
  require_finite(joints, "joints");
  const RowMatrixXd pre = config_.pregrasps_for(joints);
  const RowMatrixXd limits = hand_->joint_limits();
  ContactQualityResult r;
  r.links = fingers_;
  r.t = RowMatrixXd::Constant(n, F, kNaN);
  r.joints = RowMatrixXd::Constant(n, F * D, kNaN);
  r.points = RowMatrixXd::Constant(n, 3 * F, kNaN);
  r.normals = RowMatrixXd::Constant(n, 3 * F, kNaN);
  r.angles = RowMatrixXd::Constant(n, F, kNaN);
  r.patch_size = Eigen::MatrixXi::Zero(n, F);
  r.log_value = Eigen::VectorXd::Zero(n);
  const double tol = settings_.contact_tolerance;
  std::string error;
  // Small batches (annealing scores ~10 grasps at a time) stay on one thread, as the collision expert's.
#pragma omp parallel if (n >= 64)
  {
    Scratch s;
    s.poses0.resize(static_cast<size_t>(L));
    s.poses1.resize(static_cast<size_t>(L));
    s.poses.resize(static_cast<size_t>(L));
    std::vector<Contact> contacts(static_cast<size_t>(F));
    Eigen::VectorXd angles(F);
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Isometry3d W;
      try {
        W = pose_from_vector(wrists.row(i).transpose());
      } catch (const std::invalid_argument& e) {
#pragma omp critical
        error = "wrists row " + std::to_string(i) + ": " + e.what();
        continue;
      }
      const Eigen::VectorXd q = joints.row(i).transpose(), p = pre.row(i).transpose();
      const Eigen::VectorXd c = closed_configuration(p, q, limits);
      hand_->fk_into(W, p.data(), s.poses0.data());
      hand_->fk_into(W, c.data(), s.poses1.data());
      for (int f = 0; f < F; ++f) {
        const int l = fingers_[static_cast<size_t>(f)];
        contacts[static_cast<size_t>(f)] =
            translating_[static_cast<size_t>(f)]
                ? translating_contact(*index_, hand_->links()[static_cast<size_t>(l)], s.poses0[static_cast<size_t>(l)],
                                      s.poses1[static_cast<size_t>(l)], tol, s)
                : stepped_contact(*hand_, *index_, l, W, p, c, tol, settings_.closing_steps, s);
        const Contact& ct = contacts[static_cast<size_t>(f)];
        if (ct.patch == 0) continue;
        r.t(i, f) = ct.t;
        r.joints.block(i, f * D, 1, D) = (p + ct.t * (c - p)).transpose();
        r.points.block<1, 3>(i, 3 * f) = ct.point.transpose();
        r.normals.block<1, 3>(i, 3 * f) = ct.normal.transpose();
        r.patch_size(i, f) = ct.patch;
      }
      r.log_value[i] = score(contacts, settings_, angles.data());
      r.angles.row(i) = angles.transpose();
    }
  }
  if (!error.empty()) throw std::invalid_argument(error);
  return r;
}

Eigen::VectorXd ContactQualityExpert::log_value(const GraspBatch& batch) const {
  return evaluate(batch.wrists, batch.joints).log_value;
}

}  // namespace graspmix
