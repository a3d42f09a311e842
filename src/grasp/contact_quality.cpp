#include "graspmix/grasp/contact_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "grasp/contact_closing.hpp"
#include "grasp/shape_bounds.hpp"
#include "grasp/wrist_rows.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {

using closing::Contact;
using closing::kInf;
using closing::kNaN;

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
  if (!(s.patch_points >= 0.0) || !std::isfinite(s.patch_points)) {
    throw std::invalid_argument(w + "patch_points must be finite and >= 0");
  }
  if (!(s.patch_penalty >= 0.0) || !std::isfinite(s.patch_penalty)) {
    throw std::invalid_argument(w + "patch_penalty must be finite and >= 0");
  }
  if (!(s.contact_tolerance >= 0.0) || !std::isfinite(s.contact_tolerance)) {
    throw std::invalid_argument(w + "contact_tolerance must be finite and >= 0");
  }
  if (s.closing_steps < 1) throw std::invalid_argument(w + "closing_steps must be >= 1");
}

/// The fully closed configuration: each joint at its limit in its closing direction, sign(q - p), or where
/// q == p (a pre-grasp clamped at a limit) the demonstration's, sign(demo) with demo = h_g - h_e (a joint the
/// demonstration does not move stays). A joint without a finite limit there closes by max(|q - p|, |demo|)
/// past q.
Eigen::VectorXd closed_configuration(const Eigen::VectorXd& p, const Eigen::VectorXd& q, const Eigen::VectorXd& demo,
                                     const RowMatrixXd& limits) {
  Eigen::VectorXd c = q;
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    const double dir = q[j] != p[j] ? q[j] - p[j] : demo[j];
    if (dir == 0.0) continue;
    const double lim = limits(j, dir > 0 ? 1 : 0);
    c[j] = std::isfinite(lim) ? lim : q[j] + std::copysign(std::max(std::abs(q[j] - p[j]), std::abs(demo[j])), dir);
  }
  return c;
}

/// log E of the contacts; the angles of the scored pair into `angles` (NaN elsewhere).
double score(const std::vector<Contact>& contacts, const ContactQualitySettings& s,
             const std::vector<double>& reference, double* angles) {
  const double cone = std::atan(s.friction);
  const int F = static_cast<int>(contacts.size());
  int air = 0;
  double small = 0.0;  // the small patches' charge
  for (int f = 0; f < F; ++f) {
    angles[f] = kNaN;
    const int patch = contacts[static_cast<size_t>(f)].patch;
    if (patch == 0) {
      ++air;
    } else if (reference[static_cast<size_t>(f)] > 0.0) {
      small += s.patch_penalty * std::max(0.0, 1.0 - patch / reference[static_cast<size_t>(f)]);
    }
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
  double cost = s.air_penalty * air + small;
  if (ba >= 0) {
    angles[ba] = best_th[0];
    angles[bb] = best_th[1];
    cost += s.concentration * best;
  }
  return cost > 0.0 ? -cost : 0.0;  // never -0
}

/// The cloud's spacing: the median distance from a point to its nearest neighbour, over up to 65 points spread
/// through the grid's order (0: no point has a neighbour within a cell).
double cloud_spacing(const detail::UniformGrid& grid) {
  const int n = grid.size();
  std::vector<double> nearest;
  std::vector<int> nn;
  std::vector<double> d2;
  const double r2 = grid.cell_size() * grid.cell_size();
  for (int i = 0; i < n; i += std::max(1, n / 64)) {
    grid.neighbours(i, r2, nn, d2);
    double best = kInf;
    for (size_t k = 0; k < nn.size(); ++k)
      if (nn[k] != i && d2[k] > 0.0) best = std::min(best, d2[k]);
    if (std::isfinite(best)) nearest.push_back(std::sqrt(best));
  }
  if (nearest.empty()) return 0.0;
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<long>(nearest.size() / 2), nearest.end());
  return nearest[nearest.size() / 2];
}

/// m: the finest spacing a finger's flat wall is built at (ContactQualityExpert::patch_reference); a denser cloud's
/// count is this one's scaled by the squared ratio of the spacings (a patch's points are its area over the spacing
/// squared), so a dense cloud does not make the wall slow.
constexpr double kWallMinSpacing = 0.003;

/// A square of points `spacing` apart, `across` wide, centred on `centre` and facing `normal` (unit): the points and
/// their normals.
std::pair<Vec3Array, Vec3Array> square_wall(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, double across,
                                            double spacing) {
  const int side = static_cast<int>(std::floor(across / spacing)) + 1;
  const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
  const Eigen::Vector3d corner = centre - 0.5 * (side - 1) * spacing * (u + v);
  Vec3Array wall(static_cast<Eigen::Index>(side) * side, 3), normals(wall.rows(), 3);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      wall.row(static_cast<Eigen::Index>(i) * side + j) = (corner + spacing * (i * u + j * v)).transpose();
      normals.row(static_cast<Eigen::Index>(i) * side + j) = normal.transpose();
    }
  }
  return {std::move(wall), std::move(normals)};
}

}  // namespace

std::vector<double> ContactQualityExpert::flat_patches(double spacing) const {
  const int F = static_cast<int>(fingers_.size());
  std::vector<double> best(static_cast<size_t>(F), 0.0);
  if (!(spacing > 0.0)) return best;
  const Eigen::VectorXd q = config_.grasp(), p = config_.pregrasp_for(q);
  const Eigen::VectorXd c = closed_configuration(p, q, config_.grasp() - config_.pregrasp(), hand_->joint_limits());
  ContactQualitySettings wall_settings = settings_;
  wall_settings.patch_points = 0.0;  // (the wall's own expert needs no reference)
  // Each finger at the grasp and a hair further along the closing.
  const std::vector<LinkBounds> at = link_bounds(*hand_, fingers_, q);
  const std::vector<LinkBounds> on = link_bounds(*hand_, fingers_, q + 1e-3 * (c - p));
  Eigen::Vector3d centre_of_fingers = Eigen::Vector3d::Zero();
  for (const LinkBounds& b : at) centre_of_fingers += b.middle / F;
  for (int f = 0; f < F; ++f) {
    const std::vector<Eigen::Vector3d>& corners = at[static_cast<size_t>(f)].corners;
    const Eigen::Vector3d& middle = at[static_cast<size_t>(f)].middle;
    if (corners.empty()) continue;
    // The finger presses towards the other fingers (the demonstration's box faces stand across that line); one
    // finger alone, along its own motion.
    const Eigen::Vector3d motion = F > 1 ? Eigen::Vector3d(centre_of_fingers - middle)
                                         : Eigen::Vector3d(on[static_cast<size_t>(f)].middle - middle);
    if (!(motion.norm() > 1e-9)) continue;
    const Eigen::Vector3d n = motion.normalized();
    // The wall: a square facing that motion, touching the finger's foremost point at the grasp.
    double front = -kInf;
    for (const Eigen::Vector3d& x : corners) front = std::max(front, n.dot(x));
    const Eigen::Vector3d centre = middle + (front - n.dot(middle)) * n;
    // Wide enough for the finger's whole outline, two wall spacings to spare on each side.
    double reach = 0.0;
    for (const Eigen::Vector3d& x : corners) {
      const Eigen::Vector3d d = x - middle;
      reach = std::max(reach, (d - n.dot(d) * n).norm());
    }
    const double wall_spacing = std::max(spacing, kWallMinSpacing);
    const auto [wall, normals] = square_wall(centre, n, 2.0 * reach + 4.0 * wall_spacing, wall_spacing);
    const ContactQualityExpert on_wall(hand_, wall, normals, config_, wall_settings);
    PoseArray wrist(1, 7);
    wrist.row(0) = pose_to_vector(Eigen::Isometry3d::Identity()).transpose();
    const double scale = (wall_spacing / spacing) * (wall_spacing / spacing);
    best[static_cast<size_t>(f)] = scale * on_wall.evaluate(wrist, q.transpose()).patch_size(0, f);
  }
  return best;
}

ContactQualityExpert::ContactQualityExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& points,
                                           const Eigen::Ref<const Vec3Array>& normals, ConfigModel config,
                                           ContactQualitySettings settings)
    : hand_(std::move(hand)), config_(std::move(config)), settings_(std::move(settings)) {
  if (!hand_) throw std::invalid_argument("ContactQualityExpert: no hand");
  check_settings(settings_);
  require_config_of(config_, *hand_, "ContactQualityExpert");
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
  // Finger links: the hand's fingertips (Hand::fingertips: collision geometry, moved by a joint).
  for (const int l : hand_->fingertips()) {
    const LinkInfo& link = hand_->links()[static_cast<size_t>(l)];
    bool prismatic_only = true;
    for (int j = link.parent_joint; j >= 0;) {
      const JointInfo& joint = hand_->joints()[static_cast<size_t>(j)];
      if (joint.dof >= 0 && joint.type != JointType::Prismatic) prismatic_only = false;
      j = hand_->links()[static_cast<size_t>(joint.parent_link)].parent_joint;
    }
    // Boxes, and meshes whose proxy has a growth bound (hand.hpp), sweep by slab tests.
    const bool slabs =
        link.collisions.size() <= 8 &&
        std::all_of(link.collisions.begin(), link.collisions.end(), [](const CollisionShape& s) {
          return s.type == ShapeType::Box || (s.type == ShapeType::Mesh && s.hull && std::isfinite(s.box_growth));
        });
    for (const CollisionShape& s : link.collisions) {
      if (s.type == ShapeType::Mesh && !s.hull) {
        throw std::invalid_argument("ContactQualityExpert: link '" + link.name + "' has a mesh read without geometry");
      }
    }
    fingers_.push_back(l);
    translating_.push_back(prismatic_only && slabs);
  }
  if (fingers_.empty()) throw std::invalid_argument("ContactQualityExpert: the hand has no fingertip links");
  index_ = std::make_unique<const Index>(points, normals);
  patch_reference_.assign(fingers_.size(), settings_.patch_points);
  if (settings_.patch_points > 0.0) {
    const std::vector<double> flat = flat_patches(cloud_spacing(index_->grid));
    for (size_t f = 0; f < flat.size(); ++f)
      if (flat[f] > 0.0) patch_reference_[f] = std::min(settings_.patch_points, flat[f]);
  }
}

ContactQualityExpert::~ContactQualityExpert() = default;

Eigen::Index ContactQualityExpert::n_points() const { return index_->grid.size(); }

ContactQualityResult ContactQualityExpert::evaluate(const Eigen::Ref<const PoseArray>& wrists,
                                                    const Eigen::Ref<const RowMatrixXd>& joints) const {
  const Eigen::Index n = wrists.rows();
  const int D = hand_->n_dofs(), F = static_cast<int>(fingers_.size()), L = hand_->n_links();
  require_joints_shape(n, joints, D, settings_.name + " expert");
  require_finite(wrists, "wrists");
  require_finite(joints, "joints");
  const RowMatrixXd pre = config_.pregrasps_for(joints);
  const RowMatrixXd limits = hand_->joint_limits();
  const Eigen::VectorXd demo = config_.grasp() - config_.pregrasp();
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
    closing::Scratch s;
    s.poses0.resize(static_cast<size_t>(L));
    s.poses1.resize(static_cast<size_t>(L));
    s.poses.resize(static_cast<size_t>(L));
    std::vector<Contact> contacts(static_cast<size_t>(F));
    Eigen::VectorXd angles(F);
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Isometry3d W;
      if (!wrist_of_row(wrists, i, W, error)) continue;
      const Eigen::VectorXd q = joints.row(i).transpose(), p = pre.row(i).transpose();
      const Eigen::VectorXd c = closed_configuration(p, q, demo, limits);
      hand_->fk_into(W, p.data(), s.poses0.data());
      hand_->fk_into(W, c.data(), s.poses1.data());
      for (int f = 0; f < F; ++f) {
        const int l = fingers_[static_cast<size_t>(f)];
        contacts[static_cast<size_t>(f)] =
            translating_[static_cast<size_t>(f)]
                ? closing::translating_contact(*index_, hand_->links()[static_cast<size_t>(l)],
                                               s.poses0[static_cast<size_t>(l)], s.poses1[static_cast<size_t>(l)], tol,
                                               s)
                : closing::stepped_contact(*hand_, *index_, l, W, p, c, tol, settings_.closing_steps, s);
        const Contact& ct = contacts[static_cast<size_t>(f)];
        if (ct.patch == 0) continue;
        r.t(i, f) = ct.t;
        r.joints.block(i, f * D, 1, D) = (p + ct.t * (c - p)).transpose();
        r.points.block<1, 3>(i, 3 * f) = ct.point.transpose();
        r.normals.block<1, 3>(i, 3 * f) = ct.normal.transpose();
        r.patch_size(i, f) = ct.patch;
      }
      r.log_value[i] = score(contacts, settings_, patch_reference_, angles.data());
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
