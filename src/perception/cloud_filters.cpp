#include "cloud_filters.hpp"

#include <pcl/filters/statistical_outlier_removal.h>

#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

namespace graspmix::detail {

namespace {

/// PCL's SAC classes seed their generators with 12345 (or the clock); these reseed them from the
/// caller's seed so that RANSAC is both deterministic and under the caller's control.
class SeededPlaneModel : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
 public:
  SeededPlaneModel(const Cloud::ConstPtr& cloud, unsigned seed) : pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud) {
    rng_alg_.seed(seed);
  }
};

class SeededRansac : public pcl::RandomSampleConsensus<pcl::PointXYZ> {
 public:
  SeededRansac(const pcl::SampleConsensusModel<pcl::PointXYZ>::Ptr& model, double threshold, unsigned seed)
      : pcl::RandomSampleConsensus<pcl::PointXYZ>(model, threshold) {
    rng_->base().seed(seed);
    threads_ = -1;  // PCL's parallel RANSAC races on the best model: results would depend on timing
  }
};

unsigned fold_seed(std::uint64_t s) { return static_cast<unsigned>((s ^ (s >> 32)) & 0xffffffffu); }

}  // namespace

bool fit_plane(const Cloud::ConstPtr& cloud, double distance, int iterations, std::uint64_t seed,
               Eigen::VectorXf& coeffs, pcl::Indices& inliers) {
  SeededPlaneModel::Ptr model(new SeededPlaneModel(cloud, fold_seed(seed)));
  SeededRansac ransac(model, distance, fold_seed(seed) ^ 0x9e3779b9u);
  ransac.setMaxIterations(iterations);
  if (!ransac.computeModel()) return false;
  ransac.getInliers(inliers);
  ransac.getModelCoefficients(coeffs);
  Eigen::VectorXf refined = coeffs;
  model->optimizeModelCoefficients(inliers, coeffs, refined);
  if (refined.allFinite() && refined.head<3>().norm() > 0) coeffs = refined;
  coeffs /= coeffs.head<3>().norm();
  model->selectWithinDistance(coeffs, distance, inliers);
  return true;
}

pcl::Indices statistical_inliers(const Cloud::ConstPtr& cloud, int k, double std_ratio) {
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setMeanK(k);
  sor.setStddevMulThresh(std_ratio);
  sor.setInputCloud(cloud);
  pcl::Indices kept;
  sor.filter(kept);
  return kept;
}

}  // namespace graspmix::detail
