#include "pile_split.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/lccp_segmentation.h>
#include <pcl/segmentation/supervoxel_clustering.h>

#include "cloud_filters.hpp"
#include "occlusion_merge.hpp"

// SupervoxelClustering<PointXYZ>'s voxel data: PCL's header declares how a voxel accumulates its points but leaves
// the definition to libpcl_segmentation, which graspmix does not link (PCL's templates are compiled here from its
// headers, cmake/graspmix_dependencies.cmake). A voxel of xyz points is their centroid: the sum as they come, divided
// by their count once all are in.
template <>
void pcl::octree::OctreePointCloudAdjacencyContainer<
    pcl::PointXYZ, pcl::SupervoxelClustering<pcl::PointXYZ>::VoxelData>::addPoint(const pcl::PointXYZ& p) {
  data_.xyz_ += p.getVector3fMap();
  num_points_ += 1;
}

template <>
void pcl::octree::OctreePointCloudAdjacencyContainer<
    pcl::PointXYZ, pcl::SupervoxelClustering<pcl::PointXYZ>::VoxelData>::computeData() {
  if (num_points_ > 0) data_.xyz_ /= static_cast<float>(num_points_);
}

namespace graspmix::detail {

namespace {

using PointCloud = pcl::PointCloud<pcl::PointXYZ>;

/// Per point of `cloud`, its piece (0..k-1) by supervoxels and LCCP; every point labelled.
std::vector<int> lccp_pieces(const PointCloud::Ptr& cloud, const SplitRule& rule) {
  const auto vr = static_cast<float>(rule.voxel_resolution), sr = static_cast<float>(rule.seed_resolution);
  pcl::SupervoxelClustering<pcl::PointXYZ> sv(vr, sr);
  sv.setUseSingleCameraTransform(false);  // the points are not a camera's organized image
  sv.setInputCloud(cloud);
  sv.setColorImportance(0.0f);
  sv.setSpatialImportance(1.0f);
  sv.setNormalImportance(4.0f);
  std::map<std::uint32_t, pcl::Supervoxel<pcl::PointXYZ>::Ptr> supervoxels;
  sv.extract(supervoxels);
  std::vector<int> piece(cloud->size(), 0);
  if (supervoxels.size() < 2) return piece;
  std::multimap<std::uint32_t, std::uint32_t> adjacency;
  sv.getSupervoxelAdjacency(adjacency);
  pcl::LCCPSegmentation<pcl::PointXYZ> lccp;
  lccp.setConcavityToleranceThreshold(static_cast<float>(rule.concavity_tolerance * 180.0 / M_PI));
  lccp.setSanityCheck(true);
  lccp.setSmoothnessCheck(true, vr, sr, 0.1f);
  lccp.setKFactor(0);
  lccp.setMinSegmentSize(0);
  lccp.setInputSupervoxels(supervoxels, adjacency);
  lccp.segment();
  pcl::PointCloud<pcl::PointXYZL>::Ptr labelled = sv.getLabeledCloud();
  lccp.relabelCloud(*labelled);
  // Labels to 0..k-1; unlabelled points (label 0: in no supervoxel) take their nearest labelled point's.
  std::map<std::uint32_t, int> index;
  PointCloud::Ptr known(new PointCloud);
  std::vector<int> known_piece;
  for (std::size_t i = 0; i < labelled->size(); ++i) {
    const std::uint32_t l = (*labelled)[i].label;
    if (l == 0) continue;
    const auto it = index.emplace(l, static_cast<int>(index.size())).first;
    piece[i] = it->second;
    known->push_back((*cloud)[i]);
    known_piece.push_back(it->second);
  }
  if (index.size() < 2) return std::vector<int>(cloud->size(), 0);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(known);
  pcl::Indices nn(1);
  std::vector<float> d2(1);
  for (std::size_t i = 0; i < labelled->size(); ++i)
    if ((*labelled)[i].label == 0 && tree.nearestKSearch((*cloud)[i], 1, nn, d2) == 1)
      piece[i] = known_piece[static_cast<std::size_t>(nn[0])];
  return piece;
}

/// Pieces under min_points join, smallest first, the piece most of their points' near neighbours (`near`: among the
/// cluster's points) lie on.
void absorb_small(const RadiusSearch& near, std::vector<int>& piece, int min_points) {
  for (;;) {
    std::map<int, int> size;
    for (const int p : piece) ++size[p];
    if (size.size() < 2) return;
    int smallest = -1;
    for (const auto& [p, n] : size)
      if (n < min_points && (smallest < 0 || n < size[smallest])) smallest = p;
    if (smallest < 0) return;
    std::map<int, int> touch;
    std::vector<int> nn;
    for (std::size_t i = 0; i < piece.size(); ++i) {
      if (piece[i] != smallest) continue;
      near.near(static_cast<int>(i), nn);
      for (const auto j : nn)
        if (piece[static_cast<std::size_t>(j)] != smallest) ++touch[piece[static_cast<std::size_t>(j)]];
    }
    int to = -1;
    for (const auto& [p, n] : touch)
      if (to < 0 || n > touch[to]) to = p;
    if (to < 0) {  // touches none: the largest piece takes it
      for (const auto& [p, n] : size)
        if (p != smallest && (to < 0 || n > size[to])) to = p;
    }
    for (int& p : piece)
      if (p == smallest) p = to;
  }
}

/// Pieces re-joined, the pair that touches most (points of one `near` the other: among the cluster's points, rows g
/// of P) first, while the joined piece's largest principal-box side stays within max_size: the fewest objects the
/// cluster can be.
void rejoin(const Vec3Array& P, const std::vector<int>& g, const RadiusSearch& near, std::vector<int>& piece,
            double max_size) {
  std::map<std::pair<int, int>, int> touch;
  std::vector<int> nn;
  for (std::size_t i = 0; i < piece.size(); ++i) {
    near.near(static_cast<int>(i), nn);
    for (const auto j : nn) {
      const int a = piece[i], b = piece[static_cast<std::size_t>(j)];
      if (a < b) ++touch[{a, b}];
      if (b < a) ++touch[{b, a}];
    }
  }
  std::map<int, std::vector<int>> rows;  // rows of P per piece
  for (std::size_t i = 0; i < piece.size(); ++i) rows[piece[i]].push_back(g[i]);
  for (;;) {
    std::vector<std::pair<int, std::pair<int, int>>> order;
    for (const auto& [ab, n] : touch) order.push_back({-n, ab});
    std::sort(order.begin(), order.end());
    bool joined = false;
    for (const auto& [n, ab] : order) {
      std::vector<int> both;
      std::merge(rows[ab.first].begin(), rows[ab.first].end(), rows[ab.second].begin(), rows[ab.second].end(),
                 std::back_inserter(both));
      if (largest_side(P, both) > max_size) continue;
      const auto [a, b] = ab;  // b joins a
      rows[a] = std::move(both);
      rows.erase(b);
      for (int& p : piece)
        if (p == b) p = a;
      std::map<std::pair<int, int>, int> next;
      for (const auto& [cd, m] : touch) {
        int c = cd.first == b ? a : cd.first, d = cd.second == b ? a : cd.second;
        if (c == d) continue;
        if (c > d) std::swap(c, d);
        next[{c, d}] += m;
      }
      touch.swap(next);
      joined = true;
      break;
    }
    if (!joined) return;
  }
}

}  // namespace

std::size_t split_touching(const Vec3Array& P, const Vec3Array& seen_from, std::vector<std::vector<int>>& groups,
                           const SplitRule& rule) {
  std::size_t added = 0;
  std::vector<std::vector<int>> out;
  for (auto& g : groups) {
    if (g.size() < 2 * static_cast<std::size_t>(std::max(rule.min_piece_points, 1)) ||
        largest_side(P, g) <= rule.max_size) {
      out.push_back(std::move(g));
      continue;
    }
    Eigen::RowVector3d eye = Eigen::RowVector3d::Zero();
    if (seen_from.rows() == P.rows()) {
      for (const int r : g) eye += seen_from.row(r);
      eye /= static_cast<double>(g.size());
    } else {
      eye = seen_from.row(0);
    }
    PointCloud::Ptr cloud(new PointCloud);
    for (const int r : g) {
      const Eigen::RowVector3d q = P.row(r) - eye;
      cloud->push_back({static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2])});
    }
    std::vector<int> piece = lccp_pieces(cloud, rule);
    // one search for both steps (two voxels' reach): the cluster's points do not move
    const RadiusSearch near(cloud, 2.0 * rule.voxel_resolution);
    absorb_small(near, piece, rule.min_piece_points);
    rejoin(P, g, near, piece, rule.max_size);
    std::map<int, std::vector<int>> parts;
    for (std::size_t i = 0; i < g.size(); ++i) parts[piece[i]].push_back(g[i]);
    if (parts.size() < 2) {
      out.push_back(std::move(g));
      continue;
    }
    added += parts.size() - 1;
    for (auto& [p, rows] : parts) out.push_back(std::move(rows));  // g sorted: each part's rows stay sorted
  }
  groups.swap(out);
  return added;
}

}  // namespace graspmix::detail
