#pragma once
// Contact models M_i (eq:relative_pose_u_mixture, eq:contact_model_mixture,
// eq:contact_model_mixture_feature): for each hand link, the density of the link's pose u relative to a
// surface frame v of the object, given that frame's features r, learnt from the object points near the
// link in ONE demonstrated grasp. The density is any PoseDensity: a PoseMixture (the paper's, K = 2) or
// a PoseKDE (Kopicki et al. 2015's baseline).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"
#include "graspmix/density/pose_density.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

struct ContactSettings {
  double max_distance = 0.01;  ///< m: object points farther than this from a link's geometry are not its contacts
  double lambda = 5000.0;      ///< 1/m^2: a contact at distance d weighs exp(-lambda d^2) (1 cm: e^-0.5)
  int min_points = 10;         ///< a link with fewer contact points gets no contact model
};

/// The demonstration data set D_O of one link: u_ij = v_j^-1 o s_i for every object point j near it.
struct ContactData {
  int link = -1;
  std::vector<int> indices;  ///< object points used (rows of frames / features)
  PoseArray u;               ///< (M, 7) link pose in each point's frame
  RowMatrixXd r;             ///< (M, n) the points' features
  Eigen::VectorXd weights;   ///< (M) exp(-lambda d^2)
  Eigen::VectorXd distance;  ///< (M) m, distance from the point to the link's geometry (0 inside)
};

/// Contact data of one link for the demonstrated grasp: the hand at T_world_wrist with joints q
/// (joint_names() order), the object surface as per-point frames v (N, 7) and features r (N, n).
ContactData contact_data(const Hand& hand, int link, const Eigen::Isometry3d& T_world_wrist,
                         const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const PoseArray>& frames,
                         const Eigen::Ref<const RowMatrixXd>& features, const ContactSettings& settings = {});

struct ContactModel {
  int link = -1;
  std::string link_name;
  std::shared_ptr<const PoseDensity> density;  ///< M_i(u | r) and M_i(r)
  int n_points = 0;                            ///< contact points it was learnt from
};

/// Fits a contact model for every link with at least settings.min_points contact points, each with a
/// fresh density from make_density. Throws std::invalid_argument if no link touches the object.
std::vector<ContactModel> learn_contact_models(const Hand& hand, const Eigen::Isometry3d& T_world_wrist,
                                               const Eigen::Ref<const Eigen::VectorXd>& q,
                                               const Eigen::Ref<const PoseArray>& frames,
                                               const Eigen::Ref<const RowMatrixXd>& features,
                                               const std::function<std::shared_ptr<PoseDensity>()>& make_density,
                                               const ContactSettings& settings = {});

}  // namespace graspmix
