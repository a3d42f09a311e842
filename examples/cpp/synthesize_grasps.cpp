// Learns the GMM contact models of one demonstrated grasp and synthesises grasps on a new scene cloud with the
// library's defaults (graspmix::synthesize_scene: the whole path in one call), with graspmix's C++ API alone (no
// Python): what a robot stack linking the installed library does.
//
//   synthesize_grasps HAND.urdf DEMO_CLOUD.pcd "x,y,z,qx,qy,qz,qw" JOINT=PREGRASP:GRASP QUERY_CLOUD.pcd
//
// prints the best grasps (wrist pose, joints, log-likelihood) and exits 0; a bad input is one line on
// stderr and exit status 2.
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspmix/core/se3.hpp"
#include "graspmix/density/pose_mixture.hpp"
#include "graspmix/grasp/scene_synthesis.hpp"
#include "graspmix/perception/cleanup.hpp"
#include "graspmix/perception/cloud_io.hpp"
#include "graspmix/perception/surface.hpp"
#include "graspmix/robot/hand.hpp"

namespace {

std::vector<double> parse_numbers(const std::string& text, std::size_t n, const char* what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(std::stod(item));
  if (out.size() != n) throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(n) + " numbers");
  return out;
}

int run(int argc, char** argv) {
  if (argc != 6)
    throw std::invalid_argument("usage: synthesize_grasps HAND.urdf DEMO.pcd WRIST JOINT=PRE:GRASP QUERY.pcd");
  auto hand = std::make_shared<graspmix::Hand>(graspmix::Hand::from_urdf(argv[1]));
  const std::vector<double> w = parse_numbers(argv[3], 7, "wrist pose");
  const Eigen::Isometry3d T_world_wrist = graspmix::pose_from_vector(Eigen::Map<const Eigen::VectorXd>(w.data(), 7));
  const std::string joint_arg = argv[4];
  const auto eq = joint_arg.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("joints: expected NAME=PREGRASP:GRASP");
  std::string values = joint_arg.substr(eq + 1);
  for (char& c : values) c = c == ':' ? ',' : c;
  const std::vector<double> pg = parse_numbers(values, 2, "joints");
  const std::string joint = joint_arg.substr(0, eq);
  const Eigen::VectorXd pregrasp = hand->joints_from_map({{joint, pg[0]}});
  const Eigen::VectorXd grasp = hand->joints_from_map({{joint, pg[1]}});

  // The demonstration's object cloud: down-sampled like every query cloud (curvatures depend on density).
  graspmix::CleanupSettings demo_scene;
  demo_scene.remove_plane = false;
  const graspmix::SurfaceCloud demo = graspmix::compute_surface_features(
      graspmix::prepare_cloud(graspmix::load_cloud(argv[2]).points, demo_scene).points);
  std::vector<graspmix::ContactModel> models =
      graspmix::learn_contact_models(*hand, T_world_wrist, grasp, demo.frames, demo.curvatures, [] {
        graspmix::GmmSettings gmm;
        gmm.n_components = 2;  // the bundled model's K
        return std::make_shared<graspmix::PoseMixture>(gmm);
      });
  graspmix::ConfigModel config(pregrasp, grasp, hand->joint_limits());
  auto synthesizer = std::make_shared<const graspmix::GraspSynthesizer>(hand, std::move(models), config);

  // The query scene with the library's defaults, in one call: support plane and objects, each object's unseen side
  // completed, every expert (collision with the unseen space charged, kinematic, clear approach, contact quality),
  // sampling and annealing, grasps of all objects ranked together. The cloud file's VIEWPOINT is its camera.
  const graspmix::CloudData query = graspmix::load_cloud(argv[5]);
  graspmix::CloudInput input{query.points, query.viewpoints};
  if (input.viewpoints.rows() == 0 && query.has_viewpoint)
    input.viewpoints = query.viewpoint.head<3>().transpose().eval();
  graspmix::SceneSynthesisSettings settings;  // the library's defaults
  settings.synthesizer.seed = 1;
  const graspmix::SceneSynthesis result =
      graspmix::synthesize_scene(input, {{synthesizer, "demo", std::nullopt}}, settings);

  std::cout << "contact models: " << synthesizer->contact_models().size()
            << ", objects: " << result.scene.objects.size() << ", grasps: " << result.grasps.size()
            << ", evaluations: " << result.evaluations << ", " << result.timing.total * 1e3 << " ms\n";
  for (const std::string& note : result.completion.notes) std::cout << "note: " << note << "\n";
  for (std::size_t i = 0; i < result.grasps.size() && i < 3; ++i) {
    const graspmix::Grasp& g = result.grasps[i].grasp;
    std::cout << "grasp " << i + 1 << ": log L " << g.log_likelihood << ", object " << result.grasps[i].object
              << ", wrist " << g.T_world_wrist.transpose() << ", joints " << g.joints.transpose() << "\n";
  }
  return result.grasps.empty() ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "synthesize_grasps: " << e.what() << "\n";
    return 2;
  }
}
