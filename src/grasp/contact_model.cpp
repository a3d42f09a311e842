#include "graspmix/grasp/contact_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "graspmix/core/se3.hpp"
#include "graspmix/grasp/collision.hpp"

namespace graspmix {

ContactData contact_data(const Hand& hand, int link, const Eigen::Isometry3d& T_world_wrist,
                         const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const PoseArray>& frames,
                         const Eigen::Ref<const RowMatrixXd>& features, const ContactSettings& s) {
  if (frames.rows() != features.rows()) {
    throw std::invalid_argument("contact_data: " + std::to_string(frames.rows()) + " frames but " +
                                std::to_string(features.rows()) + " feature rows");
  }
  if (!(s.max_distance > 0.0) || !(s.lambda >= 0.0)) {
    throw std::invalid_argument("contact settings: max_distance must be > 0 and lambda >= 0");
  }
  if (link < 0 || link >= hand.n_links()) {
    throw std::invalid_argument("contact_data: link index " + std::to_string(link) + " outside [0, " +
                                std::to_string(hand.n_links()) + ") of hand '" + hand.name() + "'");
  }
  require_finite(frames, "contact_data: frames");
  require_finite(features, "contact_data: features");
  hand.check_configuration(q, "grasp joints");
  const std::vector<Eigen::Isometry3d> links = hand.fk(T_world_wrist, q);
  const Eigen::Isometry3d& T_world_link = links.at(link);
  const Eigen::VectorXd sd = link_signed_distances(hand, link, T_world_link, frames.leftCols<3>());
  ContactData out;
  out.link = link;
  for (Eigen::Index j = 0; j < frames.rows(); ++j)
    if (sd[j] <= s.max_distance) out.indices.push_back(static_cast<int>(j));
  const Eigen::Index m = static_cast<Eigen::Index>(out.indices.size());
  out.u.resize(m, 7);
  out.r.resize(m, features.cols());
  out.weights.resize(m);
  out.distance.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const int j = out.indices[k];
    const Eigen::Isometry3d T_world_feature = pose_from_vector(frames.row(j).transpose());
    out.u.row(k) = pose_to_vector(T_world_feature.inverse() * T_world_link).transpose();  // v^-1 o s
    out.r.row(k) = features.row(j);
    out.distance[k] = std::max(0.0, sd[j]);
    out.weights[k] = std::exp(-s.lambda * out.distance[k] * out.distance[k]);
  }
  return out;
}

std::vector<ContactModel> learn_contact_models(const Hand& hand, const Eigen::Isometry3d& T_world_wrist,
                                               const Eigen::Ref<const Eigen::VectorXd>& q,
                                               const Eigen::Ref<const PoseArray>& frames,
                                               const Eigen::Ref<const RowMatrixXd>& features,
                                               const std::function<std::shared_ptr<PoseDensity>()>& make_density,
                                               const ContactSettings& s) {
  std::vector<ContactModel> models;
  for (int link = 0; link < hand.n_links(); ++link) {
    if (hand.links()[link].collisions.empty()) continue;
    const ContactData d = contact_data(hand, link, T_world_wrist, q, frames, features, s);
    if (static_cast<int>(d.indices.size()) < s.min_points) continue;
    std::shared_ptr<PoseDensity> density = make_density();
    density->fit(d.u, d.r, d.weights);
    models.push_back({link, hand.link_names()[link], std::move(density), static_cast<int>(d.indices.size())});
  }
  if (models.empty()) {
    throw std::invalid_argument("learn_contact_models: no link of the hand has " + std::to_string(s.min_points) +
                                " object points within " + std::to_string(s.max_distance) +
                                " m in the demonstrated grasp (is the hand on the object?)");
  }
  return models;
}

}  // namespace graspmix
