// Object representation: cloud files, scene clean-up and surface features (O(v, r)).
#include <algorithm>
#include <limits>
#include <optional>

#include "common.hpp"
#include "graspmix/perception/cleanup.hpp"
#include "graspmix/perception/cloud_io.hpp"
#include "graspmix/perception/segmentation.hpp"
#include "graspmix/perception/surface.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

py::object optional_rows(const Vec3Array& a) { return a.rows() ? py::cast(a) : py::none(); }

}  // namespace

void bind_perception(py::module_& m) {
  // ---- clouds ----------------------------------------------------------------------------------
  py::class_<CloudData>(m, "CloudData", "A point cloud read from a file, with what the file said about it.")
      .def_readonly("points", &CloudData::points, "(N, 3) finite points (m); NaN points of the file are dropped.")
      .def_property_readonly(
          "normals", [](const CloudData& c) { return optional_rows(c.normals); },
          "(N, 3) normals from the file (normal_x/y/z or nx/ny/nz), or None.")
      .def_readonly("viewpoints", &CloudData::viewpoints,
                    "(N, 3) the camera position of each point (PCD/PLY fields vp_x vp_y vp_z, PCL's "
                    "PointWithViewpoint), following the points kept; (0, 3) when the file has none.")
      .def_readonly("viewpoint", &CloudData::viewpoint,
                    "Sensor pose [x, y, z, qx, qy, qz, qw] from the PCD VIEWPOINT (identity when absent).")
      .def_readonly("has_viewpoint", &CloudData::has_viewpoint, "True when the file's viewpoint is not the identity.")
      .def_readonly("fields", &CloudData::fields, "Every field of the file (x, y, z, rgb, ...).")
      .def_readonly("width", &CloudData::width)
      .def_readonly("height", &CloudData::height, "> 1 for organised clouds")
      .def_readonly("pixels", &CloudData::pixels,
                    "(N,) int64: for an organised file (height > 1) the pixel v * width + u of each point in its\n"
                    "width x height grid (row v, column u); empty for an unorganised one.")
      .def(
          "organized",
          [](const CloudData& c, const py::object& camera_pose) {
            py::array_t<double> out(
                {static_cast<py::ssize_t>(c.height), static_cast<py::ssize_t>(c.width), static_cast<py::ssize_t>(3)});
            std::optional<Eigen::Isometry3d> T;
            if (!camera_pose.is_none()) T = to_camera_pose(camera_pose, "camera_pose");
            organized_grid_into(c, out.mutable_data(), T);
            return out;
          },
          py::arg("camera_pose") = py::none(),
          "The points on their image grid: (height, width, 3) float64, NaN where the file had no finite point;\n"
          "with camera_pose [x, y, z, qx, qy, qz, qw] (a camera's pose in the file's frame, e.g. its VIEWPOINT),\n"
          "each point in that camera's frame. ValueError, naming the file, for an unorganised cloud (height 1),\n"
          "and for a camera_pose that is not a finite pose with a unit quaternion.")
      .def_readonly("n_invalid", &CloudData::n_invalid, "Points dropped for a NaN or infinite coordinate.")
      .def_readonly("format", &CloudData::format)
      .def_readonly("path", &CloudData::path)
      .def("__len__", [](const CloudData& c) { return c.points.rows(); })
      .def("__repr__", [](const CloudData& c) {
        return "<CloudData " + std::to_string(c.points.rows()) + " points from '" + c.path + "' (" + c.format + ")" +
               (c.normals.rows() ? ", normals" : "") +
               (c.n_invalid ? ", " + std::to_string(c.n_invalid) + " invalid dropped" : "") + ">";
      });

  m.def(
      "load_cloud",
      [](const py::object& path) {
        const std::string p = to_path(path, "path");
        py::gil_scoped_release release;
        return load_cloud(p);
      },
      py::arg("path"),
      "Reads a .pcd (ascii, binary, binary_compressed), .ply or .npy (N, 3) cloud. NaN points are dropped "
      "(counted in n_invalid; an organised file keeps each point's pixel in `pixels`, organized() gives the grid); "
      "extra fields are listed in `fields`. ValueError names the file and the problem.");
  m.def(
      "save_cloud",
      [](const py::object& path, const py::object& points, const py::object& normals, const std::string& encoding,
         const py::object& viewpoint, const py::object& viewpoints, const py::object& width, const py::object& height) {
        const std::string p = to_path(path, "path");
        const Vec3Array P(to_matrix(points, "save_cloud: points", 3));
        const Vec3Array N =
            normals.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(normals, "save_cloud: normals", 3));
        Eigen::Matrix<double, 7, 1> vp;
        vp << 0, 0, 0, 0, 0, 0, 1;
        if (!viewpoint.is_none()) vp = to_vector(viewpoint, "save_cloud: viewpoint", 7);
        const Vec3Array V =
            viewpoints.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(viewpoints, "save_cloud: viewpoints", 3));
        const int w = to_count(width, "save_cloud: width", 0, std::numeric_limits<int>::max());
        const int h = to_count(height, "save_cloud: height", 0, std::numeric_limits<int>::max());
        py::gil_scoped_release release;
        save_cloud(p, P, N, encoding, vp, V, static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h));
      },
      py::arg("path"), py::arg("points"), py::arg("normals") = py::none(), py::arg("encoding") = "binary",
      py::arg("viewpoint") = py::none(), py::arg("viewpoints") = py::none(), py::arg("width") = 0,
      py::arg("height") = 0,
      "Writes float32 x y z (+ normal_x normal_y normal_z, + vp_x vp_y vp_z) to .pcd (encoding ascii | binary | "
      "binary_compressed) or .ply (ascii | binary); viewpoint [x, y, z, qx, qy, qz, qw] goes into the header, "
      "viewpoints (N, 3), one camera position per point, into the fields vp_x vp_y vp_z (PCL's PointWithViewpoint). "
      "width x height: 0 x 0 writes the finite points unorganised; height > 1 an organised .pcd of width * height "
      "rows (row v * width + u is pixel (u, v); a row with NaN is a hole). PLY keeps no image grid: an organised "
      "cloud is a ValueError there.");

  // ---- scene clean-up ----------------------------------------------------------------------------
  SettingsClass<CleanupSettings>(m, "CleanupSettings", "Scene clean-up before features (prepare_cloud).")
      .field("crop", &CleanupSettings::crop, "keep only points inside [crop_min, crop_max]")
      .property(
          "crop_min", [](const CleanupSettings& s) { return Eigen::Vector3d(s.crop_min); },
          [](CleanupSettings& s, const py::object& v) { s.crop_min = to_vector(v, "crop_min", 3); },
          "m (3,), the cloud's frame")
      .property(
          "crop_max", [](const CleanupSettings& s) { return Eigen::Vector3d(s.crop_max); },
          [](CleanupSettings& s, const py::object& v) { s.crop_max = to_vector(v, "crop_max", 3); },
          "m (3,), the cloud's frame")
      .field("voxel_size", &CleanupSettings::voxel_size,
             "m: voxel-grid leaf size, 0 = off (demonstration and query clouds must share it)")
      .field("remove_outliers", &CleanupSettings::remove_outliers, "PCL StatisticalOutlierRemoval")
      .field("outlier_neighbours", &CleanupSettings::outlier_neighbours, "k of the mean-distance statistic")
      .field("outlier_std_ratio", &CleanupSettings::outlier_std_ratio,
             "drop points whose mean k-distance exceeds mean + ratio * std")
      .field("remove_plane", &CleanupSettings::remove_plane, "find the dominant plane by RANSAC and remove it")
      .field("plane_distance", &CleanupSettings::plane_distance, "m: RANSAC inlier threshold")
      .field("plane_max_iterations", &CleanupSettings::plane_max_iterations, "RANSAC iterations")
      .field("plane_min_fraction", &CleanupSettings::plane_min_fraction,
             "fraction of the cleaned points a plane needs to count as the support")
      .field("remove_below_plane", &CleanupSettings::remove_below_plane,
             "also drop points on the far side of the plane from the object")
      .seed("seed", &CleanupSettings::seed, "seeds RANSAC (None: 0)")
      .done();

  py::class_<CleanupResult>(m, "CleanupResult", "The object points of a scene and the support plane.")
      .def_readonly("points", &CleanupResult::points, "(N, 3) object points (m)")
      .def_readonly("indices", &CleanupResult::indices, "(N) input row of every point (-1 after voxel averaging)")
      .def_readonly("sources", &CleanupResult::sources,
                    "(N) input row whose per-point data (viewpoint, camera) every point carries: its own, or for a\n"
                    "voxel centroid the input point nearest to it in its voxel; index per-point arrays with it")
      .def_property_readonly(
          "plane", [](const CleanupResult& r) { return r.plane_found ? py::cast(r.plane) : py::none(); },
          "[a, b, c, d] of a x + b y + c z + d = 0, (a, b, c) unit towards the object; None if none found")
      .def_readonly("plane_found", &CleanupResult::plane_found)
      .def_readonly("n_input", &CleanupResult::n_input)
      .def_readonly("n_after_crop", &CleanupResult::n_after_crop)
      .def_readonly("n_after_voxel", &CleanupResult::n_after_voxel)
      .def_readonly("n_after_outliers", &CleanupResult::n_after_outliers)
      .def_readonly("n_plane_inliers", &CleanupResult::n_plane_inliers)
      .def_readonly("n_output", &CleanupResult::n_output)
      .def_readonly("seconds", &CleanupResult::seconds)
      .def("__repr__", [](const CleanupResult& r) {
        return "<CleanupResult " + std::to_string(r.n_input) + " -> " + std::to_string(r.n_output) + " points, plane " +
               (r.plane_found ? "found" : "not found") + ">";
      });
  m.def(
      "prepare_cloud",
      [](const py::object& points, const py::object& settings, py::kwargs kw) {
        const Vec3Array P(to_matrix(points, "prepare_cloud: points", 3));
        // crop_min / crop_max as keywords switch the crop on (None: that side unbounded, as before).
        const bool crop_given = (kw.contains("crop_min") && !kw["crop_min"].is_none()) ||
                                (kw.contains("crop_max") && !kw["crop_max"].is_none());
        for (const char* k : {"crop_min", "crop_max"})
          if (kw.contains(k) && kw[k].is_none()) PyDict_DelItemString(kw.ptr(), k);
        CleanupSettings s = settings_from<CleanupSettings>(settings, kw, "prepare_cloud");
        if (crop_given && !kw.contains("crop")) s.crop = true;
        py::gil_scoped_release release;
        return prepare_cloud(P, s);
      },
      py::arg("points"), py::kw_only(), py::arg("settings") = py::none(),
      ("Scene clean-up before features, in this order: crop box [crop_min, crop_max] (on when either is given "
       "as a keyword), voxel grid, statistical outlier removal, and removal of the dominant plane by seeded "
       "RANSAC (it must hold plane_min_fraction of the points) together with the points below it.\n" +
       settings_doc<CleanupSettings>())
          .c_str());

  // ---- scene segmentation ------------------------------------------------------------------------
  SettingsClass<SegmentationSettings>(
      m, "SegmentationSettings", "The scene model (segment_scene): support plane rule, table cut, outliers, clusters.")
      .field("voxel_size", &SegmentationSettings::voxel_size, "m: voxel-grid leaf size, 0 = off (CleanupSettings')")
      .field("plane_distance", &SegmentationSettings::plane_distance, "m: RANSAC inlier threshold")
      .field("plane_max_iterations", &SegmentationSettings::plane_max_iterations, "RANSAC iterations per candidate")
      .seed("seed", &SegmentationSettings::seed, "seeds RANSAC (None: 0)")
      .field("find_plane", &SegmentationSettings::find_plane, "search for the support plane (false: objects only)")
      .field("plane_candidates", &SegmentationSettings::plane_candidates,
             "planes tried, each on the points the previous ones left")
      .field("plane_min_fraction", &SegmentationSettings::plane_min_fraction,
             "rule 1: fraction of the voxelised points a candidate holds")
      .field("plane_behind_distance", &SegmentationSettings::plane_behind_distance,
             "m, rule 3: how far behind the plane a point counts as behind it")
      .field("plane_max_behind_fraction", &SegmentationSettings::plane_max_behind_fraction,
             "rule 3: fraction of all points allowed behind the plane")
      .field("plane_margin", &SegmentationSettings::plane_margin,
             "m, rule 4: how far the plane's inliers must reach beyond the objects' footprint")
      .field("table_clearance", &SegmentationSettings::table_clearance,
             "m: points at most this far above the support plane (or behind it) are the table")
      .field("remove_outliers", &SegmentationSettings::remove_outliers,
             "statistical outlier removal on the object points")
      .field("outlier_neighbours", &SegmentationSettings::outlier_neighbours, "k of the mean-distance statistic")
      .field("outlier_std_ratio", &SegmentationSettings::outlier_std_ratio,
             "drop points whose mean k-distance exceeds mean + ratio * std")
      .field("cluster_tolerance", &SegmentationSettings::cluster_tolerance,
             "m: object points closer than this are one object (Euclidean clusters)")
      .field("min_cluster_size", &SegmentationSettings::min_cluster_size, "smaller clusters are noise, dropped")
      .field("max_cluster_size", &SegmentationSettings::max_cluster_size, "larger clusters are dropped; 0 = no limit")
      .field("merge_seen_through", &SegmentationSettings::merge_seen_through,
             "a cluster seen through a larger one joins it (a container's inside seen over its rim)")
      .field("merge_through_fraction", &SegmentationSettings::merge_through_fraction,
             "fraction of a cluster's lines of sight that must cross the larger one's envelope")
      .field("merge_inset", &SegmentationSettings::merge_inset, "m: the larger cluster's envelope is inset by this")
      .field("join_occluded", &SegmentationSettings::join_occluded,
             "clusters whose gap the view leaves unseen (a shadow between them) join: pieces of one object")
      .field("join_max_gap", &SegmentationSettings::join_max_gap, "m, join rule 1: clusters farther apart never join")
      .field("join_seen_margin", &SegmentationSettings::join_seen_margin,
             "m, join rule 2: the gap was seen empty when the views saw more than this beyond it (median)")
      .field("join_max_size", &SegmentationSettings::join_max_size,
             "m, join rule 3: the joined cluster's largest principal-box side")
      .field("split_touching", &SegmentationSettings::split_touching,
             "a cluster is cut along its concave creases into the objects touching in it (the split rule)")
      .field("split_voxel_resolution", &SegmentationSettings::split_voxel_resolution,
             "m: the split rule's supervoxel voxel (at least voxel_size)")
      .field("split_seed_resolution", &SegmentationSettings::split_seed_resolution,
             "m: the split rule's supervoxel seed spacing")
      .field("split_concavity_tolerance", &SegmentationSettings::split_concavity_tolerance,
             "rad: a crease less concave than this is no cut (LCCP)")
      .field("split_min_points", &SegmentationSettings::split_min_points,
             "a split piece with fewer points goes back to the neighbour it touches most")
      .field("split_max_size", &SegmentationSettings::split_max_size,
             "m: one object's largest principal-box side; only larger clusters are cut, and pieces re-join within it")
      .field("split_named_max_size", &SegmentationSettings::split_named_max_size,
             "m: with a point target, its segment is tried again by the split rule gated at this size "
             "(split_object_near)")
      .field("visibility_tolerance", &SegmentationSettings::visibility_tolerance,
             "m: Segmentation.visibility's surface_tolerance (within this of the observed surface is Surface)")
      .field("visibility_resolution", &SegmentationSettings::visibility_resolution,
             "rad: the bin of Segmentation.visibility's range images (VisibilitySettings.angular_resolution)")
      .field("visibility_median_window", &SegmentationSettings::visibility_median_window,
             "px: segment_depth's visibility model keeps the depth image median-filtered over (2 r + 1)^2 pixels\n"
             "(0: as it is), against lone outline pixels that see through an object")
      .field("image_stride", &SegmentationSettings::image_stride,
             "px: segment_depth's block side, 0 = the largest within half a voxel_size at the median depth")
      .field("plane_image_stride", &SegmentationSettings::plane_image_stride,
             "px: segment_depth's block side for the support plane's search (at most image_stride: those)")
      .property(
          "workspace", [](const SegmentationSettings& s) { return py::cast(s.workspace); },
          [](SegmentationSettings& s, const py::object& v) {
            const Eigen::VectorXd w = v.is_none() ? Eigen::VectorXd() : to_vector(v, "workspace");
            if (w.size() != 0 && w.size() != 6) {
              throw py::value_error("workspace: expected [] or [x_min, y_min, z_min, x_max, y_max, z_max], got " +
                                    std::to_string(w.size()) + " numbers");
            }
            s.workspace.assign(w.data(), w.data() + w.size());
          },
          "m: the world-frame box [x_min, y_min, z_min, x_max, y_max, z_max] the input is cropped to first; [] = none")
      .done();

  py::class_<SceneObject>(m, "SceneObject", "One object of a segmented scene: a Euclidean cluster above the plane.")
      .def_readonly("index", &SceneObject::index, "its label and its place in Segmentation.objects")
      .def_readonly("rows", &SceneObject::rows, "(n) its rows of Segmentation.points")
      .def_readonly("centroid", &SceneObject::centroid, "(3,) m")
      .def_readonly("obb_center", &SceneObject::obb_center, "(3,) m: centre of the oriented bounding box")
      .def_readonly("obb_rotation", &SceneObject::obb_rotation,
                    "(3, 3): columns the box's axes by decreasing variance, right-handed")
      .def_readonly("obb_extents", &SceneObject::obb_extents, "(3,) m: side lengths along those axes")
      .def_readonly("n_points", &SceneObject::n_points);

  py::class_<PlaneCandidate>(m, "PlaneCandidate", "What the support plane rule saw of one RANSAC plane.")
      .def_readonly("plane", &PlaneCandidate::plane, "[a, b, c, d], (a, b, c) unit towards the cameras")
      .def_readonly("n_inliers", &PlaneCandidate::n_inliers)
      .def_readonly("inlier_fraction", &PlaneCandidate::inlier_fraction, "rule 1")
      .def_readonly("camera_height", &PlaneCandidate::camera_height, "m, rule 2: mean camera height above it")
      .def_readonly("behind_fraction", &PlaneCandidate::behind_fraction, "rule 3")
      .def_readonly("margin", &PlaneCandidate::margin, "m, rule 4 (NaN when not judged, inf with no object)")
      .def_readonly("accepted", &PlaneCandidate::accepted)
      .def_readonly("refused_by", &PlaneCandidate::refused_by, "the rule (1-4) that refused it; 0 when accepted")
      .def_readonly("reason", &PlaneCandidate::reason, "why it was refused, in words (empty when accepted)");

  py::class_<Segmentation>(m, "Segmentation", "The support plane and the objects of a scene cloud (segment_scene).")
      .def_property_readonly(
          "plane",
          [](const Segmentation& r) { return r.plane_found || r.plane_given ? py::cast(r.plane) : py::none(); },
          "[a, b, c, d], (a, b, c) unit towards the cameras; None without a plane")
      .def_readonly("plane_found", &Segmentation::plane_found)
      .def_readonly("plane_given", &Segmentation::plane_given)
      .def_readonly("points", &Segmentation::points, "(M, 3) the objects' points (voxelised), grouped by object")
      .def_readonly("labels", &Segmentation::labels, "(M) object index of every point")
      .def_readonly("sources", &Segmentation::sources, "(M) input row whose per-point data every point carries")
      .def_readonly("objects", &Segmentation::objects, "by decreasing point count, ties by centroid x, y, z")
      .def_readonly("candidates", &Segmentation::candidates, "the support rule's figures, in the order found")
      .def_property_readonly(
          "visibility",
          [](const Segmentation& r) -> py::object {
            if (!r.visibility) return py::none();
            return py::cast(std::const_pointer_cast<VisibilityModel>(r.visibility));
          },
          "VisibilityModel of what the cameras saw (one view per distinct viewpoint); None without viewpoints")
      .def_readonly("n_input", &Segmentation::n_input)
      .def_readonly("n_after_voxel", &Segmentation::n_after_voxel)
      .def_readonly("n_plane", &Segmentation::n_plane, "dropped as the table")
      .def_readonly("n_outliers", &Segmentation::n_outliers)
      .def_readonly("n_small_clusters", &Segmentation::n_small_clusters, "points of clusters dropped as noise")
      .def_readonly("dropped", &Segmentation::dropped,
                    "(K, 3) the points above the table the clean-up dropped (outliers, small clusters; voxelised)")
      .def_readonly("n_merged", &Segmentation::n_merged, "clusters joined to a larger one (seen through it)")
      .def_readonly("n_joined", &Segmentation::n_joined, "clusters joined to another (a shadow between them)")
      .def_readonly("n_split", &Segmentation::n_split, "clusters cut off another by the split rule")
      .def_readonly("n_output", &Segmentation::n_output)
      .def_readonly("seconds", &Segmentation::seconds, "wall time of the whole segmentation")
      .def_property_readonly(
          "step_seconds",
          [](const Segmentation& r) {
            const SegmentationTimes& t = r.times;
            py::dict d;
            d["voxel"] = t.voxel;
            d["visibility"] = t.visibility;
            d["candidates"] = t.candidates;
            d["table_cut"] = t.table_cut;
            d["outliers"] = t.outliers;
            d["clusters"] = t.clusters;
            d["merge"] = t.merge;
            d["join"] = t.join;
            d["split"] = t.split;
            d["objects"] = t.objects;
            return d;
          },
          "wall time (s) of each step: voxel, visibility, candidates (RANSAC, rules 1-3), table_cut, outliers, "
          "clusters "
          "(and rule 4), merge, join, objects; the middle three summed over the candidates tried");
  m.def(
      "segment_scene",
      [](const py::object& points, const py::object& viewpoints, const py::object& plane, const py::object& settings,
         py::kwargs kw) {
        const Vec3Array P(to_matrix(points, "segment_scene: points", 3));
        const Vec3Array V = to_points3(viewpoints, "segment_scene: viewpoints");
        std::optional<Eigen::Vector4d> known;
        if (!plane.is_none()) known = Eigen::Vector4d(to_vector(plane, "segment_scene: plane", 4));
        const SegmentationSettings s = settings_from<SegmentationSettings>(settings, kw, "segment_scene");
        py::gil_scoped_release release;
        return segment_scene(P, V, s, known);
      },
      py::arg("points"), py::arg("viewpoints") = py::none(), py::arg("plane") = py::none(), py::kw_only(),
      py::arg("settings") = py::none(),
      ("The support plane and the objects of a scene cloud (N, 3) seen from viewpoints (None: a camera at the "
       "origin; (3,) or (N, 3)); plane [a, b, c, d] gives a known support. The rule that accepts a plane is in "
       "include/graspmix/perception/segmentation.hpp.\n" +
       settings_doc<SegmentationSettings>())
          .c_str());

  // ---- surface features --------------------------------------------------------------------------
  // (The voxel size and radius a model is saved with are the Python package's FeatureScale.)
  SettingsClass<SurfaceFeatureSettings>(m, "SurfaceFeatureSettings",
                                        "Normals, curvatures and frames (compute_surface_features).")
      .field("radius", &SurfaceFeatureSettings::radius,
             "m: neighbourhood radius of normals and curvatures (paper: 1 cm)")
      .field("min_neighbours", &SurfaceFeatureSettings::min_neighbours,
             "points with fewer neighbours within radius (itself included) are dropped")
      .field("min_anisotropy", &SurfaceFeatureSettings::min_anisotropy,
             "the principal direction is x only where (k1 - k2) / k1 >= min_anisotropy ...")
      .field("flat_curvature", &SurfaceFeatureSettings::flat_curvature, "... and k1 >= flat_curvature (dimensionless)")
      .property(
          "orientation", [](const SurfaceFeatureSettings& s) { return to_string(s.orientation); },
          [](SurfaceFeatureSettings& s, const py::object& v) {
            s.orientation = normal_orientation_from_string(setting_value<std::string>(v, "orientation"));
          },
          "how normals are turned outward: auto | viewpoint | propagate | centroid | given")
      .field("orientation_neighbours", &SurfaceFeatureSettings::orientation_neighbours, "k of the propagation graph")
      .field("n_threads", &SurfaceFeatureSettings::n_threads,
             "0 = OpenMP's default, else 1..256; results do not depend on it")
      .field("max_neighbours", &SurfaceFeatureSettings::max_neighbours,
             "a neighbourhood holding more points is refused (voxel-downsample such a dense cloud first); 0: no cap")
      .done();

  py::class_<SurfaceCloud>(
      m, "SurfaceCloud", "The object representation O(v, r): points, outward normals, curvatures [k1, k2] and frames.")
      .def_readonly("points", &SurfaceCloud::points, "(N, 3) metres")
      .def_readonly("normals", &SurfaceCloud::normals, "(N, 3) unit, outward")
      .def_readonly("curvatures", &SurfaceCloud::curvatures, "(N, 2) PCL's [pc1, pc2] = [k1, k2], k1 >= k2 >= 0")
      .def_readonly("frames", &SurfaceCloud::frames,
                    "(N, 7) T_world_feature [x, y, z, qx, qy, qz, qw]: z = normal, x = principal direction, y = z x x")
      .def_readonly("indices", &SurfaceCloud::indices, "(N) input row of every kept point")
      .def_readonly("neighbours", &SurfaceCloud::neighbours, "(N) neighbours within radius, itself included")
      .def_readonly("isotropic", &SurfaceCloud::isotropic,
                    "(N) True where x came from the deterministic rule (k1 ~ k2 or flat)")
      .def_readonly("frame_ambiguity", &SurfaceCloud::frame_ambiguity,
                    "(N) radians a sampler may rotate the frame about z: pi exp(-100 ((k1 - k2) / k1)^2)")
      .def_readonly("n_input", &SurfaceCloud::n_input)
      .def_readonly("n_dropped", &SurfaceCloud::n_dropped, "points without a stable neighbourhood")
      .def_readonly("radius", &SurfaceCloud::radius)
      .def_readonly("orientation", &SurfaceCloud::orientation, "rule that oriented the normals")
      .def_readonly("seconds_normals", &SurfaceCloud::seconds_normals, "s")
      .def_readonly("seconds_orientation", &SurfaceCloud::seconds_orientation, "s")
      .def_readonly("seconds_curvatures", &SurfaceCloud::seconds_curvatures, "s")
      .def_readonly("seconds_total", &SurfaceCloud::seconds_total, "s")
      .def_property_readonly(
          "timings",
          [](const SurfaceCloud& s) {
            py::dict d;
            d["normals"] = s.seconds_normals;
            d["orientation"] = s.seconds_orientation;
            d["curvatures"] = s.seconds_curvatures;
            d["total"] = s.seconds_total;
            return d;
          },
          "seconds per stage")
      .def("__len__", [](const SurfaceCloud& s) { return s.points.rows(); })
      .def("__repr__", [](const SurfaceCloud& s) {
        return "<SurfaceCloud " + std::to_string(s.points.rows()) + " points (" + std::to_string(s.n_dropped) +
               " dropped), radius " + std::to_string(s.radius) + " m, normals by " + s.orientation + ">";
      });
  m.def(
      "compute_surface_features",
      [](const py::object& points, const py::object& radius, const py::object& normals, const py::object& viewpoints,
         const py::object& settings, py::kwargs kw) {
        const Vec3Array P(to_matrix(points, "compute_surface_features: points", 3));
        const Vec3Array N =
            normals.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(normals, "compute_surface_features: normals", 3));
        const Vec3Array V = to_points3(viewpoints, "compute_surface_features: viewpoints");
        if (!radius.is_none()) kw["radius"] = radius;
        const SurfaceFeatureSettings s =
            settings_from<SurfaceFeatureSettings>(settings, kw, "compute_surface_features");
        py::gil_scoped_release release;
        return compute_surface_features(P, s, N, V);
      },
      py::arg("points"), py::arg("radius") = py::none(), py::arg("normals") = py::none(),
      py::arg("viewpoints") = py::none(), py::kw_only(), py::arg("settings") = py::none(),
      ("O(v, r) of a cloud (N, 3): normals (the smallest eigenvector of each radius neighbourhood's covariance, PCL "
       "NormalEstimation's definition, computed in parallel here; or the given (N, 3)), outward by `orientation` "
       "(auto: towards viewpoints (3,) / (N, 3) when given, else given normals as they are, else propagated "
       "outward over the surface; or 'viewpoint', 'propagate', 'centroid', 'given'), principal curvatures (PCL, "
       "radius in m) and frames. Points with fewer than min_neighbours neighbours within radius are dropped "
       "(see indices, n_dropped). x is PCL's principal direction where (k1 - k2) / k1 >= min_anisotropy and "
       "k1 >= flat_curvature, else world z projected on the tangent plane (world x near +-z). radius=None: the "
       "settings' radius.\n" +
       settings_doc<SurfaceFeatureSettings>())
          .c_str());
  bind_visibility(m);
  bind_completion(m);
}

}  // namespace graspmix::py_bind
