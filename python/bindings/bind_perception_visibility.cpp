// Part of bind_perception: pinhole cameras, the visibility model (what the cameras saw, as space) and the scene of
// one depth image (segment_depth, segment_organized).
#include <pybind11/operators.h>

#include <algorithm>

#include "common.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/perception/camera.hpp"
#include "graspmix/perception/depth_scene.hpp"
#include "graspmix/perception/visibility.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

int to_side(const py::object& obj, const char* name) {
  if (!py::isinstance<py::int_>(obj) || py::isinstance<py::bool_>(obj))
    throw py::value_error(std::string(name) + ": expected an integer number of pixels");
  const auto v = obj.cast<long long>();
  if (v < 1 || v > 1'000'000) throw py::value_error(std::string(name) + ": expected 1 to 1000000 pixels");
  return static_cast<int>(v);
}

/// An organized cloud as (H * W, 3) rows with its height and width: from an (H, W, 3) array, or from
/// (H * W, 3) with height and width given.
Vec3Array to_organized(const py::object& points, const py::object& height, const py::object& width, int& h, int& w) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!a) throw py::value_error("points: could not be read as an array of numbers");
  if (a.ndim() == 3) {
    if (a.shape(2) != 3)
      throw py::value_error("points: expected shape (H, W, 3), got (..., " + std::to_string(a.shape(2)) + ")");
    h = to_side(py::int_(a.shape(0)), "points: height");
    w = to_side(py::int_(a.shape(1)), "points: width");
    if ((!height.is_none() && to_side(height, "height") != h) || (!width.is_none() && to_side(width, "width") != w))
      throw py::value_error("points: an (H, W, 3) array's height and width disagree with the ones given");
    return Eigen::Map<const Vec3Array>(a.data(), static_cast<Eigen::Index>(h) * w, 3);
  }
  if (height.is_none() || width.is_none())
    throw py::value_error("points: an (H * W, 3) organized cloud needs height and width (or pass it as (H, W, 3))");
  h = to_side(height, "height");
  w = to_side(width, "width");
  return Vec3Array(to_matrix(points, "points", 3));
}

/// Query points (N, 3) or one (3,) as rows, read in place from a C-contiguous float64 array (a million points
/// are 24 MB: a copy costs about as much as classifying them); other inputs are converted once.
class PointRows {
 public:
  PointRows(const py::object& obj, const char* name)
      : array_(py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj)) {
    const bool ok =
        array_ && ((array_.ndim() == 2 && array_.shape(1) == 3) || (array_.ndim() == 1 && array_.shape(0) == 3));
    if (!ok) to_matrix(obj, name, 3, true);  // throws the standard message naming the argument
    if (!ok) throw py::value_error(std::string(name) + ": expected shape (N, 3)");
  }
  Eigen::Map<const Vec3Array> rows() const {
    return {array_.data(), array_.ndim() == 1 ? 1 : static_cast<Eigen::Index>(array_.shape(0)), 3};
  }

 private:
  py::array_t<double, py::array::c_style | py::array::forcecast> array_;
};

py::object view_info_dict(const ViewInfo& v) {
  py::dict d;
  d["kind"] = v.kind == ViewKind::Pinhole ? "pinhole" : "spherical";
  d["T_world_sensor"] = Eigen::VectorXd(pose_to_vector(v.T_world_sensor));
  d["camera"] = v.camera ? py::cast(*v.camera) : py::none();
  d["width"] = v.width;
  d["height"] = v.height;
  d["n_returns"] = v.n_returns;
  d["angular_resolution"] = v.angular_resolution;
  d["fit_rms_px"] = v.fit_rms_px;
  d["seconds"] = v.seconds;
  return std::move(d);
}

void bind_camera(py::module_& m) {
  // Both classes first, so that each one's signatures name the other as a Python type.
  py::class_<PinholeCamera> camera(
      m, "PinholeCamera",
      "Pinhole intrinsics of a depth camera (px), no distortion. Sensor frame: x right, y "
      "down, z forward;\npixel (u, v) = (column, row), pixel centres at integer coordinates.");
  py::class_<PinholeFit> fit(m, "PinholeFit", "Intrinsics fitted to an organized cloud (PinholeCamera.fit).");
  camera
      .def(py::init([](const py::object& fx, const py::object& fy, const py::object& cx, const py::object& cy,
                       const py::object& width, const py::object& height) {
             return PinholeCamera(to_number(fx, "fx"), to_number(fy, "fy"), to_number(cx, "cx"), to_number(cy, "cy"),
                                  to_int(width, "width"), to_int(height, "height"));
           }),
           py::arg("fx"), py::arg("fy"), py::arg("cx"), py::arg("cy"), py::arg("width"), py::arg("height"),
           "ValueError unless fx, fy > 0, cx, cy finite, width, height >= 1.")
      .def_property_readonly("fx", &PinholeCamera::fx)
      .def_property_readonly("fy", &PinholeCamera::fy)
      .def_property_readonly("cx", &PinholeCamera::cx)
      .def_property_readonly("cy", &PinholeCamera::cy)
      .def_property_readonly("width", &PinholeCamera::width)
      .def_property_readonly("height", &PinholeCamera::height)
      .def_property_readonly("K", &PinholeCamera::matrix, "(3, 3) [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]")
      .def(
          "project",
          [](const PinholeCamera& c, const py::object& points) {
            const Vec3Array P(to_matrix(points, "project: points", 3, true));
            RowMatrixXd out(P.rows(), 2);
            for (Eigen::Index i = 0; i < P.rows(); ++i) out.row(i) = c.project(P.row(i).transpose()).transpose();
            return out;
          },
          py::arg("points"), "(N, 2) pixel coordinates (u, v) of points (N, 3) in the sensor frame; NaN where z <= 0.")
      .def(
          "back_project",
          [](const PinholeCamera& c, const py::object& depth) {
            const DepthImage D(to_matrix(depth, "depth"));
            Vec3Array P;
            {
              py::gil_scoped_release release;
              P = c.back_project(D);
            }
            py::array_t<double> out({static_cast<py::ssize_t>(c.height()), static_cast<py::ssize_t>(c.width()),
                                     static_cast<py::ssize_t>(3)});
            std::copy(P.data(), P.data() + P.size(), out.mutable_data());
            return out;
          },
          py::arg("depth"),
          "The organized cloud (H, W, 3) in the sensor frame of a depth image (H, W) in metres along z; NaN, 0 and "
          "inf are no return (NaN points), a negative depth is a ValueError.")
      .def(
          "check_image",
          [](const PinholeCamera& c, const py::object& depth) {
            const DepthImage D(to_matrix(depth, "depth"));
            return c.check_image(D, "depth");
          },
          py::arg("depth"),
          "The number of pixels of a depth image (H, W) with a return; ValueError for an image of another size or a "
          "negative depth.")
      .def_static(
          "fit",
          [](const py::object& points, const py::object& height, const py::object& width,
             const py::object& max_rms_px_obj) {
            const double max_rms_px = to_number(max_rms_px_obj, "max_rms_px");
            int h = 0, w = 0;
            const Vec3Array P = to_organized(points, height, width, h, w);
            py::gil_scoped_release release;
            return fit_pinhole(P, h, w, max_rms_px, "points");
          },
          py::arg("points"), py::arg("height") = py::none(), py::arg("width") = py::none(), py::arg("max_rms_px") = 0.5,
          "The intrinsics of an organized cloud in the sensor frame, (H, W, 3) or (H * W, 3) with height and width "
          "(NaN = no return), by least squares over its valid pixels; ValueError when the RMS reprojection residual "
          "exceeds max_rms_px (not a pinhole image in the sensor frame).")
      .def(py::self == py::self)  // NOLINT(misc-redundant-expression)
      .def(py::pickle(
          [](const PinholeCamera& c) { return py::make_tuple(c.fx(), c.fy(), c.cx(), c.cy(), c.width(), c.height()); },
          [](const py::tuple& t) {
            return PinholeCamera(t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>(),
                                 t[4].cast<int>(), t[5].cast<int>());
          }))
      .def("__repr__", [](const PinholeCamera& c) {
        return "PinholeCamera(fx=" + std::string(py::repr(py::float_(c.fx()))) +
               ", fy=" + std::string(py::repr(py::float_(c.fy()))) +
               ", cx=" + std::string(py::repr(py::float_(c.cx()))) +
               ", cy=" + std::string(py::repr(py::float_(c.cy()))) + ", width=" + std::to_string(c.width()) +
               ", height=" + std::to_string(c.height()) + ")";
      });
  camera.attr("__hash__") = py::none();
  fit.def_readonly("camera", &PinholeFit::camera)
      .def_readonly("rms_px", &PinholeFit::rms_px, "px: RMS reprojection residual over the valid pixels")
      .def_readonly("n_valid", &PinholeFit::n_valid, "pixels with a point");
}

}  // namespace

void bind_visibility(py::module_& m) {
  bind_camera(m);
  const auto code = [](SpaceState s) { return static_cast<int>(s); };
  int_enum(m, "SpaceState",
           {{"SeenFree", code(SpaceState::SeenFree)},
            {"Surface", code(SpaceState::Surface)},
            {"Unseen", code(SpaceState::Unseen)}},
           "What the views saw of a point, the codes VisibilityModel.classify returns: SeenFree (0, in front of the "
           "observed surface along the point's ray), Surface (1, within surface_tolerance of it), Unseen (2, behind "
           "it, outside every image, or on a ray with no return).");
  SettingsClass<VisibilitySettings>(m, "VisibilitySettings", "The visibility model (VisibilityModel).")
      .field("surface_tolerance", &VisibilitySettings::surface_tolerance,
             "m: within this of the observed surface along the ray is Surface (>= 0)")
      .field("angular_resolution", &VisibilitySettings::angular_resolution,
             "rad: bin size of from_points' spherical range image, in (0, 0.5]")
      .field("no_return_is_free", &VisibilitySettings::no_return_is_free,
             "a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)")
      .field("max_fit_rms", &VisibilitySettings::max_fit_rms,
             "px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on")
      .field("max_pixels", &VisibilitySettings::max_pixels, "the largest image one view may hold (pixels)")
      .done();

  py::class_<VisibilityModel, std::shared_ptr<VisibilityModel>>(
      m, "VisibilityModel",
      "What the cameras saw, as space: each point SeenFree, Surface or Unseen, from one image per view (O(1) per\n"
      "point). Views combine by: Surface if any view has the point within surface_tolerance of its surface; else\n"
      "SeenFree if any view sees it in front; else Unseen. The rule: include/graspmix/perception/visibility.hpp.")
      .def(py::init([](const py::object& settings, const py::kwargs& kw) {
             return std::make_shared<VisibilityModel>(
                 settings_from<VisibilitySettings>(settings, kw, "VisibilityModel"));
           }),
           py::kw_only(), py::arg("settings") = py::none(),
           "A model of no view (every point Unseen), to add views to (add_view) built with the same settings.")
      .def_static(
          "from_depth",
          [](const py::object& depth, const PinholeCamera& camera, const py::object& pose, const py::object& settings,
             const py::kwargs& kw) {
            DepthImage D(to_matrix(depth, "depth"));
            const Eigen::Isometry3d T = to_camera_pose(pose, "T_world_camera");
            const auto s = settings_from<VisibilitySettings>(settings, kw, "VisibilityModel.from_depth");
            py::gil_scoped_release release;
            return std::make_shared<VisibilityModel>(VisibilityModel::from_depth(std::move(D), camera, T, s));
          },
          py::arg("depth"), py::arg("camera"), py::arg("T_world_camera"), py::kw_only(),
          py::arg("settings") = py::none(),
          ("One view from a depth image (H, W) in metres along z (NaN, 0, inf: no return) of `camera`, posed at\n"
           "T_world_camera [x, y, z, qx, qy, qz, qw] (a unit quaternion).\n" +
           settings_doc<VisibilitySettings>())
              .c_str())
      .def_static(
          "from_organized",
          [](const py::object& points, const py::object& pose, const py::object& height, const py::object& width,
             const py::object& settings, const py::kwargs& kw) {
            int h = 0, w = 0;
            const Vec3Array P = to_organized(points, height, width, h, w);
            const Eigen::Isometry3d T = to_camera_pose(pose, "T_world_camera");
            const auto s = settings_from<VisibilitySettings>(settings, kw, "VisibilityModel.from_organized");
            py::gil_scoped_release release;
            return std::make_shared<VisibilityModel>(VisibilityModel::from_organized(P, h, w, T, s));
          },
          py::arg("points"), py::arg("T_world_camera"), py::kw_only(), py::arg("height") = py::none(),
          py::arg("width") = py::none(), py::arg("settings") = py::none(),
          ("One view from an organized cloud in the sensor frame (x right, y down, z forward; NaN = no return),\n"
           "(H, W, 3) or (H * W, 3) with height and width; its pinhole intrinsics are fitted (views[i]['camera']).\n" +
           settings_doc<VisibilitySettings>())
              .c_str())
      .def_static(
          "from_points",
          [](const py::object& points, const py::object& viewpoint, const py::object& settings, const py::kwargs& kw) {
            const Vec3Array P(to_matrix(points, "points", 3));
            const Eigen::Vector3d V = to_vector(viewpoint, "viewpoint", 3);
            const auto s = settings_from<VisibilitySettings>(settings, kw, "VisibilityModel.from_points");
            py::gil_scoped_release release;
            return std::make_shared<VisibilityModel>(VisibilityModel::from_points(P, V, s));
          },
          py::arg("points"), py::arg("viewpoint"), py::kw_only(), py::arg("settings") = py::none(),
          ("One view from an unorganized cloud (N, 3) in the world frame seen from viewpoint (3,): a spherical range\n"
           "image (pcl::RangeImage) at angular_resolution, each bin its nearest point; empty bins are unseen.\n" +
           settings_doc<VisibilitySettings>())
              .c_str())
      .def_static(
          "from_views",
          [](const py::object& points, const py::object& viewpoints, const py::object& settings, const py::kwargs& kw) {
            const Vec3Array P(to_matrix(points, "points", 3));
            const Vec3Array V = to_points3(viewpoints, "viewpoints");
            const auto s = settings_from<VisibilitySettings>(settings, kw, "VisibilityModel.from_views");
            py::gil_scoped_release release;
            return std::make_shared<VisibilityModel>(VisibilityModel::from_views(P, V, s));
          },
          py::arg("points"), py::arg("viewpoints"), py::kw_only(), py::arg("settings") = py::none(),
          ("Every view of an unorganized cloud (N, 3) in the world frame: viewpoints (3,) for one camera or (N, 3),\n"
           "the camera that saw each point; the points of each distinct viewpoint make one from_points view.\n" +
           settings_doc<VisibilitySettings>())
              .c_str())
      .def("add_view", &VisibilityModel::add_view, py::arg("other"),
           "Adds the views of another model built with equal settings (ValueError otherwise).")
      .def(
          "classify",
          [](const VisibilityModel& v, const py::object& points) {
            const PointRows P(points, "classify: points");
            py::array_t<std::uint8_t> out(P.rows().rows());
            {
              py::gil_scoped_release release;
              const std::vector<SpaceState> s = v.classify(P.rows());
              std::transform(s.begin(), s.end(), out.mutable_data(),
                             [](SpaceState x) { return static_cast<std::uint8_t>(x); });
            }
            return out;
          },
          py::arg("points"), "(N,) uint8 SpaceState of points (N, 3) or (3,): 0 SeenFree, 1 Surface, 2 Unseen.")
      .def(
          "signed_distance",
          [](const VisibilityModel& v, const py::object& points) {
            const PointRows P(points, "signed_distance: points");
            py::gil_scoped_release release;
            return v.signed_distances(P.rows());
          },
          py::arg("points"),
          "(N,) m along each point's ray to the observed surface, positive in front, chosen over the views by the\n"
          "classification's rule (|d| <= surface_tolerance: Surface, d > it: SeenFree, else Unseen); inf on a\n"
          "no-return ray taken as free, NaN where no view says anything.")
      .def_property_readonly("n_views", &VisibilityModel::n_views)
      .def_property_readonly(
          "views",
          [](const VisibilityModel& v) {
            py::list out;
            for (int i = 0; i < v.n_views(); ++i) out.append(view_info_dict(v.view(i)));
            return out;
          },
          "Per view: kind ('pinhole' | 'spherical'), T_world_sensor (7,), camera (PinholeCamera or None), width,\n"
          "height, n_returns, angular_resolution (rad), fit_rms_px, seconds.")
      .def_property_readonly("settings", [](const VisibilityModel& v) { return VisibilitySettings(v.settings()); })
      .def("__len__", &VisibilityModel::n_views)
      .def("__repr__",
           [](const VisibilityModel& v) { return "<VisibilityModel " + std::to_string(v.n_views()) + " view(s)>"; });

  m.def(
      "camera_pose_matrix",
      [](const py::object& pose) { return Eigen::Matrix4d(to_camera_pose(pose, "camera pose").matrix()); },
      py::arg("pose"),
      "The 4x4 T_world_camera of [x, y, z, qx, qy, qz, qw], its quaternion normalised; ValueError for a non-finite "
      "value or a quaternion whose norm is off 1 by more than 1e-3 (kUnitQuaternionTolerance).");
  m.def(
      "segment_depth",
      [](const py::object& depth, const PinholeCamera& camera, const py::object& pose, const py::object& plane,
         const py::object& settings, const py::kwargs& kw) {
        const DepthImage D(to_matrix(depth, "segment_depth: depth"));
        const Eigen::Isometry3d T = to_camera_pose(pose, "T_world_camera");
        std::optional<Eigen::Vector4d> known;
        if (!plane.is_none()) known = Eigen::Vector4d(to_vector(plane, "segment_depth: plane", 4));
        const auto s = settings_from<SegmentationSettings>(settings, kw, "segment_depth");
        py::gil_scoped_release release;
        return segment_depth(D, camera, T, s, known);
      },
      py::arg("depth"), py::arg("camera"), py::arg("T_world_camera"), py::arg("plane") = py::none(), py::kw_only(),
      py::arg("settings") = py::none(),
      ("The support plane and the objects of one depth image (H, W) in metres along z (NaN, 0, inf: no return)\n"
       "of `camera` (PinholeCamera) posed at T_world_camera [x, y, z, qx, qy, qz, qw]: segment_scene's scene in the\n"
       "world frame, made in image space (include/graspmix/perception/depth_scene.hpp); sources are pixel indices.\n" +
       settings_doc<SegmentationSettings>())
          .c_str());
  m.def(
      "segment_organized",
      [](const py::object& points, const py::object& pose, const py::object& plane, const py::object& height,
         const py::object& width, const std::optional<PinholeCamera>& camera, const py::object& settings,
         const py::kwargs& kw) {
        int h = 0, w = 0;
        const Vec3Array P = to_organized(points, height, width, h, w);
        const Eigen::Isometry3d T = to_camera_pose(pose, "T_world_camera");
        std::optional<Eigen::Vector4d> known;
        if (!plane.is_none()) known = Eigen::Vector4d(to_vector(plane, "segment_organized: plane", 4));
        const auto s = settings_from<SegmentationSettings>(settings, kw, "segment_organized");
        if (camera && (camera->height() != h || camera->width() != w))
          throw py::value_error("segment_organized: camera is " + std::to_string(camera->width()) + " x " +
                                std::to_string(camera->height()) + ", the cloud " + std::to_string(w) + " x " +
                                std::to_string(h));
        py::gil_scoped_release release;
        return camera ? segment_organized(P, *camera, T, s, known) : segment_organized(P, h, w, T, s, known);
      },
      py::arg("points"), py::arg("T_world_camera"), py::arg("plane") = py::none(), py::kw_only(),
      py::arg("height") = py::none(), py::arg("width") = py::none(), py::arg("camera") = py::none(),
      py::arg("settings") = py::none(),
      ("The support plane and the objects of an organized cloud in the sensor frame (x right, y down, z forward;\n"
       "NaN = no return), (H, W, 3) or (H * W, 3) with height and width, from a camera posed at T_world_camera: its\n"
       "intrinsics fitted (or `camera`, a PinholeCamera fitted already), then as segment_depth.\n" +
       settings_doc<SegmentationSettings>())
          .c_str());
}

}  // namespace graspmix::py_bind
