#pragma once
// The collision expert W(h) of eq:opt_criterion_std_col (after Kopicki et al. 2015): a soft penalty,
// exponential in how deep the hand's links go through the object's point cloud and below its support
// plane.
//
// Penetration depth (metres), per link l with collision shapes S_l posed by fk(h):
//   * cloud:  D_l = max over cloud points p and shapes s in S_l of max(0, r - sd_s(p)) (depths up to
//     contact_tolerance count as 0), where sd_s is
//     the signed distance from p to the surface of s (negative inside) and r = point_radius (each
//     point is a ball of radius r). It is the depth of the deepest point inside the link: independent
//     of the cloud's density, exact for boxes, cylinders and spheres. A mesh shape is taken as its
//     convex hull (as Bullet does for moving bodies): inside the hull sd is exact; just outside it,
//     the max over the hull's face planes is used, which is exact off faces and a lower bound of the
//     distance near edges and corners (matters only when r > 0).
//   * plane:  P_l = max over shapes s in S_l of the depth of the deepest point of s below the plane
//     raised by plane_margin, found by FCL (each shape against an fcl::Halfspace; meshes as fcl::Convex
//     of their hull).
//   total = sum_l (D_l + P_l + inside_weight * n_l),  log W(h) = -beta * total,  W(h) = exp(log W),
//   with n_l the number of cloud points penetrating link l (inside_weight is 0 by default),
//   A cloud samples the object's surface only: a link wholly inside the object, touching no point, has
//   D_l = 0. Grasp sampling starts links at the surface, so this rarely matters; a denser cloud or a
//   larger point_radius narrows the gap.
//   collision_free = no cloud point lies strictly inside any link (ball overlap when r > 0) and no
//   link reaches below the raised plane, i.e. total == 0 (the soft unseen charge U_l aside, below).
//
// The occupancy model (CollisionModel::Occupancy, built on an OccupancyMap of what the cameras saw): in
// place of D_l, the volume of link l inside blocked cells (occupied, and unknown when the map counts them
// as obstacles), in units of depth over reference_area:
//   O_l = V_l / reference_area,  V_l = sum over the interior samples x of l's shapes (a regular grid of
//   spacing min(map resolution, half the shape's thinnest side), each standing for its cell's volume)
//   of the sample's volume, counted when x's map cell is blocked and that cell's centre lies deeper than
//   contact_tolerance + resolution / 2 inside the shape.
// The erosion by half a cell plus the tolerance is the contact rule: the occupied cell of a surface point
// reaches up to one cell outside the true surface, and its centre half of that, so a finger touching the
// surface is not charged. O_l grows with how much of the link is inside (it does not saturate: a finger
// through the middle of an object costs its whole volume), 1 cm^3 inside costs 1 cm at the default area.
// The occupancy model adds the surface model's D_l when it is given the cloud too (the default from
// Python): a cell of 5 mm cannot tell a 3 mm penetration from a touch, the points can. The plane term
// P_l is the same in both models; total, log W and collision_free are formed alike.
//
// The cloud is indexed once, in the constructor, into a uniform grid whose cells are ordered so that
// a row of cells is one contiguous run of points; an evaluation visits only the cells under each
// shape's world bounding box, so a hand away from the object costs little more than its fk.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/occupancy.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

/// What W measures the hand against: the cloud's points (the paper's expert), or the occupancy of what the
/// cameras saw (the space behind every surface is not free).
enum class CollisionModel { Surface, Occupancy };
std::string to_string(CollisionModel model);  ///< "surface" | "occupancy"
/// The model of that name; std::invalid_argument naming the choices otherwise.
CollisionModel collision_model_from_string(const std::string& name);

struct CollisionSettings {
  /// Which model; Python's `collision="surface"|"occupancy"` default. An expert built from a cloud is a
  /// surface expert, one built from an OccupancyMap an occupancy expert.
  CollisionModel model = CollisionModel::Surface;
  /// 1/m: log W = -beta * total depth (0.5 mm of penetration costs one nat). 2000, the value grasp synthesis
  /// has always run with from Python (it was 1000 here): W must outweigh the contact terms of a grasp whose
  /// fingers sink a few millimetres into the object.
  double beta = 2000.0;
  double point_radius = 0.0;  ///< m: cloud points are balls of this radius (>= 0)
  double plane_margin = 0.0;  ///< m: the support plane is raised by this much (negative: tolerate contact)
  double cell_size = 0.0;     ///< m: grid cell of the cloud index; 0 picks one from the cloud's extent and size
  bool orient_plane = true;   ///< flip the plane's sign so the cloud's mean lies on its free (positive) side
  /// m: depths up to this count as touching, not penetrating: a sensed cloud is a noisy surface, and a
  /// point a hair inside a finger is a contact (whatever the rounding of the link's pose). 1 mm is what
  /// grasp synthesis has always used; pass ~1e-9 for exact depths.
  double contact_tolerance = 1e-3;
  /// m per point: each cloud point inside a link adds this much to the total depth. The deepest-point
  /// depth saturates at half a link's thickness (a finger right through a thin object costs no more
  /// than a shallow one); counting the points it swallows measures how much of the link is inside.
  /// 0 (the default) keeps W a function of depths alone.
  double inside_weight = 0.0;
  /// m^2: the occupancy model charges the volume inside blocked cells divided by this (1 cm^2, about a
  /// fingertip's face: a link pressed 1 mm into a surface over 1 cm^2 costs 1 mm, as a surface depth).
  double reference_area = 1e-4;
  /// Keep the hand out of the objects' solid volume too, not only away from their points: the columns of
  /// grasp/solid_volume.hpp over the expert's cloud (observed and completed points) standing on its plane, charged
  /// as the occupancy model charges blocked cells (a link's volume in them over reference_area, eroded by the
  /// contact tolerance and half a cell). A completed object is a surface: a finger wholly inside it touches none of
  /// its points. Needs a plane (without one, or with no point a cell above it, there is no volume: has_volume()).
  /// With a map of what the cameras saw (the occupancy model's, or `unseen`), the volume is only where that map calls
  /// the space unknown (behind what the cameras saw): a column fills an overhang down to the table (under a mug's
  /// handle, its hole) and a cavity's wall inwards, which cameras that saw through them or saw the surface contradict
  /// (the seen surface's band is charged by its points' depths).
  /// On by default with the unseen charge below (one view, clutter_dev, GMM, 300 attempts: docs/one-view.md).
  bool volume = true;
  double volume_resolution = 0.005;  ///< m: the volume's cell (SolidVolumeSettings::resolution), > 0
  /// The soft charge of unseen space: a link's volume in the unknown cells of a map of what the cameras saw (the
  /// occupancy model's map, or the surface model's `unseen` map) outside the solid volume, over reference_area, times
  /// this weight (>= 0; 0, the default: no charge). It enters W (total_depth) but not collision_free: the unseen is
  /// neither free nor solid, so it is preferred less, never refused. The occupancy model's map must not count unknown
  /// cells as obstacles itself (OccupancySettings::unknown_is_occupied false): where it does, they are blocked, and
  /// this charge is not made. 0.1 by default: on the development objects (one view, GMM, with the volume and the
  /// margin below) 0.05 / 0.1 / 0.2 / 0.5 lifted 87.0 / 88.3 (89.3 with the margin) / 88.3 / 86.0% (docs/one-view.md).
  double unseen_weight = 0.1;
  /// m: with the volume, unseen space within this of it (along every axis) is not charged: room for a finger at a
  /// completed side the completion placed a little short (>= 0; 0: only the volume itself is exempt).
  double unseen_margin = 0.01;
  /// The occupancy model charges a link's volume in the map's occupied cells (the seen surface's); false: the seen
  /// surface is charged by its points' depths D_l alone (the map then only gives the unseen space its charge).
  bool occupied_cells = true;
};

/// One configuration's penetration, per link in Hand::link_names() order.
struct CollisionResult {
  Eigen::VectorXd cloud_depth;    ///< D_l (m), or O_l with the occupancy model
  Eigen::VectorXd plane_depth;    ///< P_l (m)
  Eigen::VectorXi points_inside;  ///< cloud points that penetrate each link (occupancy: samples charged)
  Eigen::VectorXd unseen_depth;   ///< U_l (m): the soft charge of unseen space (CollisionSettings::unseen_weight)
  double total_depth = 0.0;       ///< sum_l D_l + P_l + inside_weight * n_l + U_l (m; see the header comment)
  double log_w = 0.0;             ///< -beta * total_depth
  double w = 1.0;                 ///< exp(log_w)
  bool collision_free = true;
};

/// Many configurations at once: (N, n_links) depths and (N) totals.
struct CollisionBatchResult {
  RowMatrixXd cloud_depth;
  RowMatrixXd plane_depth;
  RowMatrixXd unseen_depth;
  Eigen::VectorXd total_depth;
  Eigen::VectorXd log_w;
  Eigen::VectorXd w;
  Eigen::Matrix<bool, Eigen::Dynamic, 1> collision_free;
};

class CollisionExpert {
 public:
  /// The surface model (settings.model must be Surface).
  /// cloud: (N, 3) object points in the world frame (may be empty when only the plane matters).
  /// plane: [a, b, c, d] with a x + b y + c z + d = 0 (the support plane, e.g. from prepare_cloud); it
  /// is normalised, and (with orient_plane) its sign chosen so the cloud lies above it.
  /// Throws std::invalid_argument for non-finite points, a degenerate plane or bad settings.
  /// unseen: the map whose Unknown cells the soft unseen charge counts (settings.unseen_weight), e.g. one baked from
  /// the scene's visibility model (OccupancyMap's VisibilityModel constructor); null: no unseen charge.
  CollisionExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& cloud,
                  const std::optional<Eigen::Vector4d>& plane = std::nullopt, CollisionSettings settings = {},
                  std::shared_ptr<const OccupancyMap> unseen = nullptr);

  /// The occupancy model on a map of the scene (settings.model is set to Occupancy): O_l plus, when a cloud
  /// is given, the surface model's D_l on it (exact depths of shallow contacts, which the map's cells are
  /// too coarse to see). plane as above, oriented by the cloud's mean (or the map's objects' centre).
  CollisionExpert(std::shared_ptr<const Hand> hand, std::shared_ptr<const OccupancyMap> occupancy,
                  const Eigen::Ref<const Vec3Array>& cloud, const std::optional<Eigen::Vector4d>& plane = std::nullopt,
                  CollisionSettings settings = {});

  /// W(h) for the wrist pose and configuration (joint_names() order).
  CollisionResult evaluate(const Eigen::Isometry3d& T_world_wrist, const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// The same over N configurations: wrists (N, 7), q (N, n_dofs); either may be one row. Parallel (OpenMP).
  CollisionBatchResult evaluate_batch(const Eigen::Ref<const PoseArray>& T_world_wrist,
                                      const Eigen::Ref<const RowMatrixXd>& q) const;

  /// evaluate_batch's collision_free alone, faster: without the unseen charge (which never refuses a hand) and
  /// stopping at a hand's first penetration (a point deeper than the tolerance, a charged sample of a map's volume,
  /// the plane). The same answers, exactly. Parallel (OpenMP).
  Eigen::Matrix<bool, Eigen::Dynamic, 1> collision_free_batch(const Eigen::Ref<const PoseArray>& T_world_wrist,
                                                              const Eigen::Ref<const RowMatrixXd>& q) const;

  /// log W of the same wrists (N, 7) at two configurations q and q2 (N, n_dofs each; e.g. a grasp and its
  /// pre-grasp), equal to evaluate_batch's log_w of each: links posed identically by both (the palm) are
  /// evaluated once. Parallel (OpenMP).
  std::pair<Eigen::VectorXd, Eigen::VectorXd> log_w_pair(const Eigen::Ref<const PoseArray>& wrists,
                                                         const Eigen::Ref<const RowMatrixXd>& q,
                                                         const Eigen::Ref<const RowMatrixXd>& q2) const;
  /// The same pair as total depths (CollisionBatchResult::total_depth of each; 0 where collision-free).
  std::pair<Eigen::VectorXd, Eigen::VectorXd> total_depth_pair(const Eigen::Ref<const PoseArray>& wrists,
                                                               const Eigen::Ref<const RowMatrixXd>& q,
                                                               const Eigen::Ref<const RowMatrixXd>& q2) const;

  const Hand& hand() const { return *hand_; }
  const CollisionSettings& settings() const { return settings_; }
  bool has_plane() const { return plane_.has_value(); }
  /// The normalised, oriented plane [n, d] (n . x + d >= 0 is free space).
  Eigen::Vector4d plane() const { return plane_.value_or(Eigen::Vector4d::Zero()); }
  Eigen::Index n_points() const;
  /// The map of the occupancy model (null for the surface model).
  const std::shared_ptr<const OccupancyMap>& occupancy() const { return occupancy_; }
  /// The solid volume charged with settings.volume (null without it, or without a plane).
  const std::shared_ptr<const OccupancyMap>& volume() const { return volume_; }
  /// The map whose unknown cells the unseen charge counts: the occupancy model's, the surface model's `unseen`, or
  /// null.
  const std::shared_ptr<const OccupancyMap>& unseen() const { return unseen_; }
  bool has_volume() const { return volume_ != nullptr; }
  double cell_size() const;

  struct Index;   ///< the cloud's grid (defined in src/)
  struct Shapes;  ///< per-shape FCL geometry and bounds (defined in src/)

 private:
  /// Adds the terms of the links posed at link_poses (all, or those with skip[l] false) into the per-link
  /// outputs.
  void evaluate_into(const Eigen::Isometry3d* link_poses, double* cloud_depth, double* plane_depth, int* points_inside,
                     double* unseen_depth, const bool* skip = nullptr) const;

  /// Whether the links posed at link_poses penetrate anything evaluate_into charges as hard (not the unseen).
  bool penetrates(const Eigen::Isometry3d* link_poses) const;

  std::shared_ptr<const Hand> hand_;
  CollisionSettings settings_;
  std::optional<Eigen::Vector4d> plane_;
  std::shared_ptr<const Index> index_;
  std::shared_ptr<const Shapes> shapes_;
  std::shared_ptr<const OccupancyMap> occupancy_;
  std::shared_ptr<const OccupancyMap> volume_;
  std::shared_ptr<const OccupancyMap> unseen_;
  /// The volume of the cloud (with settings.volume and a plane) and the links' interior samples for the maps.
  void build_volume(const Eigen::Ref<const Vec3Array>& cloud);
};

/// Signed distance (m, negative inside) from every point (N, 3, world frame) to a link's collision
/// geometry posed at T_world_link: the minimum over the link's shapes, each as the collision expert
/// sees it (meshes as their convex hulls). +inf for a link without collision geometry. Contact models
/// use it to find the object points near each link of a demonstrated grasp.
Eigen::VectorXd link_signed_distances(const Hand& hand, int link, const Eigen::Isometry3d& T_world_link,
                                      const Eigen::Ref<const Vec3Array>& points);

}  // namespace graspmix
