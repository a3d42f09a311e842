"""
graspmix C++ core: SE(3) maps, Gaussian mixtures, pose densities (GMM and KDE)
"""
from __future__ import annotations
import builtins
import collections.abc
import enum
import numpy
import numpy.typing
import typing
__all__: list[str] = ['AnnealingSettings', 'AxisAlignmentExpert', 'AxisAlignmentSettings', 'COMPLETED_VIEW_DISTANCE', 'CleanupResult', 'CleanupSettings', 'ClearApproachExpert', 'ClearApproachSettings', 'CloudData', 'CollisionBatchResult', 'CollisionExpert', 'CollisionFreeExpert', 'CollisionResult', 'CollisionSettings', 'Completion', 'CompletionKind', 'CompletionSettings', 'ConfigModel', 'ConfigModelSettings', 'ContactData', 'ContactModel', 'ContactQualityExpert', 'ContactQualityResult', 'ContactQualitySettings', 'ContactSettings', 'Evaluation', 'Expert', 'FunctionExpert', 'GaussianMixture', 'GmmSettings', 'Grasp', 'GraspDepthExpert', 'GraspDepthSettings', 'GraspSynthesizer', 'Hand', 'HandLoadSettings', 'KdeSettings', 'KinematicFeasibilityExpert', 'KinematicFeasibilitySettings', 'MAX_OVERSAMPLE', 'OccupancyMap', 'OccupancySettings', 'POINT_TARGET_MAX_DISTANCE', 'PinholeCamera', 'PinholeFit', 'PlaneCandidate', 'PoseDensity', 'PoseKDE', 'PoseMixture', 'QueryDensity', 'QuerySettings', 'SamplingSettings', 'SceneCompletion', 'SceneObject', 'SceneSimResult', 'SceneSynthesis', 'Segmentation', 'SegmentationSettings', 'SettleResult', 'SimObject', 'SimResult', 'SimSettings', 'SpaceState', 'SurfaceCloud', 'SurfaceFeatureSettings', 'SynthesisResult', 'SynthesisTiming', 'SynthesizerSettings', 'TYPE_REFERENCE_TERM', 'URDF_AXES_ELEMENT', 'VisibilityModel', 'VisibilitySettings', 'build_info', 'camera_pose_matrix', 'complete_object', 'complete_scene', 'compute_surface_features', 'contact_data', 'learn_contact_models', 'load_cloud', 'load_mesh', 'log_vmf_s3_normaliser', 'object_surface', 'orient_plane', 'pose_inverse', 'pose_multiply', 'prepare_cloud', 'quat_exp', 'quat_log', 'query_weights', 'save_cloud', 'segment_depth', 'segment_organized', 'segment_scene', 'select_targets', 'sim_closing_speeds', 'sim_execute', 'sim_execute_scene', 'sim_settle_scene', 'solid_volume', 'synthesize_scene']
class GmmSettings:
    """
    How a GaussianMixture (or PoseMixture) is fitted by EM.
    
    Settings: settings= a GmmSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      n_components = 1: K, the number of components
      reg_covar = 1e-06: added to every covariance diagonal (units of the data squared)
      max_iter = 100: EM iterations per initialisation
      tol = 0.001: convergence threshold on the change of the mean log-likelihood
      n_init = 1: initialisations; the best lower bound wins
      seed = 0: seeds the k-means++ initialisation (None: 0; never the clock)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('n_components', 'reg_covar', 'max_iter', 'tol', 'n_init', 'seed')
    def __copy__(self) -> GmmSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> GmmSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (n_components, reg_covar, max_iter, tol, n_init, seed); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def max_iter(self) -> int:
        """
        EM iterations per initialisation
        """
    @max_iter.setter
    def max_iter(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_components(self) -> int:
        """
        K, the number of components
        """
    @n_components.setter
    def n_components(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_init(self) -> int:
        """
        initialisations; the best lower bound wins
        """
    @n_init.setter
    def n_init(self, arg0: typing.Any) -> None:
        ...
    @property
    def reg_covar(self) -> float:
        """
        added to every covariance diagonal (units of the data squared)
        """
    @reg_covar.setter
    def reg_covar(self, arg0: typing.Any) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seeds the k-means++ initialisation (None: 0; never the clock)
        """
    @seed.setter
    def seed(self, arg1: typing.Any) -> None:
        ...
    @property
    def tol(self) -> float:
        """
        convergence threshold on the change of the mean log-likelihood
        """
    @tol.setter
    def tol(self, arg0: typing.Any) -> None:
        ...
class KdeSettings:
    """
    Kernel bandwidths of a PoseKDE (Kopicki et al. 2015).
    
    Settings: settings= a KdeSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      position_bandwidth = 0.005: m: std of the position kernel
      orientation_bandwidth = 0.15: rad: approximate std of the rotation angle of the kernel
      feature_bandwidth = array([0.005]): std per feature (units of the features): one value for all, one per feature, or empty (None) for 0.01
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('position_bandwidth', 'orientation_bandwidth', 'feature_bandwidth')
    def __copy__(self) -> KdeSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> KdeSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (position_bandwidth, orientation_bandwidth, feature_bandwidth); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def feature_bandwidth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        std per feature (units of the features): one value for all, one per feature, or empty (None) for 0.01
        """
    @feature_bandwidth.setter
    def feature_bandwidth(self, arg1: typing.Any) -> None:
        ...
    @property
    def orientation_bandwidth(self) -> float:
        """
        rad: approximate std of the rotation angle of the kernel
        """
    @orientation_bandwidth.setter
    def orientation_bandwidth(self, arg0: typing.Any) -> None:
        ...
    @property
    def position_bandwidth(self) -> float:
        """
        m: std of the position kernel
        """
    @position_bandwidth.setter
    def position_bandwidth(self, arg0: typing.Any) -> None:
        ...
class GaussianMixture:
    """
    Full-covariance Gaussian mixture fitted by weighted EM, named as scikit-learn's.
    """
    @staticmethod
    def from_parameters(weights: typing.Any, means: typing.Any, covariances: typing.Any) -> GaussianMixture:
        """
        A mixture from weights (K,), means (K, d), covariances (K, d, d).
        """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, settings: typing.Any = None, **kwargs) -> None:
        """
        An unfitted mixture, e.g. GaussianMixture(n_components=3, seed=0).
        Settings: settings= a GmmSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          n_components = 1: K, the number of components
          reg_covar = 1e-06: added to every covariance diagonal (units of the data squared)
          max_iter = 100: EM iterations per initialisation
          tol = 0.001: convergence threshold on the change of the mean log-likelihood
          n_init = 1: initialisations; the best lower bound wins
          seed = 0: seeds the k-means++ initialisation (None: 0; never the clock)
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def condition(self, given_dims: typing.Any, values: typing.Any) -> GaussianMixture:
        """
        The mixture over the other dimensions (increasing order) given x[given_dims] = values.
        """
    def fit(self, X: typing.Any, weights: typing.Any = None, means_init: typing.Any = None) -> GaussianMixture:
        """
        Weighted EM; returns self.
        """
    def marginal(self, dims: typing.Any) -> GaussianMixture:
        ...
    def predict(self, X: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    def predict_proba(self, X: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    def sample(self, n: typing.Any, seed: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        n draws, (n, d).
        """
    def score(self, X: typing.Any, weights: typing.Any = None) -> float:
        """
        (Weighted) mean log density.
        """
    def score_samples(self, X: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Log density of every row.
        """
    @property
    def converged_(self) -> bool:
        ...
    @property
    def covariances_(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def lower_bound_(self) -> float:
        ...
    @property
    def lower_bound_history_(self) -> list[float]:
        ...
    @property
    def means_(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def n_components(self) -> int:
        ...
    @property
    def n_iter_(self) -> int:
        ...
    @property
    def settings(self) -> GmmSettings:
        """
        The GmmSettings it fits with (a copy).
        """
    @property
    def weights_(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class PoseDensity:
    """
    A density over poses given features: PoseMixture (the paper's) or PoseKDE (the baseline).
    """
    def feature_log_density(self, features: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        log p(r) per row (eq:density_mixture_features).
        """
    def log_density(self, poses: typing.Any, features: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        log p(u | r) per row (eq:density_mixture_rigid_body). features: (N, n), or (n,) for every pose.
        """
    def sample(self, n: typing.Any, features: typing.Any = None, seed: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 7]"]:
        """
        n poses (n, 7) drawn from p(u | r); features (n_features,) for all draws or (n, n_features) one per draw.
        """
    @property
    def fitted(self) -> bool:
        ...
    @property
    def kind(self) -> str:
        """
        'gmm' or 'kde'.
        """
    @property
    def n_features(self) -> int:
        ...
    @property
    def n_kernels(self) -> int:
        """
        Components (GMM) or kernels (KDE).
        """
class PoseMixture(PoseDensity):
    """
    The paper's mixture over (p, q, r), fitted in (p, log q, r): p(u|r) by conditioning, p(r) by marginalising.
    """
    @staticmethod
    def default_settings() -> GmmSettings:
        """
        GmmSettings with the paper's K = 2 components.
        """
    @staticmethod
    def from_parameters(reference: typing.Any, joint: GaussianMixture) -> PoseMixture:
        ...
    def __getstate__(self) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 1]"], GaussianMixture]:
        ...
    def __init__(self, settings: typing.Any = None, **kwargs) -> None:
        """
        An unfitted pose mixture. Its defaults are PoseMixture.default_settings() (the paper's K = 2), not
        GmmSettings()'s.
        Settings: settings= a GmmSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          n_components = 2: K, the number of components
          reg_covar = 1e-06: added to every covariance diagonal (units of the data squared)
          max_iter = 100: EM iterations per initialisation
          tol = 0.001: convergence threshold on the change of the mean log-likelihood
          n_init = 1: initialisations; the best lower bound wins
          seed = 0: seeds the k-means++ initialisation (None: 0; never the clock)
        """
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def fit(self, poses: typing.Any, features: typing.Any = None, weights: typing.Any = None) -> PoseMixture:
        """
        Fits to poses (N, 7), features (N, n), weights (N,); returns self.
        """
    @property
    def joint(self) -> GaussianMixture:
        """
        The mixture over (p, log(q_ref^-1 q), r).
        """
    @property
    def reference(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 1]"]:
        """
        The chart's reference rotation [x, y, z, w].
        """
    @property
    def settings(self) -> GmmSettings:
        """
        The GmmSettings it fits with (a copy).
        """
class PoseKDE(PoseDensity):
    """
    Kopicki et al. 2015's non-parametric density: one weighted kernel per data point.
    """
    def __init__(self, settings: typing.Any = None, **kwargs) -> None:
        """
        An unfitted KDE.
        Settings: settings= a KdeSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          position_bandwidth = 0.005: m: std of the position kernel
          orientation_bandwidth = 0.15: rad: approximate std of the rotation angle of the kernel
          feature_bandwidth = array([0.005]): std per feature (units of the features): one value for all, one per feature, or empty (None) for 0.01
        """
    def fit(self, poses: typing.Any, features: typing.Any = None, weights: typing.Any = None) -> PoseKDE:
        ...
    @property
    def concentration(self) -> float:
        ...
    @property
    def feature_bandwidth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def features(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def orientation_bandwidth(self) -> float:
        ...
    @property
    def orientations(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 4]"]:
        ...
    @property
    def position_bandwidth(self) -> float:
        ...
    @property
    def positions(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def settings(self) -> KdeSettings:
        """
        The KdeSettings it was made with (a copy).
        """
    @property
    def weights(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class CloudData:
    """
    A point cloud read from a file, with what the file said about it.
    """
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def organized(self, camera_pose: typing.Any = None) -> numpy.typing.NDArray[numpy.float64]:
        """
        The points on their image grid: (height, width, 3) float64, NaN where the file had no finite point;
        with camera_pose [x, y, z, qx, qy, qz, qw] (a camera's pose in the file's frame, e.g. its VIEWPOINT),
        each point in that camera's frame. ValueError, naming the file, for an unorganised cloud (height 1),
        and for a camera_pose that is not a finite pose with a unit quaternion.
        """
    @property
    def fields(self) -> list[str]:
        """
        Every field of the file (x, y, z, rgb, ...).
        """
    @property
    def format(self) -> str:
        ...
    @property
    def has_viewpoint(self) -> bool:
        """
        True when the file's viewpoint is not the identity.
        """
    @property
    def height(self) -> int:
        """
        > 1 for organised clouds
        """
    @property
    def n_invalid(self) -> int:
        """
        Points dropped for a NaN or infinite coordinate.
        """
    @property
    def normals(self) -> typing.Any:
        """
        (N, 3) normals from the file (normal_x/y/z or nx/ny/nz), or None.
        """
    @property
    def path(self) -> str:
        ...
    @property
    def pixels(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, 1]"]:
        """
        (N,) int64: for an organised file (height > 1) the pixel v * width + u of each point in its
        width x height grid (row v, column u); empty for an unorganised one.
        """
    @property
    def points(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (N, 3) finite points (m); NaN points of the file are dropped.
        """
    @property
    def viewpoint(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 1]"]:
        """
        Sensor pose [x, y, z, qx, qy, qz, qw] from the PCD VIEWPOINT (identity when absent).
        """
    @property
    def viewpoints(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (N, 3) the camera position of each point (PCD/PLY fields vp_x vp_y vp_z, PCL's PointWithViewpoint), following the points kept; (0, 3) when the file has none.
        """
    @property
    def width(self) -> int:
        ...
class CleanupSettings:
    """
    Scene clean-up before features (prepare_cloud).
    
    Settings: settings= a CleanupSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      crop = False: keep only points inside [crop_min, crop_max]
      crop_min = array([-inf, -inf, -inf]): m (3,), the cloud's frame
      crop_max = array([inf, inf, inf]): m (3,), the cloud's frame
      voxel_size = 0.003: m: voxel-grid leaf size, 0 = off (demonstration and query clouds must share it)
      remove_outliers = True: PCL StatisticalOutlierRemoval
      outlier_neighbours = 20: k of the mean-distance statistic
      outlier_std_ratio = 2.0: drop points whose mean k-distance exceeds mean + ratio * std
      remove_plane = True: find the dominant plane by RANSAC and remove it
      plane_distance = 0.005: m: RANSAC inlier threshold
      plane_max_iterations = 1000: RANSAC iterations
      plane_min_fraction = 0.2: fraction of the cleaned points a plane needs to count as the support
      remove_below_plane = True: also drop points on the far side of the plane from the object
      seed = 0: seeds RANSAC (None: 0)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('crop', 'crop_min', 'crop_max', 'voxel_size', 'remove_outliers', 'outlier_neighbours', 'outlier_std_ratio', 'remove_plane', 'plane_distance', 'plane_max_iterations', 'plane_min_fraction', 'remove_below_plane', 'seed')
    def __copy__(self) -> CleanupSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> CleanupSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (crop, crop_min, crop_max, voxel_size, remove_outliers, outlier_neighbours, outlier_std_ratio, remove_plane, plane_distance, plane_max_iterations, plane_min_fraction, remove_below_plane, seed); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def crop(self) -> bool:
        """
        keep only points inside [crop_min, crop_max]
        """
    @crop.setter
    def crop(self, arg0: typing.Any) -> None:
        ...
    @property
    def crop_max(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        m (3,), the cloud's frame
        """
    @crop_max.setter
    def crop_max(self, arg1: typing.Any) -> None:
        ...
    @property
    def crop_min(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        m (3,), the cloud's frame
        """
    @crop_min.setter
    def crop_min(self, arg1: typing.Any) -> None:
        ...
    @property
    def outlier_neighbours(self) -> int:
        """
        k of the mean-distance statistic
        """
    @outlier_neighbours.setter
    def outlier_neighbours(self, arg0: typing.Any) -> None:
        ...
    @property
    def outlier_std_ratio(self) -> float:
        """
        drop points whose mean k-distance exceeds mean + ratio * std
        """
    @outlier_std_ratio.setter
    def outlier_std_ratio(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_distance(self) -> float:
        """
        m: RANSAC inlier threshold
        """
    @plane_distance.setter
    def plane_distance(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_max_iterations(self) -> int:
        """
        RANSAC iterations
        """
    @plane_max_iterations.setter
    def plane_max_iterations(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_min_fraction(self) -> float:
        """
        fraction of the cleaned points a plane needs to count as the support
        """
    @plane_min_fraction.setter
    def plane_min_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def remove_below_plane(self) -> bool:
        """
        also drop points on the far side of the plane from the object
        """
    @remove_below_plane.setter
    def remove_below_plane(self, arg0: typing.Any) -> None:
        ...
    @property
    def remove_outliers(self) -> bool:
        """
        PCL StatisticalOutlierRemoval
        """
    @remove_outliers.setter
    def remove_outliers(self, arg0: typing.Any) -> None:
        ...
    @property
    def remove_plane(self) -> bool:
        """
        find the dominant plane by RANSAC and remove it
        """
    @remove_plane.setter
    def remove_plane(self, arg0: typing.Any) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seeds RANSAC (None: 0)
        """
    @seed.setter
    def seed(self, arg1: typing.Any) -> None:
        ...
    @property
    def voxel_size(self) -> float:
        """
        m: voxel-grid leaf size, 0 = off (demonstration and query clouds must share it)
        """
    @voxel_size.setter
    def voxel_size(self, arg0: typing.Any) -> None:
        ...
class CleanupResult:
    """
    The object points of a scene and the support plane.
    """
    def __repr__(self) -> str:
        ...
    @property
    def indices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (N) input row of every point (-1 after voxel averaging)
        """
    @property
    def n_after_crop(self) -> int:
        ...
    @property
    def n_after_outliers(self) -> int:
        ...
    @property
    def n_after_voxel(self) -> int:
        ...
    @property
    def n_input(self) -> int:
        ...
    @property
    def n_output(self) -> int:
        ...
    @property
    def n_plane_inliers(self) -> int:
        ...
    @property
    def plane(self) -> typing.Any:
        """
        [a, b, c, d] of a x + b y + c z + d = 0, (a, b, c) unit towards the object; None if none found
        """
    @property
    def plane_found(self) -> bool:
        ...
    @property
    def points(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (N, 3) object points (m)
        """
    @property
    def seconds(self) -> float:
        ...
    @property
    def sources(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (N) input row whose per-point data (viewpoint, camera) every point carries: its own, or for a
        voxel centroid the input point nearest to it in its voxel; index per-point arrays with it
        """
class SegmentationSettings:
    """
    The scene model (segment_scene): support plane rule, table cut, outliers, clusters.
    
    Settings: settings= a SegmentationSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      voxel_size = 0.003: m: voxel-grid leaf size, 0 = off (CleanupSettings')
      plane_distance = 0.005: m: RANSAC inlier threshold
      plane_max_iterations = 1000: RANSAC iterations per candidate
      seed = 0: seeds RANSAC (None: 0)
      find_plane = True: search for the support plane (false: objects only)
      plane_candidates = 3: planes tried, each on the points the previous ones left
      plane_min_fraction = 0.05: rule 1: fraction of the voxelised points a candidate holds
      plane_behind_distance = 0.01: m, rule 3: how far behind the plane a point counts as behind it
      plane_max_behind_fraction = 0.05: rule 3: fraction of all points allowed behind the plane
      plane_margin = 0.01: m, rule 4: how far the plane's inliers must reach beyond the objects' footprint
      table_clearance = 0.005: m: points at most this far above the support plane (or behind it) are the table
      remove_outliers = True: statistical outlier removal on the object points
      outlier_neighbours = 20: k of the mean-distance statistic
      outlier_std_ratio = 2.0: drop points whose mean k-distance exceeds mean + ratio * std
      cluster_tolerance = 0.006: m: object points closer than this are one object (Euclidean clusters)
      min_cluster_size = 20: smaller clusters are noise, dropped
      max_cluster_size = 0: larger clusters are dropped; 0 = no limit
      merge_seen_through = True: a cluster seen through a larger one joins it (a container's inside seen over its rim)
      merge_through_fraction = 0.2: fraction of a cluster's lines of sight that must cross the larger one's envelope
      merge_inset = 0.006: m: the larger cluster's envelope is inset by this
      join_occluded = True: clusters whose gap the view leaves unseen (a shadow between them) join: pieces of one object
      join_max_gap = 0.03: m, join rule 1: clusters farther apart never join
      join_seen_margin = 0.005: m, join rule 2: the gap was seen empty when the views saw more than this beyond it (median)
      join_max_size = 0.15: m, join rule 3: the joined cluster's largest principal-box side
      split_touching = True: a cluster is cut along its concave creases into the objects touching in it (the split rule)
      split_voxel_resolution = 0.004: m: the split rule's supervoxel voxel (at least voxel_size)
      split_seed_resolution = 0.015: m: the split rule's supervoxel seed spacing
      split_concavity_tolerance = 0.35: rad: a crease less concave than this is no cut (LCCP)
      split_min_points = 150: a split piece with fewer points goes back to the neighbour it touches most
      split_max_size = 0.15: m: one object's largest principal-box side; only larger clusters are cut, and pieces re-join within it
      split_named_max_size = 0.12: m: with a point target, its segment is tried again by the split rule gated at this size (split_object_near)
      visibility_tolerance = 0.008: m: Segmentation.visibility's surface_tolerance (within this of the observed surface is Surface)
      visibility_resolution = 0.005: rad: the bin of Segmentation.visibility's range images (VisibilitySettings.angular_resolution)
      visibility_median_window = 1: px: segment_depth's visibility model keeps the depth image median-filtered over (2 r + 1)^2 pixels
    (0: as it is), against lone outline pixels that see through an object
      image_stride = 0: px: segment_depth's block side, 0 = the largest within half a voxel_size at the median depth
      plane_image_stride = 4: px: segment_depth's block side for the support plane's search (at most image_stride: those)
      workspace = []: m: the world-frame box [x_min, y_min, z_min, x_max, y_max, z_max] the input is cropped to first; [] = none
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('voxel_size', 'plane_distance', 'plane_max_iterations', 'seed', 'find_plane', 'plane_candidates', 'plane_min_fraction', 'plane_behind_distance', 'plane_max_behind_fraction', 'plane_margin', 'table_clearance', 'remove_outliers', 'outlier_neighbours', 'outlier_std_ratio', 'cluster_tolerance', 'min_cluster_size', 'max_cluster_size', 'merge_seen_through', 'merge_through_fraction', 'merge_inset', 'join_occluded', 'join_max_gap', 'join_seen_margin', 'join_max_size', 'split_touching', 'split_voxel_resolution', 'split_seed_resolution', 'split_concavity_tolerance', 'split_min_points', 'split_max_size', 'split_named_max_size', 'visibility_tolerance', 'visibility_resolution', 'visibility_median_window', 'image_stride', 'plane_image_stride', 'workspace')
    def __copy__(self) -> SegmentationSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> SegmentationSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (voxel_size, plane_distance, plane_max_iterations, seed, find_plane, plane_candidates, plane_min_fraction, plane_behind_distance, plane_max_behind_fraction, plane_margin, table_clearance, remove_outliers, outlier_neighbours, outlier_std_ratio, cluster_tolerance, min_cluster_size, max_cluster_size, merge_seen_through, merge_through_fraction, merge_inset, join_occluded, join_max_gap, join_seen_margin, join_max_size, split_touching, split_voxel_resolution, split_seed_resolution, split_concavity_tolerance, split_min_points, split_max_size, split_named_max_size, visibility_tolerance, visibility_resolution, visibility_median_window, image_stride, plane_image_stride, workspace); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def cluster_tolerance(self) -> float:
        """
        m: object points closer than this are one object (Euclidean clusters)
        """
    @cluster_tolerance.setter
    def cluster_tolerance(self, arg0: typing.Any) -> None:
        ...
    @property
    def find_plane(self) -> bool:
        """
        search for the support plane (false: objects only)
        """
    @find_plane.setter
    def find_plane(self, arg0: typing.Any) -> None:
        ...
    @property
    def image_stride(self) -> int:
        """
        px: segment_depth's block side, 0 = the largest within half a voxel_size at the median depth
        """
    @image_stride.setter
    def image_stride(self, arg0: typing.Any) -> None:
        ...
    @property
    def join_max_gap(self) -> float:
        """
        m, join rule 1: clusters farther apart never join
        """
    @join_max_gap.setter
    def join_max_gap(self, arg0: typing.Any) -> None:
        ...
    @property
    def join_max_size(self) -> float:
        """
        m, join rule 3: the joined cluster's largest principal-box side
        """
    @join_max_size.setter
    def join_max_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def join_occluded(self) -> bool:
        """
        clusters whose gap the view leaves unseen (a shadow between them) join: pieces of one object
        """
    @join_occluded.setter
    def join_occluded(self, arg0: typing.Any) -> None:
        ...
    @property
    def join_seen_margin(self) -> float:
        """
        m, join rule 2: the gap was seen empty when the views saw more than this beyond it (median)
        """
    @join_seen_margin.setter
    def join_seen_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_cluster_size(self) -> int:
        """
        larger clusters are dropped; 0 = no limit
        """
    @max_cluster_size.setter
    def max_cluster_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def merge_inset(self) -> float:
        """
        m: the larger cluster's envelope is inset by this
        """
    @merge_inset.setter
    def merge_inset(self, arg0: typing.Any) -> None:
        ...
    @property
    def merge_seen_through(self) -> bool:
        """
        a cluster seen through a larger one joins it (a container's inside seen over its rim)
        """
    @merge_seen_through.setter
    def merge_seen_through(self, arg0: typing.Any) -> None:
        ...
    @property
    def merge_through_fraction(self) -> float:
        """
        fraction of a cluster's lines of sight that must cross the larger one's envelope
        """
    @merge_through_fraction.setter
    def merge_through_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_cluster_size(self) -> int:
        """
        smaller clusters are noise, dropped
        """
    @min_cluster_size.setter
    def min_cluster_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def outlier_neighbours(self) -> int:
        """
        k of the mean-distance statistic
        """
    @outlier_neighbours.setter
    def outlier_neighbours(self, arg0: typing.Any) -> None:
        ...
    @property
    def outlier_std_ratio(self) -> float:
        """
        drop points whose mean k-distance exceeds mean + ratio * std
        """
    @outlier_std_ratio.setter
    def outlier_std_ratio(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_behind_distance(self) -> float:
        """
        m, rule 3: how far behind the plane a point counts as behind it
        """
    @plane_behind_distance.setter
    def plane_behind_distance(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_candidates(self) -> int:
        """
        planes tried, each on the points the previous ones left
        """
    @plane_candidates.setter
    def plane_candidates(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_distance(self) -> float:
        """
        m: RANSAC inlier threshold
        """
    @plane_distance.setter
    def plane_distance(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_image_stride(self) -> int:
        """
        px: segment_depth's block side for the support plane's search (at most image_stride: those)
        """
    @plane_image_stride.setter
    def plane_image_stride(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_margin(self) -> float:
        """
        m, rule 4: how far the plane's inliers must reach beyond the objects' footprint
        """
    @plane_margin.setter
    def plane_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_max_behind_fraction(self) -> float:
        """
        rule 3: fraction of all points allowed behind the plane
        """
    @plane_max_behind_fraction.setter
    def plane_max_behind_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_max_iterations(self) -> int:
        """
        RANSAC iterations per candidate
        """
    @plane_max_iterations.setter
    def plane_max_iterations(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_min_fraction(self) -> float:
        """
        rule 1: fraction of the voxelised points a candidate holds
        """
    @plane_min_fraction.setter
    def plane_min_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def remove_outliers(self) -> bool:
        """
        statistical outlier removal on the object points
        """
    @remove_outliers.setter
    def remove_outliers(self, arg0: typing.Any) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seeds RANSAC (None: 0)
        """
    @seed.setter
    def seed(self, arg1: typing.Any) -> None:
        ...
    @property
    def split_concavity_tolerance(self) -> float:
        """
        rad: a crease less concave than this is no cut (LCCP)
        """
    @split_concavity_tolerance.setter
    def split_concavity_tolerance(self, arg0: typing.Any) -> None:
        ...
    @property
    def split_max_size(self) -> float:
        """
        m: one object's largest principal-box side; only larger clusters are cut, and pieces re-join within it
        """
    @split_max_size.setter
    def split_max_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def split_min_points(self) -> int:
        """
        a split piece with fewer points goes back to the neighbour it touches most
        """
    @split_min_points.setter
    def split_min_points(self, arg0: typing.Any) -> None:
        ...
    @property
    def split_named_max_size(self) -> float:
        """
        m: with a point target, its segment is tried again by the split rule gated at this size (split_object_near)
        """
    @split_named_max_size.setter
    def split_named_max_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def split_seed_resolution(self) -> float:
        """
        m: the split rule's supervoxel seed spacing
        """
    @split_seed_resolution.setter
    def split_seed_resolution(self, arg0: typing.Any) -> None:
        ...
    @property
    def split_touching(self) -> bool:
        """
        a cluster is cut along its concave creases into the objects touching in it (the split rule)
        """
    @split_touching.setter
    def split_touching(self, arg0: typing.Any) -> None:
        ...
    @property
    def split_voxel_resolution(self) -> float:
        """
        m: the split rule's supervoxel voxel (at least voxel_size)
        """
    @split_voxel_resolution.setter
    def split_voxel_resolution(self, arg0: typing.Any) -> None:
        ...
    @property
    def table_clearance(self) -> float:
        """
        m: points at most this far above the support plane (or behind it) are the table
        """
    @table_clearance.setter
    def table_clearance(self, arg0: typing.Any) -> None:
        ...
    @property
    def visibility_median_window(self) -> int:
        """
        px: segment_depth's visibility model keeps the depth image median-filtered over (2 r + 1)^2 pixels
        (0: as it is), against lone outline pixels that see through an object
        """
    @visibility_median_window.setter
    def visibility_median_window(self, arg0: typing.Any) -> None:
        ...
    @property
    def visibility_resolution(self) -> float:
        """
        rad: the bin of Segmentation.visibility's range images (VisibilitySettings.angular_resolution)
        """
    @visibility_resolution.setter
    def visibility_resolution(self, arg0: typing.Any) -> None:
        ...
    @property
    def visibility_tolerance(self) -> float:
        """
        m: Segmentation.visibility's surface_tolerance (within this of the observed surface is Surface)
        """
    @visibility_tolerance.setter
    def visibility_tolerance(self, arg0: typing.Any) -> None:
        ...
    @property
    def voxel_size(self) -> float:
        """
        m: voxel-grid leaf size, 0 = off (CleanupSettings')
        """
    @voxel_size.setter
    def voxel_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def workspace(self) -> typing.Any:
        """
        m: the world-frame box [x_min, y_min, z_min, x_max, y_max, z_max] the input is cropped to first; [] = none
        """
    @workspace.setter
    def workspace(self, arg1: typing.Any) -> None:
        ...
class SceneObject:
    """
    One object of a segmented scene: a Euclidean cluster above the plane.
    """
    @property
    def centroid(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) m
        """
    @property
    def index(self) -> int:
        """
        its label and its place in Segmentation.objects
        """
    @property
    def n_points(self) -> int:
        ...
    @property
    def obb_center(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) m: centre of the oriented bounding box
        """
    @property
    def obb_extents(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) m: side lengths along those axes
        """
    @property
    def obb_rotation(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        (3, 3): columns the box's axes by decreasing variance, right-handed
        """
    @property
    def rows(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (n) its rows of Segmentation.points
        """
class PlaneCandidate:
    """
    What the support plane rule saw of one RANSAC plane.
    """
    @property
    def accepted(self) -> bool:
        ...
    @property
    def behind_fraction(self) -> float:
        """
        rule 3
        """
    @property
    def camera_height(self) -> float:
        """
        m, rule 2: mean camera height above it
        """
    @property
    def inlier_fraction(self) -> float:
        """
        rule 1
        """
    @property
    def margin(self) -> float:
        """
        m, rule 4 (NaN when not judged, inf with no object)
        """
    @property
    def n_inliers(self) -> int:
        ...
    @property
    def plane(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 1]"]:
        """
        [a, b, c, d], (a, b, c) unit towards the cameras
        """
    @property
    def reason(self) -> str:
        """
        why it was refused, in words (empty when accepted)
        """
    @property
    def refused_by(self) -> int:
        """
        the rule (1-4) that refused it; 0 when accepted
        """
class Segmentation:
    """
    The support plane and the objects of a scene cloud (segment_scene).
    """
    @property
    def candidates(self) -> list[PlaneCandidate]:
        """
        the support rule's figures, in the order found
        """
    @property
    def dropped(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (K, 3) the points above the table the clean-up dropped (outliers, small clusters; voxelised)
        """
    @property
    def labels(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (M) object index of every point
        """
    @property
    def n_after_voxel(self) -> int:
        ...
    @property
    def n_input(self) -> int:
        ...
    @property
    def n_joined(self) -> int:
        """
        clusters joined to another (a shadow between them)
        """
    @property
    def n_merged(self) -> int:
        """
        clusters joined to a larger one (seen through it)
        """
    @property
    def n_outliers(self) -> int:
        ...
    @property
    def n_output(self) -> int:
        ...
    @property
    def n_plane(self) -> int:
        """
        dropped as the table
        """
    @property
    def n_small_clusters(self) -> int:
        """
        points of clusters dropped as noise
        """
    @property
    def n_split(self) -> int:
        """
        clusters cut off another by the split rule
        """
    @property
    def objects(self) -> list[SceneObject]:
        """
        by decreasing point count, ties by centroid x, y, z
        """
    @property
    def plane(self) -> typing.Any:
        """
        [a, b, c, d], (a, b, c) unit towards the cameras; None without a plane
        """
    @property
    def plane_found(self) -> bool:
        ...
    @property
    def plane_given(self) -> bool:
        ...
    @property
    def points(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (M, 3) the objects' points (voxelised), grouped by object
        """
    @property
    def seconds(self) -> float:
        """
        wall time of the whole segmentation
        """
    @property
    def sources(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (M) input row whose per-point data every point carries
        """
    @property
    def step_seconds(self) -> dict:
        """
        wall time (s) of each step: voxel, visibility, candidates (RANSAC, rules 1-3), table_cut, outliers, clusters (and rule 4), merge, join, objects; the middle three summed over the candidates tried
        """
    @property
    def visibility(self) -> typing.Any:
        """
        VisibilityModel of what the cameras saw (one view per distinct viewpoint); None without viewpoints
        """
class SurfaceFeatureSettings:
    """
    Normals, curvatures and frames (compute_surface_features).
    
    Settings: settings= a SurfaceFeatureSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      radius = 0.01: m: neighbourhood radius of normals and curvatures (paper: 1 cm)
      min_neighbours = 10: points with fewer neighbours within radius (itself included) are dropped
      min_anisotropy = 0.25: the principal direction is x only where (k1 - k2) / k1 >= min_anisotropy ...
      flat_curvature = 0.0001: ... and k1 >= flat_curvature (dimensionless)
      orientation = 'auto': how normals are turned outward: auto | viewpoint | propagate | centroid | given
      orientation_neighbours = 10: k of the propagation graph
      n_threads = 0: 0 = OpenMP's default, else 1..256; results do not depend on it
      max_neighbours = 5000: a neighbourhood holding more points is refused (voxel-downsample such a dense cloud first); 0: no cap
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('radius', 'min_neighbours', 'min_anisotropy', 'flat_curvature', 'orientation', 'orientation_neighbours', 'n_threads', 'max_neighbours')
    def __copy__(self) -> SurfaceFeatureSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> SurfaceFeatureSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (radius, min_neighbours, min_anisotropy, flat_curvature, orientation, orientation_neighbours, n_threads, max_neighbours); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def flat_curvature(self) -> float:
        """
        ... and k1 >= flat_curvature (dimensionless)
        """
    @flat_curvature.setter
    def flat_curvature(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_neighbours(self) -> int:
        """
        a neighbourhood holding more points is refused (voxel-downsample such a dense cloud first); 0: no cap
        """
    @max_neighbours.setter
    def max_neighbours(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_anisotropy(self) -> float:
        """
        the principal direction is x only where (k1 - k2) / k1 >= min_anisotropy ...
        """
    @min_anisotropy.setter
    def min_anisotropy(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_neighbours(self) -> int:
        """
        points with fewer neighbours within radius (itself included) are dropped
        """
    @min_neighbours.setter
    def min_neighbours(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_threads(self) -> int:
        """
        0 = OpenMP's default, else 1..256; results do not depend on it
        """
    @n_threads.setter
    def n_threads(self, arg0: typing.Any) -> None:
        ...
    @property
    def orientation(self) -> str:
        """
        how normals are turned outward: auto | viewpoint | propagate | centroid | given
        """
    @orientation.setter
    def orientation(self, arg1: typing.Any) -> None:
        ...
    @property
    def orientation_neighbours(self) -> int:
        """
        k of the propagation graph
        """
    @orientation_neighbours.setter
    def orientation_neighbours(self, arg0: typing.Any) -> None:
        ...
    @property
    def radius(self) -> float:
        """
        m: neighbourhood radius of normals and curvatures (paper: 1 cm)
        """
    @radius.setter
    def radius(self, arg0: typing.Any) -> None:
        ...
class SurfaceCloud:
    """
    The object representation O(v, r): points, outward normals, curvatures [k1, k2] and frames.
    """
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def curvatures(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        """
        (N, 2) PCL's [pc1, pc2] = [k1, k2], k1 >= k2 >= 0
        """
    @property
    def frame_ambiguity(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N) radians a sampler may rotate the frame about z: pi exp(-100 ((k1 - k2) / k1)^2)
        """
    @property
    def frames(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 7]"]:
        """
        (N, 7) T_world_feature [x, y, z, qx, qy, qz, qw]: z = normal, x = principal direction, y = z x x
        """
    @property
    def indices(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (N) input row of every kept point
        """
    @property
    def isotropic(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        (N) True where x came from the deterministic rule (k1 ~ k2 or flat)
        """
    @property
    def n_dropped(self) -> int:
        """
        points without a stable neighbourhood
        """
    @property
    def n_input(self) -> int:
        ...
    @property
    def neighbours(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (N) neighbours within radius, itself included
        """
    @property
    def normals(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (N, 3) unit, outward
        """
    @property
    def orientation(self) -> str:
        """
        rule that oriented the normals
        """
    @property
    def points(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (N, 3) metres
        """
    @property
    def radius(self) -> float:
        ...
    @property
    def seconds_curvatures(self) -> float:
        """
        s
        """
    @property
    def seconds_normals(self) -> float:
        """
        s
        """
    @property
    def seconds_orientation(self) -> float:
        """
        s
        """
    @property
    def seconds_total(self) -> float:
        """
        s
        """
    @property
    def timings(self) -> dict:
        """
        seconds per stage
        """
class PinholeCamera:
    """
    Pinhole intrinsics of a depth camera (px), no distortion. Sensor frame: x right, y down, z forward;
    pixel (u, v) = (column, row), pixel centres at integer coordinates.
    """
    __hash__: typing.ClassVar[None] = None
    @staticmethod
    def fit(points: typing.Any, height: typing.Any = None, width: typing.Any = None, max_rms_px: typing.Any = 0.5) -> PinholeFit:
        """
        The intrinsics of an organized cloud in the sensor frame, (H, W, 3) or (H * W, 3) with height and width (NaN = no return), by least squares over its valid pixels; ValueError when the RMS reprojection residual exceeds max_rms_px (not a pinhole image in the sensor frame).
        """
    def __eq__(self, arg0: PinholeCamera) -> bool:
        ...
    def __getstate__(self) -> tuple[float, float, float, float, int, int]:
        ...
    def __init__(self, fx: typing.Any, fy: typing.Any, cx: typing.Any, cy: typing.Any, width: typing.Any, height: typing.Any) -> None:
        """
        ValueError unless fx, fy > 0, cx, cy finite, width, height >= 1.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def back_project(self, depth: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        The organized cloud (H, W, 3) in the sensor frame of a depth image (H, W) in metres along z; NaN, 0 and inf are no return (NaN points), a negative depth is a ValueError.
        """
    def check_image(self, depth: typing.Any) -> int:
        """
        The number of pixels of a depth image (H, W) with a return; ValueError for an image of another size or a negative depth.
        """
    def project(self, points: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, 2) pixel coordinates (u, v) of points (N, 3) in the sensor frame; NaN where z <= 0.
        """
    @property
    def K(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
        """
        (3, 3) [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]
        """
    @property
    def cx(self) -> float:
        ...
    @property
    def cy(self) -> float:
        ...
    @property
    def fx(self) -> float:
        ...
    @property
    def fy(self) -> float:
        ...
    @property
    def height(self) -> int:
        ...
    @property
    def width(self) -> int:
        ...
class PinholeFit:
    """
    Intrinsics fitted to an organized cloud (PinholeCamera.fit).
    """
    @property
    def camera(self) -> PinholeCamera:
        ...
    @property
    def n_valid(self) -> int:
        """
        pixels with a point
        """
    @property
    def rms_px(self) -> float:
        """
        px: RMS reprojection residual over the valid pixels
        """
class SpaceState(enum.IntEnum):
    """
    What the views saw of a point, the codes VisibilityModel.classify returns: SeenFree (0, in front of the observed surface along the point's ray), Surface (1, within surface_tolerance of it), Unseen (2, behind it, outside every image, or on a ray with no return).
    """
    SeenFree: typing.ClassVar[SpaceState]
    Surface: typing.ClassVar[SpaceState]
    Unseen: typing.ClassVar[SpaceState]
    _member_map_: typing.ClassVar[dict]
    _member_names_: typing.ClassVar[list] = ['SeenFree', 'Surface', 'Unseen']
    _unhashable_values_: typing.ClassVar[list] = list()
    _use_args_: typing.ClassVar[bool] = True
    _value2member_map_: typing.ClassVar[dict]
    _member_type_ = builtins.int
    @staticmethod
    def _generate_next_value_(name, start, count, last_values):
        """
                Generate the next value when not given.
        
                name: the name of the member
                start: the initial start value or None
                count: the number of existing members
                last_values: the list of values assigned
                
        """
    @staticmethod
    def _new_member_(type, *args, **kwargs):
        """
        Create and return a new object.  See help(type) for accurate signature.
        """
    @classmethod
    def __new__(cls, value):
        ...
    def __format__(self, format_spec):
        ...
    def _value_repr_(self):
        """
        Return repr(self).
        """
class VisibilitySettings:
    """
    The visibility model (VisibilityModel).
    
    Settings: settings= a VisibilitySettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      surface_tolerance = 0.005: m: within this of the observed surface along the ray is Surface (>= 0)
      angular_resolution = 0.005: rad: bin size of from_points' spherical range image, in (0, 0.5]
      no_return_is_free = False: a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)
      max_fit_rms = 0.5: px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on
      max_pixels = 10000000: the largest image one view may hold (pixels)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('surface_tolerance', 'angular_resolution', 'no_return_is_free', 'max_fit_rms', 'max_pixels')
    def __copy__(self) -> VisibilitySettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> VisibilitySettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (surface_tolerance, angular_resolution, no_return_is_free, max_fit_rms, max_pixels); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def angular_resolution(self) -> float:
        """
        rad: bin size of from_points' spherical range image, in (0, 0.5]
        """
    @angular_resolution.setter
    def angular_resolution(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_fit_rms(self) -> float:
        """
        px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on
        """
    @max_fit_rms.setter
    def max_fit_rms(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_pixels(self) -> int:
        """
        the largest image one view may hold (pixels)
        """
    @max_pixels.setter
    def max_pixels(self, arg0: typing.Any) -> None:
        ...
    @property
    def no_return_is_free(self) -> bool:
        """
        a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)
        """
    @no_return_is_free.setter
    def no_return_is_free(self, arg0: typing.Any) -> None:
        ...
    @property
    def surface_tolerance(self) -> float:
        """
        m: within this of the observed surface along the ray is Surface (>= 0)
        """
    @surface_tolerance.setter
    def surface_tolerance(self, arg0: typing.Any) -> None:
        ...
class VisibilityModel:
    """
    What the cameras saw, as space: each point SeenFree, Surface or Unseen, from one image per view (O(1) per
    point). Views combine by: Surface if any view has the point within surface_tolerance of its surface; else
    SeenFree if any view sees it in front; else Unseen. The rule: include/graspmix/perception/visibility.hpp.
    """
    @staticmethod
    def from_depth(depth: typing.Any, camera: PinholeCamera, T_world_camera: typing.Any, *, settings: typing.Any = None, **kwargs) -> VisibilityModel:
        """
        One view from a depth image (H, W) in metres along z (NaN, 0, inf: no return) of `camera`, posed at
        T_world_camera [x, y, z, qx, qy, qz, qw] (a unit quaternion).
        Settings: settings= a VisibilitySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          surface_tolerance = 0.005: m: within this of the observed surface along the ray is Surface (>= 0)
          angular_resolution = 0.005: rad: bin size of from_points' spherical range image, in (0, 0.5]
          no_return_is_free = False: a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)
          max_fit_rms = 0.5: px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on
          max_pixels = 10000000: the largest image one view may hold (pixels)
        """
    @staticmethod
    def from_organized(points: typing.Any, T_world_camera: typing.Any, *, height: typing.Any = None, width: typing.Any = None, settings: typing.Any = None, **kwargs) -> VisibilityModel:
        """
        One view from an organized cloud in the sensor frame (x right, y down, z forward; NaN = no return),
        (H, W, 3) or (H * W, 3) with height and width; its pinhole intrinsics are fitted (views[i]['camera']).
        Settings: settings= a VisibilitySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          surface_tolerance = 0.005: m: within this of the observed surface along the ray is Surface (>= 0)
          angular_resolution = 0.005: rad: bin size of from_points' spherical range image, in (0, 0.5]
          no_return_is_free = False: a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)
          max_fit_rms = 0.5: px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on
          max_pixels = 10000000: the largest image one view may hold (pixels)
        """
    @staticmethod
    def from_points(points: typing.Any, viewpoint: typing.Any, *, settings: typing.Any = None, **kwargs) -> VisibilityModel:
        """
        One view from an unorganized cloud (N, 3) in the world frame seen from viewpoint (3,): a spherical range
        image (pcl::RangeImage) at angular_resolution, each bin its nearest point; empty bins are unseen.
        Settings: settings= a VisibilitySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          surface_tolerance = 0.005: m: within this of the observed surface along the ray is Surface (>= 0)
          angular_resolution = 0.005: rad: bin size of from_points' spherical range image, in (0, 0.5]
          no_return_is_free = False: a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)
          max_fit_rms = 0.5: px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on
          max_pixels = 10000000: the largest image one view may hold (pixels)
        """
    @staticmethod
    def from_views(points: typing.Any, viewpoints: typing.Any, *, settings: typing.Any = None, **kwargs) -> VisibilityModel:
        """
        Every view of an unorganized cloud (N, 3) in the world frame: viewpoints (3,) for one camera or (N, 3),
        the camera that saw each point; the points of each distinct viewpoint make one from_points view.
        Settings: settings= a VisibilitySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          surface_tolerance = 0.005: m: within this of the observed surface along the ray is Surface (>= 0)
          angular_resolution = 0.005: rad: bin size of from_points' spherical range image, in (0, 0.5]
          no_return_is_free = False: a depth pixel with no return (NaN, 0, inf) sees its whole ray free (else it says nothing)
          max_fit_rms = 0.5: px: from_organized refuses a cloud its fitted intrinsics leave a larger RMS residual on
          max_pixels = 10000000: the largest image one view may hold (pixels)
        """
    def __init__(self, *, settings: typing.Any = None, **kwargs) -> None:
        """
        A model of no view (every point Unseen), to add views to (add_view) built with the same settings.
        """
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def add_view(self, other: VisibilityModel) -> None:
        """
        Adds the views of another model built with equal settings (ValueError otherwise).
        """
    def classify(self, points: typing.Any) -> numpy.typing.NDArray[numpy.uint8]:
        """
        (N,) uint8 SpaceState of points (N, 3) or (3,): 0 SeenFree, 1 Surface, 2 Unseen.
        """
    def signed_distance(self, points: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,) m along each point's ray to the observed surface, positive in front, chosen over the views by the
        classification's rule (|d| <= surface_tolerance: Surface, d > it: SeenFree, else Unseen); inf on a
        no-return ray taken as free, NaN where no view says anything.
        """
    @property
    def n_views(self) -> int:
        ...
    @property
    def settings(self) -> VisibilitySettings:
        ...
    @property
    def views(self) -> list:
        """
        Per view: kind ('pinhole' | 'spherical'), T_world_sensor (7,), camera (PinholeCamera or None), width,
        height, n_returns, angular_resolution (rad), fit_rms_px, seconds.
        """
class CompletionKind(enum.IntEnum):
    """
    Which hypothesis completed an object (complete_object): None_ (0, none accepted), Mirror (1, a vertical plane), Rotation (2, a vertical axis), Extrusion (3, walls down to the table).
    """
    Extrusion: typing.ClassVar[CompletionKind]
    Mirror: typing.ClassVar[CompletionKind]
    None_: typing.ClassVar[CompletionKind]
    Rotation: typing.ClassVar[CompletionKind]
    _member_map_: typing.ClassVar[dict]
    _member_names_: typing.ClassVar[list] = ['None_', 'Mirror', 'Rotation', 'Extrusion']
    _unhashable_values_: typing.ClassVar[list] = list()
    _use_args_: typing.ClassVar[bool] = True
    _value2member_map_: typing.ClassVar[dict]
    _member_type_ = builtins.int
    @staticmethod
    def _generate_next_value_(name, start, count, last_values):
        """
                Generate the next value when not given.
        
                name: the name of the member
                start: the initial start value or None
                count: the number of existing members
                last_values: the list of values assigned
                
        """
    @staticmethod
    def _new_member_(type, *args, **kwargs):
        """
        Create and return a new object.  See help(type) for accurate signature.
        """
    @classmethod
    def __new__(cls, value):
        ...
    def __format__(self, format_spec):
        ...
    def _value_repr_(self):
        """
        Return repr(self).
        """
class CompletionSettings:
    """
    The completion of an object's unseen side.
    
    Settings: settings= a CompletionSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      spacing = 0.003: m: the completed points' spacing, the profile's and footprint's bins
      max_free_fraction = 0.05: a hypothesis with more of its points in seen-free space is refused, in [0, 1]
      min_unseen_fraction = 0.15: a hypothesis with less of its points in unseen space is refused, in [0, 1]
      free_weight = 4.0: score = surface_fraction - free_weight * free_fraction (>= 0)
      mirror_angle_step = 0.07: rad: the step between mirror planes' orientations around each principal axis
      mirror_angle_steps = 3: orientations each side of each principal axis (0..20)
      mirror_max_depth = 0.05: m: a mirror plane lies at most this far behind the footprint's far edge
      circle_max_rms = 0.003: m: a rotation needs the outline's inliers within this RMS of their circle
      circle_min_inliers = 0.7: the fraction of the outline within 2 circle_max_rms of its circle for a rotation
      max_radius = 0.25: m: no rotation about a larger circle
      normal_radius = 0.01: m: the neighbourhood of the observed points' normals (> spacing)
      max_scoring_points = 160: points each hypothesis is scored on (>= 16)
      border_margin = 2.0: px: an observed point this close to a pinhole image's edge sets the border warning
      min_height = 0.005: m: completed points lower than this above the support plane are dropped (the table's clearance)
      rotation_margin = 0.05: the rotation wins unless the best accepted mirror scores more than this above it
      observed_clearance = 0.006: m: no completed point within this of an observed point (the seen surface is not doubled)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('spacing', 'max_free_fraction', 'min_unseen_fraction', 'free_weight', 'mirror_angle_step', 'mirror_angle_steps', 'mirror_max_depth', 'circle_max_rms', 'circle_min_inliers', 'max_radius', 'normal_radius', 'max_scoring_points', 'border_margin', 'min_height', 'rotation_margin', 'observed_clearance')
    def __copy__(self) -> CompletionSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> CompletionSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (spacing, max_free_fraction, min_unseen_fraction, free_weight, mirror_angle_step, mirror_angle_steps, mirror_max_depth, circle_max_rms, circle_min_inliers, max_radius, normal_radius, max_scoring_points, border_margin, min_height, rotation_margin, observed_clearance); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def border_margin(self) -> float:
        """
        px: an observed point this close to a pinhole image's edge sets the border warning
        """
    @border_margin.setter
    def border_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def circle_max_rms(self) -> float:
        """
        m: a rotation needs the outline's inliers within this RMS of their circle
        """
    @circle_max_rms.setter
    def circle_max_rms(self, arg0: typing.Any) -> None:
        ...
    @property
    def circle_min_inliers(self) -> float:
        """
        the fraction of the outline within 2 circle_max_rms of its circle for a rotation
        """
    @circle_min_inliers.setter
    def circle_min_inliers(self, arg0: typing.Any) -> None:
        ...
    @property
    def free_weight(self) -> float:
        """
        score = surface_fraction - free_weight * free_fraction (>= 0)
        """
    @free_weight.setter
    def free_weight(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_free_fraction(self) -> float:
        """
        a hypothesis with more of its points in seen-free space is refused, in [0, 1]
        """
    @max_free_fraction.setter
    def max_free_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_radius(self) -> float:
        """
        m: no rotation about a larger circle
        """
    @max_radius.setter
    def max_radius(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_scoring_points(self) -> int:
        """
        points each hypothesis is scored on (>= 16)
        """
    @max_scoring_points.setter
    def max_scoring_points(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_height(self) -> float:
        """
        m: completed points lower than this above the support plane are dropped (the table's clearance)
        """
    @min_height.setter
    def min_height(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_unseen_fraction(self) -> float:
        """
        a hypothesis with less of its points in unseen space is refused, in [0, 1]
        """
    @min_unseen_fraction.setter
    def min_unseen_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def mirror_angle_step(self) -> float:
        """
        rad: the step between mirror planes' orientations around each principal axis
        """
    @mirror_angle_step.setter
    def mirror_angle_step(self, arg0: typing.Any) -> None:
        ...
    @property
    def mirror_angle_steps(self) -> int:
        """
        orientations each side of each principal axis (0..20)
        """
    @mirror_angle_steps.setter
    def mirror_angle_steps(self, arg0: typing.Any) -> None:
        ...
    @property
    def mirror_max_depth(self) -> float:
        """
        m: a mirror plane lies at most this far behind the footprint's far edge
        """
    @mirror_max_depth.setter
    def mirror_max_depth(self, arg0: typing.Any) -> None:
        ...
    @property
    def normal_radius(self) -> float:
        """
        m: the neighbourhood of the observed points' normals (> spacing)
        """
    @normal_radius.setter
    def normal_radius(self, arg0: typing.Any) -> None:
        ...
    @property
    def observed_clearance(self) -> float:
        """
        m: no completed point within this of an observed point (the seen surface is not doubled)
        """
    @observed_clearance.setter
    def observed_clearance(self, arg0: typing.Any) -> None:
        ...
    @property
    def rotation_margin(self) -> float:
        """
        the rotation wins unless the best accepted mirror scores more than this above it
        """
    @rotation_margin.setter
    def rotation_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def spacing(self) -> float:
        """
        m: the completed points' spacing, the profile's and footprint's bins
        """
    @spacing.setter
    def spacing(self, arg0: typing.Any) -> None:
        ...
class Completion:
    """
    The completed unseen side of one object (complete_object).
    """
    def __repr__(self) -> str:
        ...
    @property
    def hypotheses(self) -> list:
        """
        Every hypothesis scored, the winner first when there is one: dicts of kind, score, free_fraction,
        surface_fraction, unseen_fraction, known_fraction, accepted, plane_or_axis (a mirror's plane [a, b, c, d];
        a rotation's axis foot on the table and radius [x, y, z, r]).
        """
    @property
    def kind(self) -> typing.Any:
        """
        the winner's CompletionKind
        """
    @property
    def normals(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (M, 3) unit normals, out of the object
        """
    @property
    def points(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (M, 3) the completed points only (m, world frame)
        """
    @property
    def score(self) -> float:
        """
        the winner's score (0 for None_)
        """
    @property
    def seconds(self) -> float:
        """
        s, wall time
        """
    @property
    def warning(self) -> str:
        """
        why completion was limited, empty if nothing
        """
class SceneCompletion:
    """
    Every object of a scene completed (complete_scene).
    """
    @property
    def completions(self) -> list[Completion | None]:
        """
        per object, its Completion or None
        """
    @property
    def notes(self) -> list[str]:
        """
        why objects were not completed, and the warnings
        """
    @property
    def seconds(self) -> float:
        """
        s, wall time
        """
class HandLoadSettings:
    """
    How a URDF's meshes are found and loaded (Hand.from_urdf).
    
    Settings: settings= a HandLoadSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      package_dirs = []: extra folders searched for package://name/... meshes (each holds package folders, as in ROS_PACKAGE_PATH)
      load_meshes = True: False: mesh shapes keep only their file names (no geometry)
      approach_snap_deg = 20.0: degrees: the inferred approach axis snaps to the nearest wrist axis within this (Hand.approach_axis)
      same_finger_deg = 45.0: degrees: two chain ends within this across the approach axis lie on one finger (Hand.fingertips)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('package_dirs', 'load_meshes', 'approach_snap_deg', 'same_finger_deg')
    def __copy__(self) -> HandLoadSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> HandLoadSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (package_dirs, load_meshes, approach_snap_deg, same_finger_deg); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def approach_snap_deg(self) -> float:
        """
        degrees: the inferred approach axis snaps to the nearest wrist axis within this (Hand.approach_axis)
        """
    @approach_snap_deg.setter
    def approach_snap_deg(self, arg0: typing.Any) -> None:
        ...
    @property
    def load_meshes(self) -> bool:
        """
        False: mesh shapes keep only their file names (no geometry)
        """
    @load_meshes.setter
    def load_meshes(self, arg0: typing.Any) -> None:
        ...
    @property
    def package_dirs(self) -> list[str]:
        """
        extra folders searched for package://name/... meshes (each holds package folders, as in ROS_PACKAGE_PATH)
        """
    @package_dirs.setter
    def package_dirs(self, arg1: typing.Any) -> None:
        ...
    @property
    def same_finger_deg(self) -> float:
        """
        degrees: two chain ends within this across the approach axis lie on one finger (Hand.fingertips)
        """
    @same_finger_deg.setter
    def same_finger_deg(self, arg0: typing.Any) -> None:
        ...
class Hand:
    """
    A hand as a kinematic tree from a URDF (urdfdom): fk (eq:fk_function) and collision geometry.
    The wrist is the root link; joint_names are the independent joints (mimic joints follow
    value = multiplier * master + offset and are not listed); poses are [x, y, z, qx, qy, qz, qw]
    of the URDF link frames (not inertial frames).
    """
    @staticmethod
    def from_urdf(path: typing.Any, package_dirs: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> Hand:
        """
        Reads a URDF. Mesh files (STL, OBJ, ... via assimp) resolve against the URDF's folder; package://
        paths also against its parents and package_dirs. ValueError names a missing file, malformed XML,
        a URDF without links or with more than 1000, anything urdfdom complains about, and every bad number
        or shape (non-finite, lower > upper limits, zero axis, non-positive size or mesh scale) with the
        link or joint at fault, an unsupported joint or an unreadable mesh.
        Settings: settings= a HandLoadSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          package_dirs = []: extra folders searched for package://name/... meshes (each holds package folders, as in ROS_PACKAGE_PATH)
          load_meshes = True: False: mesh shapes keep only their file names (no geometry)
          approach_snap_deg = 20.0: degrees: the inferred approach axis snaps to the nearest wrist axis within this (Hand.approach_axis)
          same_finger_deg = 45.0: degrees: two chain ends within this across the approach axis lie on one finger (Hand.fingertips)
        """
    @staticmethod
    def from_urdf_string(xml: str, base_dir: typing.Any = '.', package_dirs: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> Hand:
        """
        A hand from URDF text; relative mesh paths resolve against base_dir.
        Settings: settings= a HandLoadSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          package_dirs = []: extra folders searched for package://name/... meshes (each holds package folders, as in ROS_PACKAGE_PATH)
          load_meshes = True: False: mesh shapes keep only their file names (no geometry)
          approach_snap_deg = 20.0: degrees: the inferred approach axis snaps to the nearest wrist axis within this (Hand.approach_axis)
          same_finger_deg = 45.0: degrees: two chain ends within this across the approach axis lie on one finger (Hand.fingertips)
        """
    def __repr__(self) -> str:
        ...
    def all_joint_values(self, joints: typing.Any) -> dict:
        """
        {name: value} for every movable URDF joint, mimic joints resolved (e.g. to drive a simulator).
        """
    def clamp(self, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The configuration clamped into the joint limits.
        """
    def collision_mesh(self, link: str) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"]]:
        """
        (vertices (V, 3), triangles (T, 3)) of all of a link's collision geometry in the link frame
        (cylinders and spheres tessellated).
        """
    def collision_shapes(self, link: str) -> list:
        """
        The <collision> elements of a link as dicts: type (box|cylinder|sphere|mesh), origin (7,) in the link
        frame, and size (box, full sides), radius/length (cylinder, along z), radius (sphere), or file, scale,
        vertices (V, 3, scaled, in the shape frame) and triangles (T, 3) (mesh), with the mesh's convex hull as
        hull_planes (P, 4) [nx, ny, nz, offset] (n . x <= offset inside) and its proxy: an oriented box proxy_box (7,)
        in the shape frame with half extents proxy_half (3,) around the hull, and proxy_growth: every point whose
        largest n . x - offset is g >= 0 or less lies within the box grown by proxy_growth * g; proxy_inner (3,),
        the half extents of a box of the same frame inside the hull (zeros: none).
        """
    def fk(self, T_world_wrist: typing.Any, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        eq:fk_function: (n_links, 7) world poses of every link (link_names order) for a wrist pose (7,)
        and joints (mapping or array in joint_names order). Joint limits are not enforced.
        """
    def fk_batch(self, T_world_wrist: typing.Any, joints: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        fk over N hands: wrists (N, 7), joints (N, n_dofs), a list of mappings, or one configuration for all
        -> (N, n_links, 7).
        """
    def joints_array(self, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        A configuration (mapping or array) as an array in joint_names order.
        """
    def joints_dict(self, joints: typing.Any) -> dict[str, float]:
        """
        A configuration as {joint name: value}.
        """
    def link_index(self, link: str) -> int:
        ...
    def set_grasp_axes(self, approach_axis: typing.Any, fingertips: collections.abc.Sequence[str]) -> None:
        """
        Gives the approach axis (3,) and fingertip links; ValueError naming a bad value.
        """
    def within_limits(self, joints: typing.Any, tolerance: typing.Any = None) -> bool:
        """
        True when every joint is within its limits, up to tolerance (joint units; None: the C++ default of Hand::within_limits).
        """
    @property
    def approach_axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) unit: the approach axis in the wrist frame, from the URDF's <graspmix approach_axis> or inferred (the direction from the wrist to the fingertips, snapped to a wrist axis within approach_snap_deg)
        """
    @property
    def fingertips(self) -> list[str]:
        """
        The fingertip links (link_names order): from the URDF's <graspmix fingertips> or inferred (the distal link of each finger chain)
        """
    @property
    def grasp_axes_source(self) -> str:
        """
        'urdf' (its <graspmix> element), 'inferred' or 'set' (set_grasp_axes)
        """
    @property
    def joint_limits(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (n_dofs, 2) lower, upper (m or rad; +-inf if unbounded).
        """
    @property
    def joint_names(self) -> list[str]:
        """
        Independent joints, the order of joint arrays.
        """
    @property
    def joints(self) -> list:
        """
        Every URDF joint (fixed and mimic included) as dicts, parents before children.
        """
    @property
    def link_names(self) -> list[str]:
        """
        Every link, the wrist (root) first; the order of fk rows.
        """
    @property
    def mimic_joints(self) -> dict:
        """
        name -> (independent joint, multiplier, offset): value = multiplier * joints[master] + offset.
        """
    @property
    def n_dofs(self) -> int:
        ...
    @property
    def n_links(self) -> int:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def root_link(self) -> str:
        ...
    @property
    def source(self) -> str:
        """
        The URDF file it was read from.
        """
class OccupancySettings:
    """
    The occupancy map of a scene from its cameras' rays (OccupancyMap).
    
    Settings: settings= a OccupancySettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      resolution = 0.005: m: cell size (OctoMap's resolution), > 0
      margin = 0.1: m: the objects' bounding box grown by this is the mapped region
      unknown_is_occupied = True: cells no ray reached are obstacles (space the cameras did not see is not free)
      max_cells = 50000000: the dense grid's largest size (cells)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('resolution', 'margin', 'unknown_is_occupied', 'max_cells')
    def __copy__(self) -> OccupancySettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> OccupancySettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (resolution, margin, unknown_is_occupied, max_cells); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def margin(self) -> float:
        """
        m: the objects' bounding box grown by this is the mapped region
        """
    @margin.setter
    def margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_cells(self) -> int:
        """
        the dense grid's largest size (cells)
        """
    @max_cells.setter
    def max_cells(self, arg0: typing.Any) -> None:
        ...
    @property
    def resolution(self) -> float:
        """
        m: cell size (OctoMap's resolution), > 0
        """
    @resolution.setter
    def resolution(self, arg0: typing.Any) -> None:
        ...
    @property
    def unknown_is_occupied(self) -> bool:
        """
        cells no ray reached are obstacles (space the cameras did not see is not free)
        """
    @unknown_is_occupied.setter
    def unknown_is_occupied(self, arg0: typing.Any) -> None:
        ...
class OccupancyMap:
    """
    Free, occupied and unknown space of a scene: OctoMap's ray insertion of every point from its own viewpoint,
    baked into a dense grid over the objects' box grown by a margin (free outside it, and within one cell of
    the support plane). The rule: include/graspmix/grasp/occupancy.hpp.
    """
    @staticmethod
    def from_visibility(visibility: VisibilityModel, objects: typing.Any, plane: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> OccupancyMap:
        """
        The same region and rules from a VisibilityModel's views instead of OctoMap's rays: each cell by its
        centre's state (seen free -> free, surface -> occupied, unseen -> unknown). objects (M, 3): the points
        whose box, grown by margin, is mapped; plane [a, b, c, d] or None.
        """
    def __init__(self, points: typing.Any, viewpoints: typing.Any, objects: typing.Any = None, plane: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> None:
        """
        points (N, 3), the whole cloud; viewpoints (3,) or (N, 3), the camera of each point; objects (M, 3): the
        points whose box (grown by margin) is mapped (None: all points); plane [a, b, c, d] or None.
        Settings: settings= a OccupancySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          resolution = 0.005: m: cell size (OctoMap's resolution), > 0
          margin = 0.1: m: the objects' bounding box grown by this is the mapped region
          unknown_is_occupied = True: cells no ray reached are obstacles (space the cameras did not see is not free)
          max_cells = 50000000: the dense grid's largest size (cells)
        """
    def state(self, points: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.uint8], "[m, 1]"]:
        """
        (N,) uint8 state of each point's cell: 0 free, 1 occupied, 2 unknown (free outside).
        """
    @property
    def dims(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[3, 1]"]:
        """
        (3,) cells along x, y, z.
        """
    @property
    def plane(self) -> typing.Any:
        """
        The support plane, normalised, its normal towards the cameras, or None.
        """
    @property
    def region_max(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) upper corner of the mapped region (m).
        """
    @property
    def region_min(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) lower corner of the mapped region (m).
        """
    @property
    def resolution(self) -> float:
        ...
    @property
    def settings(self) -> OccupancySettings:
        ...
    @property
    def stats(self) -> dict:
        """
        Rays inserted (one per cell and viewpoint; 0 for a map from a visibility model), cells by state, wall time
        (s).
        """
class CollisionSettings:
    """
    The collision expert W(h) (eq:opt_criterion_std_col).
    
    Settings: settings= a CollisionSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      model = 'surface': surface (the cloud's points) | occupancy (an OccupancyMap of what the cameras saw)
      beta = 2000.0: 1/m: log W = -beta * total depth (2000: 0.5 mm of penetration costs one nat)
      point_radius = 0.0: m: cloud points are balls of this radius (>= 0)
      plane_margin = 0.0: m: the support plane is raised by this much (negative: tolerate contact)
      cell_size = 0.0: m: grid cell of the cloud index; 0 picks one from the cloud
      orient_plane = True: flip the plane's sign so the cloud's mean lies on its free (positive) side
      contact_tolerance = 0.001: m: depths up to this count as touching, not penetrating (a cloud is a noisy surface)
      inside_weight = 0.0: m per point: each cloud point inside a link adds this much to the total depth (0: depths alone)
      reference_area = 0.0001: m^2: the occupancy model charges a link's volume in blocked cells divided by this
      volume = True: keep the hand out of the objects' solid volume too (columns from the plane up to the points: solid_volume)
      volume_resolution = 0.005: m: the solid volume's cell, > 0
      unseen_weight = 0.1: a link's volume in the unknown cells of a map of what the cameras saw (the occupancy model's, or the
    surface model's unseen map) outside the solid volume is charged at this weight (soft: in W, not in
    collision_free; an occupancy map with OccupancySettings.unknown_is_occupied charges them in full instead)
      unseen_margin = 0.01: m: with the volume, unseen space within this of it is not charged (>= 0)
      occupied_cells = True: the occupancy model charges the volume in occupied (seen surface) cells; False: their points' depths only
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('model', 'beta', 'point_radius', 'plane_margin', 'cell_size', 'orient_plane', 'contact_tolerance', 'inside_weight', 'reference_area', 'volume', 'volume_resolution', 'unseen_weight', 'unseen_margin', 'occupied_cells')
    def __copy__(self) -> CollisionSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> CollisionSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (model, beta, point_radius, plane_margin, cell_size, orient_plane, contact_tolerance, inside_weight, reference_area, volume, volume_resolution, unseen_weight, unseen_margin, occupied_cells); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def beta(self) -> float:
        """
        1/m: log W = -beta * total depth (2000: 0.5 mm of penetration costs one nat)
        """
    @beta.setter
    def beta(self, arg0: typing.Any) -> None:
        ...
    @property
    def cell_size(self) -> float:
        """
        m: grid cell of the cloud index; 0 picks one from the cloud
        """
    @cell_size.setter
    def cell_size(self, arg0: typing.Any) -> None:
        ...
    @property
    def contact_tolerance(self) -> float:
        """
        m: depths up to this count as touching, not penetrating (a cloud is a noisy surface)
        """
    @contact_tolerance.setter
    def contact_tolerance(self, arg0: typing.Any) -> None:
        ...
    @property
    def inside_weight(self) -> float:
        """
        m per point: each cloud point inside a link adds this much to the total depth (0: depths alone)
        """
    @inside_weight.setter
    def inside_weight(self, arg0: typing.Any) -> None:
        ...
    @property
    def model(self) -> str:
        """
        surface (the cloud's points) | occupancy (an OccupancyMap of what the cameras saw)
        """
    @model.setter
    def model(self, arg1: typing.Any) -> None:
        ...
    @property
    def occupied_cells(self) -> bool:
        """
        the occupancy model charges the volume in occupied (seen surface) cells; False: their points' depths only
        """
    @occupied_cells.setter
    def occupied_cells(self, arg0: typing.Any) -> None:
        ...
    @property
    def orient_plane(self) -> bool:
        """
        flip the plane's sign so the cloud's mean lies on its free (positive) side
        """
    @orient_plane.setter
    def orient_plane(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_margin(self) -> float:
        """
        m: the support plane is raised by this much (negative: tolerate contact)
        """
    @plane_margin.setter
    def plane_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def point_radius(self) -> float:
        """
        m: cloud points are balls of this radius (>= 0)
        """
    @point_radius.setter
    def point_radius(self, arg0: typing.Any) -> None:
        ...
    @property
    def reference_area(self) -> float:
        """
        m^2: the occupancy model charges a link's volume in blocked cells divided by this
        """
    @reference_area.setter
    def reference_area(self, arg0: typing.Any) -> None:
        ...
    @property
    def unseen_margin(self) -> float:
        """
        m: with the volume, unseen space within this of it is not charged (>= 0)
        """
    @unseen_margin.setter
    def unseen_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def unseen_weight(self) -> float:
        """
        a link's volume in the unknown cells of a map of what the cameras saw (the occupancy model's, or the
        surface model's unseen map) outside the solid volume is charged at this weight (soft: in W, not in
        collision_free; an occupancy map with OccupancySettings.unknown_is_occupied charges them in full instead)
        """
    @unseen_weight.setter
    def unseen_weight(self, arg0: typing.Any) -> None:
        ...
    @property
    def volume(self) -> bool:
        """
        keep the hand out of the objects' solid volume too (columns from the plane up to the points: solid_volume)
        """
    @volume.setter
    def volume(self, arg0: typing.Any) -> None:
        ...
    @property
    def volume_resolution(self) -> float:
        """
        m: the solid volume's cell, > 0
        """
    @volume_resolution.setter
    def volume_resolution(self, arg0: typing.Any) -> None:
        ...
class CollisionResult:
    """
    The collision expert for one configuration (depths in m, per link).
    """
    def __repr__(self) -> str:
        ...
    @property
    def cloud_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (n_links,) deepest cloud point inside each link.
        """
    @property
    def collision_free(self) -> bool:
        ...
    @property
    def log_w(self) -> float:
        """
        log W(h) = -beta * total_depth.
        """
    @property
    def plane_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (n_links,) depth of each link below the support plane.
        """
    @property
    def points_inside(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        """
        (n_links,) cloud points inside each link.
        """
    @property
    def total_depth(self) -> float:
        ...
    @property
    def unseen_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (n_links,) the soft charge of unseen space (CollisionSettings.unseen_weight).
        """
    @property
    def w(self) -> float:
        """
        W(h).
        """
class CollisionBatchResult:
    """
    The collision expert over N configurations.
    """
    @property
    def cloud_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, n_links)
        """
    @property
    def collision_free(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        (N,) bool
        """
    @property
    def log_w(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,)
        """
    @property
    def plane_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, n_links)
        """
    @property
    def total_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,)
        """
    @property
    def unseen_depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, n_links)
        """
    @property
    def w(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,)
        """
class CollisionExpert:
    """
    W(h) = exp(-beta * total penetration) of a hand through an object's cloud and below its support plane
    (eq:opt_criterion_std_col). Cloud depth of a link: the deepest cloud point inside it (exact for boxes,
    cylinders, spheres; meshes as their convex hulls); plane depth: the deepest point of the link below the
    plane (FCL half-space). The cloud is indexed once at construction.
    """
    def __init__(self, hand: Hand, cloud: typing.Any, plane: typing.Any = None, *, occupancy: OccupancyMap = None, unseen: OccupancyMap = None, settings: typing.Any = None, **kwargs) -> None:
        """
        hand: Hand; cloud: (N, 3) points (world frame) or None; plane: [a, b, c, d] of a x + b y + c z + d = 0
        or None; occupancy: an OccupancyMap for the occupancy model (its volume charge, plus the cloud's
        depths), None for the surface model (settings.model names it); unseen: the surface model's map whose
        unknown cells settings.unseen_weight charges (OccupancyMap.from_visibility), or None.
        Settings: settings= a CollisionSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          model = 'surface': surface (the cloud's points) | occupancy (an OccupancyMap of what the cameras saw)
          beta = 2000.0: 1/m: log W = -beta * total depth (2000: 0.5 mm of penetration costs one nat)
          point_radius = 0.0: m: cloud points are balls of this radius (>= 0)
          plane_margin = 0.0: m: the support plane is raised by this much (negative: tolerate contact)
          cell_size = 0.0: m: grid cell of the cloud index; 0 picks one from the cloud
          orient_plane = True: flip the plane's sign so the cloud's mean lies on its free (positive) side
          contact_tolerance = 0.001: m: depths up to this count as touching, not penetrating (a cloud is a noisy surface)
          inside_weight = 0.0: m per point: each cloud point inside a link adds this much to the total depth (0: depths alone)
          reference_area = 0.0001: m^2: the occupancy model charges a link's volume in blocked cells divided by this
          volume = True: keep the hand out of the objects' solid volume too (columns from the plane up to the points: solid_volume)
          volume_resolution = 0.005: m: the solid volume's cell, > 0
          unseen_weight = 0.1: a link's volume in the unknown cells of a map of what the cameras saw (the occupancy model's, or the
        surface model's unseen map) outside the solid volume is charged at this weight (soft: in W, not in
        collision_free; an occupancy map with OccupancySettings.unknown_is_occupied charges them in full instead)
          unseen_margin = 0.01: m: with the volume, unseen space within this of it is not charged (>= 0)
          occupied_cells = True: the occupancy model charges the volume in occupied (seen surface) cells; False: their points' depths only
        """
    def collision_free(self, T_world_wrist: typing.Any, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        (N,) bool: no cloud point inside the hand and nothing below the plane.
        """
    def evaluate(self, T_world_wrist: typing.Any, joints: typing.Any) -> CollisionResult:
        """
        The expert for one wrist pose (7,) and configuration.
        """
    def evaluate_batch(self, T_world_wrist: typing.Any, joints: typing.Any) -> CollisionBatchResult:
        """
        The expert over wrists (N, 7) and joints (N, n_dofs) (or one for all).
        """
    def log_w(self, T_world_wrist: typing.Any, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        log W(h) (N,) over wrists (N, 7) and joints.
        """
    @property
    def beta(self) -> float:
        ...
    @property
    def cell_size(self) -> float:
        """
        The grid cell of the cloud index (m).
        """
    @property
    def model(self) -> str:
        """
        surface | occupancy
        """
    @property
    def n_points(self) -> int:
        ...
    @property
    def occupancy(self) -> typing.Any:
        """
        The OccupancyMap of the occupancy model, or None.
        """
    @property
    def plane(self) -> typing.Any:
        """
        The normalised, oriented plane [a, b, c, d] (free side a x + b y + c z + d > 0), or None.
        """
    @property
    def plane_margin(self) -> float:
        ...
    @property
    def point_radius(self) -> float:
        ...
    @property
    def settings(self) -> CollisionSettings:
        """
        The CollisionSettings it was built with (a copy).
        """
    @property
    def unseen(self) -> typing.Any:
        """
        The map whose unknown cells settings.unseen_weight charges (the occupancy model's, or unseen=), or None.
        """
    @property
    def volume(self) -> typing.Any:
        """
        The solid volume charged with settings.volume (an OccupancyMap: solid_volume), or None.
        """
class ContactSettings:
    """
    How contact points are taken from a demonstration.
    
    Settings: settings= a ContactSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      max_distance = 0.01: m: object points farther than this from a link's geometry are not its contacts
      lambda_ = 5000.0: 1/m^2: a contact at distance d weighs exp(-lambda d^2)
      min_points = 10: a link with fewer contact points gets no contact model
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('max_distance', 'lambda_', 'min_points')
    def __copy__(self) -> ContactSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> ContactSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (max_distance, lambda_, min_points); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def lambda_(self) -> float:
        """
        1/m^2: a contact at distance d weighs exp(-lambda d^2)
        """
    @lambda_.setter
    def lambda_(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_distance(self) -> float:
        """
        m: object points farther than this from a link's geometry are not its contacts
        """
    @max_distance.setter
    def max_distance(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_points(self) -> int:
        """
        a link with fewer contact points gets no contact model
        """
    @min_points.setter
    def min_points(self, arg0: typing.Any) -> None:
        ...
class ContactData:
    """
    The demonstration data D_O of one link (contact_data).
    """
    def __len__(self) -> int:
        ...
    @property
    def distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (M) m, from the point to the link's geometry (0 inside)
        """
    @property
    def indices(self) -> list[int]:
        """
        (M) object points used (rows of frames / features)
        """
    @property
    def link(self) -> int:
        ...
    @property
    def r(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (M, n) the points' features
        """
    @property
    def u(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 7]"]:
        """
        (M, 7) the link pose in each point's frame
        """
    @property
    def weights(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (M) exp(-lambda d^2)
        """
class ContactModel:
    """
    M_i: one link's contact density.
    """
    def __init__(self, link: typing.Any, link_name: str, density: PoseDensity, n_points: typing.Any = 0) -> None:
        ...
    @property
    def density(self) -> PoseDensity:
        ...
    @property
    def link(self) -> int:
        ...
    @property
    def link_name(self) -> str:
        ...
    @property
    def n_points(self) -> int:
        ...
class ConfigModelSettings:
    """
    The hand configuration model C(h_c) (eq:manipulator_model).
    
    Settings: settings= a ConfigModelSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      beta = 1.0: gamma range: configurations up to beta (h_e - h_g) either side of h_g
      n_kernels = 21: kernels along the line (odd keeps one on h_g)
      alpha = 2.0: decay of the kernel weights away from h_g (unitless)
      bandwidth = 0.1: kernel std as a fraction of |h_e - h_g|
      min_bandwidth = 0.001: floor of the kernel std (joint units: m or rad)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('beta', 'n_kernels', 'alpha', 'bandwidth', 'min_bandwidth')
    def __copy__(self) -> ConfigModelSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> ConfigModelSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (beta, n_kernels, alpha, bandwidth, min_bandwidth); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def alpha(self) -> float:
        """
        decay of the kernel weights away from h_g (unitless)
        """
    @alpha.setter
    def alpha(self, arg0: typing.Any) -> None:
        ...
    @property
    def bandwidth(self) -> float:
        """
        kernel std as a fraction of |h_e - h_g|
        """
    @bandwidth.setter
    def bandwidth(self, arg0: typing.Any) -> None:
        ...
    @property
    def beta(self) -> float:
        """
        gamma range: configurations up to beta (h_e - h_g) either side of h_g
        """
    @beta.setter
    def beta(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_bandwidth(self) -> float:
        """
        floor of the kernel std (joint units: m or rad)
        """
    @min_bandwidth.setter
    def min_bandwidth(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_kernels(self) -> int:
        """
        kernels along the line (odd keeps one on h_g)
        """
    @n_kernels.setter
    def n_kernels(self, arg0: typing.Any) -> None:
        ...
class ConfigModel:
    """
    C(h_c) of eq:manipulator_model.
    """
    def __init__(self, pregrasp: typing.Any, grasp: typing.Any, limits: typing.Any, settings: typing.Any = None, **kwargs) -> None:
        """
        pregrasp h_e and grasp h_g (D,), limits (D, 2).
        Settings: settings= a ConfigModelSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          beta = 1.0: gamma range: configurations up to beta (h_e - h_g) either side of h_g
          n_kernels = 21: kernels along the line (odd keeps one on h_g)
          alpha = 2.0: decay of the kernel weights away from h_g (unitless)
          bandwidth = 0.1: kernel std as a fraction of |h_e - h_g|
          min_bandwidth = 0.001: floor of the kernel std (joint units: m or rad)
        """
    def log_density(self, q: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def pregrasp_for(self, arg0: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def sample(self, n: typing.Any, seed: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def grasp(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def kernels(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def limits(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def pregrasp(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def settings(self) -> ConfigModelSettings:
        ...
    @property
    def sigma(self) -> float:
        ...
class Expert:
    """
    A task-constraint expert E_k (log values per grasp).
    """
    def log_value(self, wrists: typing.Any, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def name(self) -> str:
        ...
class KinematicFeasibilitySettings:
    """
    The hard kinematic-feasibility expert.
    
    Settings: settings= a KinematicFeasibilitySettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      plane_margin = 0.0: m: links must stay this far above the support plane
      plane_tolerance = 1e-09: m: a link this little below the (raised) plane still counts as clear (rounding, not penetration)
      limit_tolerance = 1e-09: joint units (m or rad): slack allowed past the joint limits
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('plane_margin', 'plane_tolerance', 'limit_tolerance')
    def __copy__(self) -> KinematicFeasibilitySettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> KinematicFeasibilitySettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (plane_margin, plane_tolerance, limit_tolerance); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def limit_tolerance(self) -> float:
        """
        joint units (m or rad): slack allowed past the joint limits
        """
    @limit_tolerance.setter
    def limit_tolerance(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_margin(self) -> float:
        """
        m: links must stay this far above the support plane
        """
    @plane_margin.setter
    def plane_margin(self, arg0: typing.Any) -> None:
        ...
    @property
    def plane_tolerance(self) -> float:
        """
        m: a link this little below the (raised) plane still counts as clear (rounding, not penetration)
        """
    @plane_tolerance.setter
    def plane_tolerance(self, arg0: typing.Any) -> None:
        ...
class KinematicFeasibilityExpert(Expert):
    """
    Hard: joint limits, no link below the support plane, and an optional reachability test reachable(wrists (N,7), joints (N,D)) -> bool array.
    """
    def __init__(self, hand: Hand, plane: typing.Any = None, reachable: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> None:
        """
        Settings: settings= a KinematicFeasibilitySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          plane_margin = 0.0: m: links must stay this far above the support plane
          plane_tolerance = 1e-09: m: a link this little below the (raised) plane still counts as clear (rounding, not penetration)
          limit_tolerance = 1e-09: joint units (m or rad): slack allowed past the joint limits
        """
class AxisAlignmentSettings:
    """
    The soft principal-axis alignment expert.
    
    Settings: settings= a AxisAlignmentSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      hand_axis = None: (3,) the hand's axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)
      concentration = 20.0: nats: log E = concentration (cos theta - 1), so a 90-degree deviation costs this much
      name = 'approach_axis': the key of its term in a grasp's experts table
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('hand_axis', 'concentration', 'name')
    def __copy__(self) -> AxisAlignmentSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> AxisAlignmentSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (hand_axis, concentration, name); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def concentration(self) -> float:
        """
        nats: log E = concentration (cos theta - 1), so a 90-degree deviation costs this much
        """
    @concentration.setter
    def concentration(self, arg0: typing.Any) -> None:
        ...
    @property
    def hand_axis(self) -> typing.Any:
        """
        (3,) the hand's axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)
        """
    @hand_axis.setter
    def hand_axis(self, arg1: typing.Any) -> None:
        ...
    @property
    def name(self) -> str:
        """
        the key of its term in a grasp's experts table
        """
    @name.setter
    def name(self, arg0: typing.Any) -> None:
        ...
class AxisAlignmentExpert(Expert):
    """
    Soft: log E = concentration (cos(angle between hand axis and world axis) - 1).
    """
    def __init__(self, axis: typing.Any, hand_axis: typing.Any = None, *, settings: typing.Any = None, hand: Hand = None, **kwargs) -> None:
        """
        axis: (3,) the desired world axis; hand_axis=None: the settings' hand_axis, or (None too) the hand's approach_axis (without a hand: the wrist's +z).
        Settings: settings= a AxisAlignmentSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          hand_axis = None: (3,) the hand's axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)
          concentration = 20.0: nats: log E = concentration (cos theta - 1), so a 90-degree deviation costs this much
          name = 'approach_axis': the key of its term in a grasp's experts table
        """
class CollisionFreeExpert(Expert):
    """
    Hard: the hand touches none of a CollisionExpert's cloud and plane at the grasp (and, given a ConfigModel, at its pre-grasp).
    """
    def __init__(self, collision: CollisionExpert, pregrasp_config: ConfigModel | None = None, name: str = 'collision_free') -> None:
        """
        collision: the CollisionExpert of what to keep clear of; pregrasp_config: a ConfigModel whose pregrasp_for(q) gives each grasp's pre-grasp, checked too (None: the grasp only).
        """
class ClearApproachSettings:
    """
    The hard clear-approach expert.
    
    Settings: settings= a ClearApproachSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      stand_off = 0.1: m: the hand starts this far back along its approach axis from the pre-grasp (>= 0)
      step = 0.02: m: the path is checked at poses this far apart (> 0)
      clearance = 0.002: m: the points of the collision expert the path is checked against are balls of this radius (scene synthesis builds it so), which the open hand may enter by that expert's contact tolerance (1 mm by default: the hand keeps 1 mm from every point)
      hand_axis = None: (3,) the approach axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)
      name = 'clear_approach': the key of its term in a grasp's experts table
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('stand_off', 'step', 'clearance', 'hand_axis', 'name')
    def __copy__(self) -> ClearApproachSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> ClearApproachSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (stand_off, step, clearance, hand_axis, name); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def clearance(self) -> float:
        """
        m: the points of the collision expert the path is checked against are balls of this radius (scene synthesis builds it so), which the open hand may enter by that expert's contact tolerance (1 mm by default: the hand keeps 1 mm from every point)
        """
    @clearance.setter
    def clearance(self, arg0: typing.Any) -> None:
        ...
    @property
    def hand_axis(self) -> typing.Any:
        """
        (3,) the approach axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)
        """
    @hand_axis.setter
    def hand_axis(self, arg1: typing.Any) -> None:
        ...
    @property
    def name(self) -> str:
        """
        the key of its term in a grasp's experts table
        """
    @name.setter
    def name(self, arg0: typing.Any) -> None:
        ...
    @property
    def stand_off(self) -> float:
        """
        m: the hand starts this far back along its approach axis from the pre-grasp (>= 0)
        """
    @stand_off.setter
    def stand_off(self, arg0: typing.Any) -> None:
        ...
    @property
    def step(self) -> float:
        """
        m: the path is checked at poses this far apart (> 0)
        """
    @step.setter
    def step(self, arg0: typing.Any) -> None:
        ...
class ClearApproachExpert(Expert):
    """
    Hard: the open hand (each grasp's pre-grasp) moves along its approach axis from the stand-off to the pre-grasp without touching the CollisionExpert's scene and plane.
    """
    def __init__(self, collision: CollisionExpert, config: ConfigModel, *, settings: typing.Any = None, **kwargs) -> None:
        """
        collision: the CollisionExpert of the scene; config: the ConfigModel whose pregrasp_for(q) is the open hand.
        Settings: settings= a ClearApproachSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          stand_off = 0.1: m: the hand starts this far back along its approach axis from the pre-grasp (>= 0)
          step = 0.02: m: the path is checked at poses this far apart (> 0)
          clearance = 0.002: m: the points of the collision expert the path is checked against are balls of this radius (scene synthesis builds it so), which the open hand may enter by that expert's contact tolerance (1 mm by default: the hand keeps 1 mm from every point)
          hand_axis = None: (3,) the approach axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)
          name = 'clear_approach': the key of its term in a grasp's experts table
        """
    @property
    def offsets(self) -> list[float]:
        """
        m: the distances back along the axis at which the open hand is checked
        """
class FunctionExpert(Expert):
    """
    A user expert: fn(wrists (N,7), joints (N,D)) -> log E (N,), called once per batch.
    """
    def __init__(self, name: str, fn: collections.abc.Callable) -> None:
        ...
class ContactQualitySettings:
    """
    The contact-quality expert (antipodal friction-cone deviation).
    
    Settings: settings= a ContactQualitySettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      friction = 0.5: Coulomb coefficient mu (> 0): the friction cone's half-angle is atan(mu)
      concentration = 10.0: nats per radian beyond the friction cone, per contact
      air_penalty = 40.0: nats per finger that closes on nothing
      patch_points = 30.0: a finger's contact patch of fewer cloud points than this is charged (0: off)
      patch_penalty = 20.0: nats: a patch of n < patch_points points costs patch_penalty * (1 - n / patch_points)
      contact_tolerance = 0.001: m: points within this of a link's surface are in contact
      closing_steps = 16: steps of the closing motion before bisection (links that do not translate)
      name = 'contact_quality': the key of its term in a grasp's experts table
      target_first = True: scene synthesis: a grasp whose finger, closing, meets another object's observed points before the
    target's is rejected (its target_first term -inf)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('friction', 'concentration', 'air_penalty', 'patch_points', 'patch_penalty', 'contact_tolerance', 'closing_steps', 'name', 'target_first')
    def __copy__(self) -> ContactQualitySettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> ContactQualitySettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (friction, concentration, air_penalty, patch_points, patch_penalty, contact_tolerance, closing_steps, name, target_first); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def air_penalty(self) -> float:
        """
        nats per finger that closes on nothing
        """
    @air_penalty.setter
    def air_penalty(self, arg0: typing.Any) -> None:
        ...
    @property
    def closing_steps(self) -> int:
        """
        steps of the closing motion before bisection (links that do not translate)
        """
    @closing_steps.setter
    def closing_steps(self, arg0: typing.Any) -> None:
        ...
    @property
    def concentration(self) -> float:
        """
        nats per radian beyond the friction cone, per contact
        """
    @concentration.setter
    def concentration(self, arg0: typing.Any) -> None:
        ...
    @property
    def contact_tolerance(self) -> float:
        """
        m: points within this of a link's surface are in contact
        """
    @contact_tolerance.setter
    def contact_tolerance(self, arg0: typing.Any) -> None:
        ...
    @property
    def friction(self) -> float:
        """
        Coulomb coefficient mu (> 0): the friction cone's half-angle is atan(mu)
        """
    @friction.setter
    def friction(self, arg0: typing.Any) -> None:
        ...
    @property
    def name(self) -> str:
        """
        the key of its term in a grasp's experts table
        """
    @name.setter
    def name(self, arg0: typing.Any) -> None:
        ...
    @property
    def patch_penalty(self) -> float:
        """
        nats: a patch of n < patch_points points costs patch_penalty * (1 - n / patch_points)
        """
    @patch_penalty.setter
    def patch_penalty(self, arg0: typing.Any) -> None:
        ...
    @property
    def patch_points(self) -> float:
        """
        a finger's contact patch of fewer cloud points than this is charged (0: off)
        """
    @patch_points.setter
    def patch_points(self, arg0: typing.Any) -> None:
        ...
    @property
    def target_first(self) -> bool:
        """
        scene synthesis: a grasp whose finger, closing, meets another object's observed points before the
        target's is rejected (its target_first term -inf)
        """
    @target_first.setter
    def target_first(self, arg0: typing.Any) -> None:
        ...
class ContactQualityResult:
    """
    The contacts of N grasps, F finger links each (expert.finger_links order).
    """
    @property
    def angles(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, F) angle (rad) between each contact's normal axis and the grasp line, in the scored pair
        """
    @property
    def joints(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, F, D) the configuration at each finger's contact (NaN: none)
        """
    @property
    def links(self) -> list[int]:
        """
        (F,) the finger links (indices into Hand.link_names)
        """
    @property
    def log_value(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,) log E
        """
    @property
    def normals(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, F, 3) contact normal axes, unit, pointing towards the finger (NaN: none)
        """
    @property
    def patch_size(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, n]"]:
        """
        (N, F) points in each contact patch
        """
    @property
    def points(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, F, 3) contact points, world frame (NaN: none)
        """
    @property
    def t(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, F) closing parameter of each first contact (NaN: none)
        """
class ContactQualityExpert(Expert):
    """
    Soft: close the hand from each grasp's pre-grasp until each finger meets the cloud, then
    log E = -concentration * sum_i max(0, theta_i - atan(friction)) - air_penalty * (fingers on nothing)
            - patch_penalty * sum_f max(0, 1 - patch_f / reference_f) (fingers that touch),
    theta_i the angle between contact i's normal axis and the line between the contacts, patch_f the points
    in finger f's contact patch, reference_f = min(patch_points, what finger f meets of a flat face:
    patch_reference)
    (include/graspmix/grasp/contact_quality.hpp).
    """
    def __init__(self, hand: Hand, points: typing.Any, normals: typing.Any, pregrasp_config: ConfigModel, *, settings: typing.Any = None, **kwargs) -> None:
        """
        hand: Hand; points, normals: (N, 3) the object's cloud and surface normals (world frame; a normal's
        sign is ignored); pregrasp_config: a ConfigModel whose pregrasp_for(q) opens each grasp.
        Settings: settings= a ContactQualitySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          friction = 0.5: Coulomb coefficient mu (> 0): the friction cone's half-angle is atan(mu)
          concentration = 10.0: nats per radian beyond the friction cone, per contact
          air_penalty = 40.0: nats per finger that closes on nothing
          patch_points = 30.0: a finger's contact patch of fewer cloud points than this is charged (0: off)
          patch_penalty = 20.0: nats: a patch of n < patch_points points costs patch_penalty * (1 - n / patch_points)
          contact_tolerance = 0.001: m: points within this of a link's surface are in contact
          closing_steps = 16: steps of the closing motion before bisection (links that do not translate)
          name = 'contact_quality': the key of its term in a grasp's experts table
          target_first = True: scene synthesis: a grasp whose finger, closing, meets another object's observed points before the
        target's is rejected (its target_first term -inf)
        """
    def evaluate(self, wrists: typing.Any, joints: typing.Any) -> ContactQualityResult:
        """
        The contacts, angles and log E of wrists (N, 7) and joints (N, D): a ContactQualityResult.
        """
    @property
    def finger_links(self) -> list[int]:
        """
        Indices (into Hand.link_names) of the links that close on the object.
        """
    @property
    def finger_names(self) -> list[str]:
        """
        Names of the finger links.
        """
    @property
    def n_points(self) -> int:
        ...
    @property
    def patch_reference(self) -> list[float]:
        """
        Per finger, the patch size below which it is charged: min(patch_points, the patch it makes closing face-on onto a flat wall of the cloud's spacing).
        """
    @property
    def settings(self) -> ContactQualitySettings:
        """
        The ContactQualitySettings it was built with (a copy).
        """
class GraspDepthSettings:
    """
    The grasp-depth expert (how far back the object reaches between the fingers).
    
    Settings: settings= a GraspDepthSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      min_depth = 0.02: m: how far back from the fingertips' far end the object's points between the fingers must reach
      penalty = 1000.0: nats per metre short of min_depth
      min_radius = 0.01: m: the radius of the cylinder between the fingers is at least this
      name = 'grasp_depth': the key of its term in a grasp's experts table
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('min_depth', 'penalty', 'min_radius', 'name')
    def __copy__(self) -> GraspDepthSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> GraspDepthSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (min_depth, penalty, min_radius, name); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def min_depth(self) -> float:
        """
        m: how far back from the fingertips' far end the object's points between the fingers must reach
        """
    @min_depth.setter
    def min_depth(self, arg0: typing.Any) -> None:
        ...
    @property
    def min_radius(self) -> float:
        """
        m: the radius of the cylinder between the fingers is at least this
        """
    @min_radius.setter
    def min_radius(self, arg0: typing.Any) -> None:
        ...
    @property
    def name(self) -> str:
        """
        the key of its term in a grasp's experts table
        """
    @name.setter
    def name(self, arg0: typing.Any) -> None:
        ...
    @property
    def penalty(self) -> float:
        """
        nats per metre short of min_depth
        """
    @penalty.setter
    def penalty(self, arg0: typing.Any) -> None:
        ...
class GraspDepthExpert(Expert):
    """
    Soft: log E = -penalty * max(0, min_depth - depth), depth how far back from the fingertips' far end (along
    the approach) the object's points inside the cylinder between the fingers reach
    (include/graspmix/grasp/grasp_depth.hpp).
    """
    def __init__(self, hand: Hand, points: typing.Any, *, settings: typing.Any = None, **kwargs) -> None:
        """
        hand: Hand; points: (N, 3) the object's surface (world frame).
        Settings: settings= a GraspDepthSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          min_depth = 0.02: m: how far back from the fingertips' far end the object's points between the fingers must reach
          penalty = 1000.0: nats per metre short of min_depth
          min_radius = 0.01: m: the radius of the cylinder between the fingers is at least this
          name = 'grasp_depth': the key of its term in a grasp's experts table
        """
    def depths(self, wrists: typing.Any, joints: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,) each grasp's depth (m) for wrists (N, 7) and joints (N, D), capped at min_depth.
        """
    @property
    def settings(self) -> GraspDepthSettings:
        """
        The GraspDepthSettings it was built with (a copy).
        """
class QuerySettings:
    """
    Contact query densities Q_i (eq:query_density_approx).
    
    Settings: settings= a QuerySettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      n_samples = 500: N_Q: samples per link to fit each query density from
      n_components = 5: K_Q: components of each query mixture (GMM models)
      max_iter = 100: EM iterations of the query mixtures
      reg_covar = 1e-06: added to the query mixtures' covariance diagonals
      kde = KdeSettings(position_bandwidth=0.005, orientation_bandwidth=0.15, feature_bandwidth=array([0.005])): KdeSettings of KDE query densities (features unused)
      frame_jitter = True: rotate each sampled surface frame about its normal by up to pi exp(-jitter_sharpness ((k1 - k2) / k1)^2)
      jitter_sharpness = 100.0: s of Kopicki's rule above
      completed_weight = 1.0: prior weight of a completed (unseen) point in the query densities, an observed one's being 1
      link_floor = -20.0: nats or None: each link's contact term is log(Q_i + exp(link_floor)); None: log Q_i (the paper's)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('n_samples', 'n_components', 'max_iter', 'reg_covar', 'kde', 'frame_jitter', 'jitter_sharpness', 'completed_weight', 'link_floor')
    def __copy__(self) -> QuerySettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> QuerySettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (n_samples, n_components, max_iter, reg_covar, kde, frame_jitter, jitter_sharpness, completed_weight, link_floor); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def completed_weight(self) -> float:
        """
        prior weight of a completed (unseen) point in the query densities, an observed one's being 1
        """
    @completed_weight.setter
    def completed_weight(self, arg0: typing.Any) -> None:
        ...
    @property
    def frame_jitter(self) -> bool:
        """
        rotate each sampled surface frame about its normal by up to pi exp(-jitter_sharpness ((k1 - k2) / k1)^2)
        """
    @frame_jitter.setter
    def frame_jitter(self, arg0: typing.Any) -> None:
        ...
    @property
    def jitter_sharpness(self) -> float:
        """
        s of Kopicki's rule above
        """
    @jitter_sharpness.setter
    def jitter_sharpness(self, arg0: typing.Any) -> None:
        ...
    @property
    def kde(self) -> KdeSettings:
        """
        KdeSettings of KDE query densities (features unused)
        """
    @kde.setter
    def kde(self, arg0: typing.Any) -> None:
        ...
    @property
    def link_floor(self) -> typing.Any:
        """
        nats or None: each link's contact term is log(Q_i + exp(link_floor)); None: log Q_i (the paper's)
        """
    @link_floor.setter
    def link_floor(self, arg1: typing.Any) -> None:
        ...
    @property
    def max_iter(self) -> int:
        """
        EM iterations of the query mixtures
        """
    @max_iter.setter
    def max_iter(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_components(self) -> int:
        """
        K_Q: components of each query mixture (GMM models)
        """
    @n_components.setter
    def n_components(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_samples(self) -> int:
        """
        N_Q: samples per link to fit each query density from
        """
    @n_samples.setter
    def n_samples(self, arg0: typing.Any) -> None:
        ...
    @property
    def reg_covar(self) -> float:
        """
        added to the query mixtures' covariance diagonals
        """
    @reg_covar.setter
    def reg_covar(self, arg0: typing.Any) -> None:
        ...
class AnnealingSettings:
    """
    Simulated annealing of the best candidates.
    
    Settings: settings= a AnnealingSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      iterations = 100: the paper's 100
      initial_temperature = 1.0: the paper's 1.0, falling linearly to 0
      position_step = 0.005: m: std of wrist translation proposals at temperature 1
      rotation_step = 0.1: rad: std of wrist rotation proposals at temperature 1
      joint_step = 0.5: std of joint proposals at temperature 1, in units of the config model's kernel std
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('iterations', 'initial_temperature', 'position_step', 'rotation_step', 'joint_step')
    def __copy__(self) -> AnnealingSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> AnnealingSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (iterations, initial_temperature, position_step, rotation_step, joint_step); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def initial_temperature(self) -> float:
        """
        the paper's 1.0, falling linearly to 0
        """
    @initial_temperature.setter
    def initial_temperature(self, arg0: typing.Any) -> None:
        ...
    @property
    def iterations(self) -> int:
        """
        the paper's 100
        """
    @iterations.setter
    def iterations(self, arg0: typing.Any) -> None:
        ...
    @property
    def joint_step(self) -> float:
        """
        std of joint proposals at temperature 1, in units of the config model's kernel std
        """
    @joint_step.setter
    def joint_step(self, arg0: typing.Any) -> None:
        ...
    @property
    def position_step(self) -> float:
        """
        m: std of wrist translation proposals at temperature 1
        """
    @position_step.setter
    def position_step(self, arg0: typing.Any) -> None:
        ...
    @property
    def rotation_step(self) -> float:
        """
        rad: std of wrist rotation proposals at temperature 1
        """
    @rotation_step.setter
    def rotation_step(self, arg0: typing.Any) -> None:
        ...
class SamplingSettings:
    """
    How many grasps are drawn, kept and annealed.
    
    Settings: settings= a SamplingSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      n_samples = 200: grasps sampled, ranked and returned
      n_optimise = 10: the best this many are optimised
      optimise = True: anneal the best n_optimise
      clear_pregrasp = True: an extra collision expert on the pre-grasp configuration (log W of the opened hand)
      max_sampling_rounds = 10: batches of n_samples drawn at most until n_samples grasps pass every hard expert
      topdown_seeds = True: scene synthesis adds each object's top-down seeds (grasp/topdown_seeds.hpp) to the drawn grasps
      oversample = 2: oversample * n_samples grasps are drawn and ranked, the best n_samples returned (1: the paper's)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('n_samples', 'n_optimise', 'optimise', 'clear_pregrasp', 'max_sampling_rounds', 'topdown_seeds', 'oversample')
    def __copy__(self) -> SamplingSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> SamplingSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (n_samples, n_optimise, optimise, clear_pregrasp, max_sampling_rounds, topdown_seeds, oversample); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def clear_pregrasp(self) -> bool:
        """
        an extra collision expert on the pre-grasp configuration (log W of the opened hand)
        """
    @clear_pregrasp.setter
    def clear_pregrasp(self, arg0: typing.Any) -> None:
        ...
    @property
    def max_sampling_rounds(self) -> int:
        """
        batches of n_samples drawn at most until n_samples grasps pass every hard expert
        """
    @max_sampling_rounds.setter
    def max_sampling_rounds(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_optimise(self) -> int:
        """
        the best this many are optimised
        """
    @n_optimise.setter
    def n_optimise(self, arg0: typing.Any) -> None:
        ...
    @property
    def n_samples(self) -> int:
        """
        grasps sampled, ranked and returned
        """
    @n_samples.setter
    def n_samples(self, arg0: typing.Any) -> None:
        ...
    @property
    def optimise(self) -> bool:
        """
        anneal the best n_optimise
        """
    @optimise.setter
    def optimise(self, arg0: typing.Any) -> None:
        ...
    @property
    def oversample(self) -> int:
        """
        oversample * n_samples grasps are drawn and ranked, the best n_samples returned (1: the paper's)
        """
    @oversample.setter
    def oversample(self, arg0: typing.Any) -> None:
        ...
    @property
    def topdown_seeds(self) -> bool:
        """
        scene synthesis adds each object's top-down seeds (grasp/topdown_seeds.hpp) to the drawn grasps
        """
    @topdown_seeds.setter
    def topdown_seeds(self, arg0: typing.Any) -> None:
        ...
class SynthesizerSettings:
    """
    What GraspSynthesizer.synthesize needs besides the object and the experts (scene synthesis builds it from graspmix.SynthesisOptions).
    
    Settings: settings= a SynthesizerSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      sampling = SamplingSettings(n_samples=200, n_optimise=10, optimise=True, clear_pregrasp=True, max_sampling_rounds=10, topdown_seeds=True, oversample=2): SamplingSettings
      query = QuerySettings(n_samples=500, n_components=5, max_iter=100, reg_covar=1e-06, kde=KdeSettings(position_bandwidth=0.005, orientation_bandwidth=0.15, feature_bandwidth=array([0.005])), frame_jitter=True, jitter_sharpness=100.0, completed_weight=1.0, link_floor=-20.0): QuerySettings
      annealing = AnnealingSettings(iterations=100, initial_temperature=1.0, position_step=0.005, rotation_step=0.1, joint_step=0.5): AnnealingSettings
      seed = 0: seeds everything random in synthesis (None: 0)
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('sampling', 'query', 'annealing', 'seed')
    def __copy__(self) -> SynthesizerSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> SynthesizerSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (sampling, query, annealing, seed); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def annealing(self) -> AnnealingSettings:
        """
        AnnealingSettings
        """
    @annealing.setter
    def annealing(self, arg0: typing.Any) -> None:
        ...
    @property
    def query(self) -> QuerySettings:
        """
        QuerySettings
        """
    @query.setter
    def query(self, arg0: typing.Any) -> None:
        ...
    @property
    def sampling(self) -> SamplingSettings:
        """
        SamplingSettings
        """
    @sampling.setter
    def sampling(self, arg0: typing.Any) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seeds everything random in synthesis (None: 0)
        """
    @seed.setter
    def seed(self, arg1: typing.Any) -> None:
        ...
class Grasp:
    """
    One synthesised grasp and its log-likelihood terms.
    """
    def __repr__(self) -> str:
        ...
    @property
    def T_world_wrist(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 1]"]:
        """
        (7,) [x, y, z, qx, qy, qz, qw]
        """
    @property
    def joints(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        grasp configuration h_c (Hand.joint_names order)
        """
    @property
    def log_collision(self) -> float:
        """
        log W
        """
    @property
    def log_config(self) -> float:
        """
        log C
        """
    @property
    def log_contact(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        log Q_i per query link (SynthesisResult.contact_links)
        """
    @property
    def log_experts(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        log E_k per expert (SynthesisResult.expert_names)
        """
    @property
    def log_likelihood(self) -> float:
        """
        log L (eq:opt_criterion_extended)
        """
    @property
    def log_pregrasp(self) -> float:
        """
        log W of the pre-grasp configuration (clear_pregrasp)
        """
    @property
    def optimised(self) -> bool:
        ...
    @property
    def pregrasp(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        the configuration to approach with
        """
class SynthesisTiming:
    """
    Seconds spent in each stage of synthesis.
    """
    def __repr__(self) -> str:
        ...
    @property
    def optimisation(self) -> float:
        """
        s: annealing the best candidates
        """
    @property
    def query(self) -> float:
        """
        s: query density estimation
        """
    @property
    def sampling(self) -> float:
        """
        s: sampling and ranking
        """
    @property
    def total(self) -> float:
        """
        s
        """
class SynthesisResult:
    """
    Grasps best first, with diagnostics.
    """
    def columns(self) -> dict:
        """
        The grasps' fields as arrays, one row a grasp (best first): {Grasp key: (N,) or (N, k)}; what result.grasps gives one grasp at a time, without a Python object per grasp and field
        """
    @property
    def contact_links(self) -> list[str]:
        ...
    @property
    def evaluations(self) -> int:
        """
        grasps scored in all
        """
    @property
    def expert_names(self) -> list[str]:
        ...
    @property
    def grasps(self) -> list[Grasp]:
        """
        list of Grasp, best first
        """
    @property
    def rejected(self) -> int:
        """
        samples a hard constraint rejected
        """
    @property
    def term_names(self) -> list[str]:
        """
        every term of log L, in the order of the columns' log_terms: collision, config, pregrasp_clear, contact/<link> per query link, the experts
        """
    @property
    def timing(self) -> SynthesisTiming:
        """
        SynthesisTiming
        """
class Evaluation:
    """
    log L and its terms for a batch of grasps.
    """
    @property
    def log_collision(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,)
        """
    @property
    def log_config(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,)
        """
    @property
    def log_contact(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, query links)
        """
    @property
    def log_experts(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, experts)
        """
    @property
    def log_pregrasp(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,)
        """
    @property
    def total(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (N,) log L
        """
class QueryDensity:
    """
    Q_i: one link's query density on an object.
    """
    @property
    def density(self) -> PoseDensity:
        ...
    @property
    def link(self) -> int:
        ...
    @property
    def link_name(self) -> str:
        ...
class GraspSynthesizer:
    """
    Query densities, sampling, ranking and annealing for one learnt model.
    """
    def __init__(self, hand: Hand, contact_models: collections.abc.Sequence[ContactModel], config_model: ConfigModel) -> None:
        ...
    def evaluate(self, query: collections.abc.Sequence[QueryDensity], collision: CollisionExpert, experts: typing.Any, wrists: typing.Any, joints: typing.Any, clear_pregrasp: typing.Any = None) -> Evaluation:
        """
        log L and its terms (an Evaluation) for a batch of grasps; clear_pregrasp=None: SamplingSettings' default.
        """
    def query_densities(self, frames: typing.Any, features: typing.Any, settings: typing.Any = None, seed: typing.Any = None, *, weights: typing.Any = None, **kwargs) -> list[QueryDensity]:
        """
        The query densities Q_i on an object; weights (N,): each point's prior weight (None: all 1).
        Settings: settings= a QuerySettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          n_samples = 500: N_Q: samples per link to fit each query density from
          n_components = 5: K_Q: components of each query mixture (GMM models)
          max_iter = 100: EM iterations of the query mixtures
          reg_covar = 1e-06: added to the query mixtures' covariance diagonals
          kde = KdeSettings(position_bandwidth=0.005, orientation_bandwidth=0.15, feature_bandwidth=array([0.005])): KdeSettings of KDE query densities (features unused)
          frame_jitter = True: rotate each sampled surface frame about its normal by up to pi exp(-jitter_sharpness ((k1 - k2) / k1)^2)
          jitter_sharpness = 100.0: s of Kopicki's rule above
          completed_weight = 1.0: prior weight of a completed (unseen) point in the query densities, an observed one's being 1
          link_floor = -20.0: nats or None: each link's contact term is log(Q_i + exp(link_floor)); None: log Q_i (the paper's)
        """
    def sample_grasps(self, query: collections.abc.Sequence[QueryDensity], n: typing.Any, seed: typing.Any = None) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 7]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]]:
        """
        (wrists (n, 7), joints (n, D)).
        """
    def synthesize(self, frames: typing.Any, features: typing.Any, collision: CollisionExpert, experts: typing.Any = None, settings: typing.Any = None, *, weights: typing.Any = None, **kwargs) -> SynthesisResult:
        """
        Query densities, sampling, ranking and annealing on an object's frames (N, 7) and features (N, n);
        weights (N,): each point's prior weight in the query densities (None: all 1).
        Settings: settings= a SynthesizerSettings (None: its defaults), and/or its fields as keywords,
        which override it (an unknown keyword is a ValueError):
          sampling = SamplingSettings(n_samples=200, n_optimise=10, optimise=True, clear_pregrasp=True, max_sampling_rounds=10, topdown_seeds=True, oversample=2): SamplingSettings
          query = QuerySettings(n_samples=500, n_components=5, max_iter=100, reg_covar=1e-06, kde=KdeSettings(position_bandwidth=0.005, orientation_bandwidth=0.15, feature_bandwidth=array([0.005])), frame_jitter=True, jitter_sharpness=100.0, completed_weight=1.0, link_floor=-20.0): QuerySettings
          annealing = AnnealingSettings(iterations=100, initial_temperature=1.0, position_step=0.005, rotation_step=0.1, joint_step=0.5): AnnealingSettings
          seed = 0: seeds everything random in synthesis (None: 0)
        """
    @property
    def config_model(self) -> ConfigModel:
        ...
    @property
    def contact_models(self) -> list[ContactModel]:
        ...
    @property
    def method(self) -> str:
        ...
class SceneSynthesis:
    """
    What synthesize_scene made: the scene, the targets, ranked grasps.
    """
    def __len__(self) -> int:
        ...
    def columns(self) -> dict:
        """
        The ranked grasps as arrays: T_world_wrist (N, 7), joints, pregrasp (N, D), log_likelihood, optimised, object, type (N,), log_terms (a list of N lists, in the order of term_names[type])
        """
    @property
    def completion(self) -> SceneCompletion:
        """
        the SceneCompletion of every object
        """
    @property
    def evaluations(self) -> int:
        ...
    @property
    def rejected(self) -> int:
        ...
    @property
    def scene(self) -> Segmentation:
        """
        the Segmentation (support plane and objects)
        """
    @property
    def surfaces(self) -> list[SurfaceCloud]:
        """
        per target, its SurfaceCloud
        """
    @property
    def targets(self) -> list[int]:
        """
        the objects grasps were sampled on
        """
    @property
    def term_names(self) -> list[list[str]]:
        """
        per grasp type, the names of a grasp's log_terms
        """
    @property
    def timing(self) -> dict:
        """
        seconds: segmentation (with the completion and the targets' choice), occupancy (None: no map), features, query, sampling, optimisation, total
        """
    @property
    def viewpoints(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (M, 3) the camera of each scene point; (0, 3) unknown
        """
class SimSettings:
    """
    Settings of a grasp execution in Bullet (units: m, s, N, kg).
    
    Settings: settings= a SimSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      gravity = array([ 0.  ,  0.  , -9.81]): m/s^2 (3,)
      time_step = 0.004166666666666667: s (pybullet's default)
      solver_iterations = 50: constraint solver iterations per step
      hand_friction = 1.0: lateral friction coefficient of every hand link
      object_friction = -1.0: < 0: the URDF's <contact><lateral_friction> (0.5 if absent)
      support_friction = 1.0: lateral friction of the support plane
      object_mass = -1.0: kg; < 0: the URDF's
      grip_force = 40.0: N (N m): force limit of every finger joint motor
      close_speed = 0.2: m/s: fingertip speed limit while closing (sim_closing_speeds)
      close_overshoot = 0.5: motor targets lie this fraction of (grasp - pregrasp) past the grasp joints
      close_time = 0.5: s spent closing before the lift
      position_gain = 20.0: 1/s: joint velocity command = gain * position error
      lift_height = 0.2: m
      lift_speed = 0.5: m/s
      lift_force = 1000.0: N: force limit of the lift joint
      hold_time = 0.5: s held at the top
      start_penetration = 0.002: m: a start penetrating deeper than this is 'start in collision'
      contact_distance = 0.001: m: contact points closer than this count as touching
      success_fraction = 0.5: the object must rise by this fraction of lift_height
    """
    __hash__: typing.ClassVar[None] = None
    _fields: typing.ClassVar[tuple] = ('gravity', 'time_step', 'solver_iterations', 'hand_friction', 'object_friction', 'support_friction', 'object_mass', 'grip_force', 'close_speed', 'close_overshoot', 'close_time', 'position_gain', 'lift_height', 'lift_speed', 'lift_force', 'hold_time', 'start_penetration', 'contact_distance', 'success_fraction')
    def __copy__(self) -> SimSettings:
        ...
    def __deepcopy__(self, memo: typing.Any) -> SimSettings:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    @typing.overload
    def __init__(self) -> None:
        """
        The defaults: those of the default-constructed C++ struct.
        """
    @typing.overload
    def __init__(self, **kwargs) -> None:
        """
        Keyword constructor: any of the fields (gravity, time_step, solver_iterations, hand_friction, object_friction, support_friction, object_mass, grip_force, close_speed, close_overshoot, close_time, position_gain, lift_height, lift_speed, lift_force, hold_time, start_penetration, contact_distance, success_fraction); the others keep their defaults.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def close_overshoot(self) -> float:
        """
        motor targets lie this fraction of (grasp - pregrasp) past the grasp joints
        """
    @close_overshoot.setter
    def close_overshoot(self, arg0: typing.Any) -> None:
        ...
    @property
    def close_speed(self) -> float:
        """
        m/s: fingertip speed limit while closing (sim_closing_speeds)
        """
    @close_speed.setter
    def close_speed(self, arg0: typing.Any) -> None:
        ...
    @property
    def close_time(self) -> float:
        """
        s spent closing before the lift
        """
    @close_time.setter
    def close_time(self, arg0: typing.Any) -> None:
        ...
    @property
    def contact_distance(self) -> float:
        """
        m: contact points closer than this count as touching
        """
    @contact_distance.setter
    def contact_distance(self, arg0: typing.Any) -> None:
        ...
    @property
    def gravity(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        m/s^2 (3,)
        """
    @gravity.setter
    def gravity(self, arg1: typing.Any) -> None:
        ...
    @property
    def grip_force(self) -> float:
        """
        N (N m): force limit of every finger joint motor
        """
    @grip_force.setter
    def grip_force(self, arg0: typing.Any) -> None:
        ...
    @property
    def hand_friction(self) -> float:
        """
        lateral friction coefficient of every hand link
        """
    @hand_friction.setter
    def hand_friction(self, arg0: typing.Any) -> None:
        ...
    @property
    def hold_time(self) -> float:
        """
        s held at the top
        """
    @hold_time.setter
    def hold_time(self, arg0: typing.Any) -> None:
        ...
    @property
    def lift_force(self) -> float:
        """
        N: force limit of the lift joint
        """
    @lift_force.setter
    def lift_force(self, arg0: typing.Any) -> None:
        ...
    @property
    def lift_height(self) -> float:
        """
        m
        """
    @lift_height.setter
    def lift_height(self, arg0: typing.Any) -> None:
        ...
    @property
    def lift_speed(self) -> float:
        """
        m/s
        """
    @lift_speed.setter
    def lift_speed(self, arg0: typing.Any) -> None:
        ...
    @property
    def object_friction(self) -> float:
        """
        < 0: the URDF's <contact><lateral_friction> (0.5 if absent)
        """
    @object_friction.setter
    def object_friction(self, arg0: typing.Any) -> None:
        ...
    @property
    def object_mass(self) -> float:
        """
        kg; < 0: the URDF's
        """
    @object_mass.setter
    def object_mass(self, arg0: typing.Any) -> None:
        ...
    @property
    def position_gain(self) -> float:
        """
        1/s: joint velocity command = gain * position error
        """
    @position_gain.setter
    def position_gain(self, arg0: typing.Any) -> None:
        ...
    @property
    def solver_iterations(self) -> int:
        """
        constraint solver iterations per step
        """
    @solver_iterations.setter
    def solver_iterations(self, arg0: typing.Any) -> None:
        ...
    @property
    def start_penetration(self) -> float:
        """
        m: a start penetrating deeper than this is 'start in collision'
        """
    @start_penetration.setter
    def start_penetration(self, arg0: typing.Any) -> None:
        ...
    @property
    def success_fraction(self) -> float:
        """
        the object must rise by this fraction of lift_height
        """
    @success_fraction.setter
    def success_fraction(self, arg0: typing.Any) -> None:
        ...
    @property
    def support_friction(self) -> float:
        """
        lateral friction of the support plane
        """
    @support_friction.setter
    def support_friction(self, arg0: typing.Any) -> None:
        ...
    @property
    def time_step(self) -> float:
        """
        s (pybullet's default)
        """
    @time_step.setter
    def time_step(self, arg0: typing.Any) -> None:
        ...
class SimObject:
    """
    An object to grasp from a one-link URDF: collision meshes as convex hulls, mass, friction.
    """
    @staticmethod
    def from_urdf(path: typing.Any) -> SimObject:
        """
        Reads a one-link object URDF; ValueError names a missing or unusable file.
        """
    def rest_pose(self, x: typing.Any = 0.0, y: typing.Any = 0.0, orientation: typing.Any = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 1]"]:
        """
        The link pose (7,) resting the object on z = 0 at (x, y) with orientation [qx, qy, qz, qw].
        """
    @property
    def inertia_scaling(self) -> float:
        """
        the URDF's <contact><inertia_scaling>, 1 if none
        """
    @property
    def lateral_friction(self) -> float:
        """
        the URDF's <contact> value, -1 if none
        """
    @property
    def mass(self) -> float:
        """
        kg
        """
    @property
    def model(self) -> Hand:
        """
        The object as a (one-link) Hand: its collision geometry.
        """
    @property
    def source(self) -> str:
        ...
class SimResult:
    """
    The outcome of one grasp execution.
    """
    def __repr__(self) -> str:
        ...
    @property
    def contact_count(self) -> int:
        """
        hand-object contact points at the end
        """
    @property
    def lift_height(self) -> float:
        """
        m the object's centre of mass rose
        """
    @property
    def object_pose(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 1]"]:
        """
        the object's final link pose (7,)
        """
    @property
    def reason(self) -> str:
        """
        'success', 'start in collision', 'no contact' or 'not held'
        """
    @property
    def simulated_time(self) -> float:
        """
        s
        """
    @property
    def start_penetration(self) -> float:
        """
        m
        """
    @property
    def steps(self) -> int:
        ...
    @property
    def success(self) -> bool:
        ...
    @property
    def wall_time(self) -> float:
        """
        s
        """
class SceneSimResult:
    """
    The outcome of one grasp in a scene of several objects.
    """
    @property
    def lifted(self) -> list[int]:
        """
        indices of the objects that rose and are held by the hand
        """
    @property
    def moved(self) -> list[float]:
        """
        m each object's link origin moved
        """
    @property
    def object_poses(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, 7) every object's final link pose
        """
    @property
    def result(self) -> SimResult:
        """
        SimResult: outcome of the grasp; lift_height and object_pose of the object that rose most
        """
    @property
    def rise(self) -> list[float]:
        """
        m each object's centre of mass rose
        """
class SettleResult:
    """
    A scene simulated without a hand until its objects rest.
    """
    @property
    def at_rest(self) -> bool:
        """
        every object came to rest in time
        """
    @property
    def object_poses(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (N, 7) every object's final link pose
        """
    @property
    def simulated_time(self) -> float:
        """
        s
        """
    @property
    def steps(self) -> int:
        ...
def build_info() -> dict[str, str]:
    """
    Versions of graspmix and of every library it was built against.
    """
def camera_pose_matrix(pose: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 4]"]:
    """
    The 4x4 T_world_camera of [x, y, z, qx, qy, qz, qw], its quaternion normalised; ValueError for a non-finite value or a quaternion whose norm is off 1 by more than 1e-3 (kUnitQuaternionTolerance).
    """
def complete_object(points: typing.Any, plane: typing.Any, visibility: VisibilityModel, *, settings: typing.Any = None, **kwargs) -> Completion:
    """
    The unseen side of one object: its observed points (N, 3; voxelised, world frame), the support plane
    [a, b, c, d] ((a, b, c) unit, towards the cameras) and the VisibilityModel of what the cameras saw
    (scene.result.visibility). Mirror, rotation and extrusion hypotheses are scored by the views (the rule:
    include/graspmix/perception/completion.hpp); ValueError naming the cause for bad input.
    Settings: settings= a CompletionSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      spacing = 0.003: m: the completed points' spacing, the profile's and footprint's bins
      max_free_fraction = 0.05: a hypothesis with more of its points in seen-free space is refused, in [0, 1]
      min_unseen_fraction = 0.15: a hypothesis with less of its points in unseen space is refused, in [0, 1]
      free_weight = 4.0: score = surface_fraction - free_weight * free_fraction (>= 0)
      mirror_angle_step = 0.07: rad: the step between mirror planes' orientations around each principal axis
      mirror_angle_steps = 3: orientations each side of each principal axis (0..20)
      mirror_max_depth = 0.05: m: a mirror plane lies at most this far behind the footprint's far edge
      circle_max_rms = 0.003: m: a rotation needs the outline's inliers within this RMS of their circle
      circle_min_inliers = 0.7: the fraction of the outline within 2 circle_max_rms of its circle for a rotation
      max_radius = 0.25: m: no rotation about a larger circle
      normal_radius = 0.01: m: the neighbourhood of the observed points' normals (> spacing)
      max_scoring_points = 160: points each hypothesis is scored on (>= 16)
      border_margin = 2.0: px: an observed point this close to a pinhole image's edge sets the border warning
      min_height = 0.005: m: completed points lower than this above the support plane are dropped (the table's clearance)
      rotation_margin = 0.05: the rotation wins unless the best accepted mirror scores more than this above it
      observed_clearance = 0.006: m: no completed point within this of an observed point (the seen surface is not doubled)
    """
def complete_scene(scene: Segmentation, *, settings: typing.Any = None, **kwargs) -> SceneCompletion:
    """
    Each object of a Segmentation completed (complete_object) from its visibility model and plane; without either nothing is completed and a note says why; an object complete_object refuses stays as seen, with a note. ValueError for settings out of range.
    """
def compute_surface_features(points: typing.Any, radius: typing.Any = None, normals: typing.Any = None, viewpoints: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> SurfaceCloud:
    """
    O(v, r) of a cloud (N, 3): normals (the smallest eigenvector of each radius neighbourhood's covariance, PCL NormalEstimation's definition, computed in parallel here; or the given (N, 3)), outward by `orientation` (auto: towards viewpoints (3,) / (N, 3) when given, else given normals as they are, else propagated outward over the surface; or 'viewpoint', 'propagate', 'centroid', 'given'), principal curvatures (PCL, radius in m) and frames. Points with fewer than min_neighbours neighbours within radius are dropped (see indices, n_dropped). x is PCL's principal direction where (k1 - k2) / k1 >= min_anisotropy and k1 >= flat_curvature, else world z projected on the tangent plane (world x near +-z). radius=None: the settings' radius.
    Settings: settings= a SurfaceFeatureSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      radius = 0.01: m: neighbourhood radius of normals and curvatures (paper: 1 cm)
      min_neighbours = 10: points with fewer neighbours within radius (itself included) are dropped
      min_anisotropy = 0.25: the principal direction is x only where (k1 - k2) / k1 >= min_anisotropy ...
      flat_curvature = 0.0001: ... and k1 >= flat_curvature (dimensionless)
      orientation = 'auto': how normals are turned outward: auto | viewpoint | propagate | centroid | given
      orientation_neighbours = 10: k of the propagation graph
      n_threads = 0: 0 = OpenMP's default, else 1..256; results do not depend on it
      max_neighbours = 5000: a neighbourhood holding more points is refused (voxel-downsample such a dense cloud first); 0: no cap
    """
def contact_data(hand: Hand, link: typing.Any, T_world_wrist: typing.Any, joints: typing.Any, frames: typing.Any, features: typing.Any, settings: typing.Any = None, **kwargs) -> ContactData:
    """
    eq:relative_pose_u_mixture: the contact points of one link in a demonstrated grasp, u = v^-1 o s.
    Settings: settings= a ContactSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      max_distance = 0.01: m: object points farther than this from a link's geometry are not its contacts
      lambda_ = 5000.0: 1/m^2: a contact at distance d weighs exp(-lambda d^2)
      min_points = 10: a link with fewer contact points gets no contact model
    """
def learn_contact_models(hand: Hand, T_world_wrist: typing.Any, joints: typing.Any, frames: typing.Any, features: typing.Any, make_density: collections.abc.Callable, settings: typing.Any = None, **kwargs) -> list[ContactModel]:
    """
    A contact model for every link with enough object points near it in the demonstrated grasp.
    Settings: settings= a ContactSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      max_distance = 0.01: m: object points farther than this from a link's geometry are not its contacts
      lambda_ = 5000.0: 1/m^2: a contact at distance d weighs exp(-lambda d^2)
      min_points = 10: a link with fewer contact points gets no contact model
    """
def load_cloud(path: typing.Any) -> CloudData:
    """
    Reads a .pcd (ascii, binary, binary_compressed), .ply or .npy (N, 3) cloud. NaN points are dropped (counted in n_invalid; an organised file keeps each point's pixel in `pixels`, organized() gives the grid); extra fields are listed in `fields`. ValueError names the file and the problem.
    """
def load_mesh(path: typing.Any, scale: typing.Any = None) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 3]"]]:
    """
    (vertices (V, 3), triangles (T, 3)) of every triangle in a mesh file (STL, OBJ, ... via assimp), scaled.
    """
def log_vmf_s3_normaliser(kappa: typing.Any) -> float:
    """
    log of the hemisphere-restricted antipodal vMF normaliser on S^3 used by PoseKDE.
    """
def object_surface(scene: Segmentation, viewpoints: typing.Any, completions: collections.abc.Sequence[Completion | None], index: typing.SupportsInt | typing.SupportsIndex, *, settings: typing.Any = None, **kwargs) -> SurfaceCloud:
    """
    Object `index`'s surface features as synthesize_scene computes them: a Segmentation, each of its points' camera (M, 3) or None, per object its Completion or None (include/graspmix/grasp/scene_synthesis.hpp).
    """
def orient_plane(plane: typing.Any, points: typing.Any, rule: str) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[4, 1]"]:
    """
    The plane [a, b, c, d] or its negation, whichever has the points on its positive side by `rule`
    (majority: more points strictly above; mean / median of their signed heights >= 0). The one rule of
    docs/design.md that every part orienting a support plane uses.
    """
def pose_inverse(a: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 7]"]:
    """
    Row-wise inverse of (N, 7) poses.
    """
def pose_multiply(a: typing.Any, b: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 7]"]:
    """
    Row-wise a o b over (N, 7) poses [x, y, z, qx, qy, qz, qw]; a side with one row is broadcast.
    """
def prepare_cloud(points: typing.Any, *, settings: typing.Any = None, **kwargs) -> CleanupResult:
    """
    Scene clean-up before features, in this order: crop box [crop_min, crop_max] (on when either is given as a keyword), voxel grid, statistical outlier removal, and removal of the dominant plane by seeded RANSAC (it must hold plane_min_fraction of the points) together with the points below it.
    Settings: settings= a CleanupSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      crop = False: keep only points inside [crop_min, crop_max]
      crop_min = array([-inf, -inf, -inf]): m (3,), the cloud's frame
      crop_max = array([inf, inf, inf]): m (3,), the cloud's frame
      voxel_size = 0.003: m: voxel-grid leaf size, 0 = off (demonstration and query clouds must share it)
      remove_outliers = True: PCL StatisticalOutlierRemoval
      outlier_neighbours = 20: k of the mean-distance statistic
      outlier_std_ratio = 2.0: drop points whose mean k-distance exceeds mean + ratio * std
      remove_plane = True: find the dominant plane by RANSAC and remove it
      plane_distance = 0.005: m: RANSAC inlier threshold
      plane_max_iterations = 1000: RANSAC iterations
      plane_min_fraction = 0.2: fraction of the cleaned points a plane needs to count as the support
      remove_below_plane = True: also drop points on the far side of the plane from the object
      seed = 0: seeds RANSAC (None: 0)
    """
def quat_exp(w: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 4]"]:
    """
    eq:exp_map on (N, 3) rotation vectors (half-angle convention) -> (N, 4) quaternions [x, y, z, w].
    """
def quat_log(q: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    eq:log_map on (N, 4) quaternions [x, y, z, w]: arccos(w) v/|v| after canonicalising w >= 0 -> (N, 3).
    """
def query_weights(surface: SurfaceCloud, n_observed: typing.SupportsInt | typing.SupportsIndex, completed_weight: typing.SupportsFloat | typing.SupportsIndex) -> typing.Any:
    """
    Each surface point's prior weight in the query densities (1 observed, completed_weight completed: the points from n_observed on); None when nothing is completed.
    """
def save_cloud(path: typing.Any, points: typing.Any, normals: typing.Any = None, encoding: str = 'binary', viewpoint: typing.Any = None, viewpoints: typing.Any = None, width: typing.Any = 0, height: typing.Any = 0) -> None:
    """
    Writes float32 x y z (+ normal_x normal_y normal_z, + vp_x vp_y vp_z) to .pcd (encoding ascii | binary | binary_compressed) or .ply (ascii | binary); viewpoint [x, y, z, qx, qy, qz, qw] goes into the header, viewpoints (N, 3), one camera position per point, into the fields vp_x vp_y vp_z (PCL's PointWithViewpoint). width x height: 0 x 0 writes the finite points unorganised; height > 1 an organised .pcd of width * height rows (row v * width + u is pixel (u, v); a row with NaN is a hole). PLY keeps no image grid: an organised cloud is a ValueError there.
    """
def segment_depth(depth: typing.Any, camera: PinholeCamera, T_world_camera: typing.Any, plane: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> Segmentation:
    """
    The support plane and the objects of one depth image (H, W) in metres along z (NaN, 0, inf: no return)
    of `camera` (PinholeCamera) posed at T_world_camera [x, y, z, qx, qy, qz, qw]: segment_scene's scene in the
    world frame, made in image space (include/graspmix/perception/depth_scene.hpp); sources are pixel indices.
    Settings: settings= a SegmentationSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      voxel_size = 0.003: m: voxel-grid leaf size, 0 = off (CleanupSettings')
      plane_distance = 0.005: m: RANSAC inlier threshold
      plane_max_iterations = 1000: RANSAC iterations per candidate
      seed = 0: seeds RANSAC (None: 0)
      find_plane = True: search for the support plane (false: objects only)
      plane_candidates = 3: planes tried, each on the points the previous ones left
      plane_min_fraction = 0.05: rule 1: fraction of the voxelised points a candidate holds
      plane_behind_distance = 0.01: m, rule 3: how far behind the plane a point counts as behind it
      plane_max_behind_fraction = 0.05: rule 3: fraction of all points allowed behind the plane
      plane_margin = 0.01: m, rule 4: how far the plane's inliers must reach beyond the objects' footprint
      table_clearance = 0.005: m: points at most this far above the support plane (or behind it) are the table
      remove_outliers = True: statistical outlier removal on the object points
      outlier_neighbours = 20: k of the mean-distance statistic
      outlier_std_ratio = 2.0: drop points whose mean k-distance exceeds mean + ratio * std
      cluster_tolerance = 0.006: m: object points closer than this are one object (Euclidean clusters)
      min_cluster_size = 20: smaller clusters are noise, dropped
      max_cluster_size = 0: larger clusters are dropped; 0 = no limit
      merge_seen_through = True: a cluster seen through a larger one joins it (a container's inside seen over its rim)
      merge_through_fraction = 0.2: fraction of a cluster's lines of sight that must cross the larger one's envelope
      merge_inset = 0.006: m: the larger cluster's envelope is inset by this
      join_occluded = True: clusters whose gap the view leaves unseen (a shadow between them) join: pieces of one object
      join_max_gap = 0.03: m, join rule 1: clusters farther apart never join
      join_seen_margin = 0.005: m, join rule 2: the gap was seen empty when the views saw more than this beyond it (median)
      join_max_size = 0.15: m, join rule 3: the joined cluster's largest principal-box side
      split_touching = True: a cluster is cut along its concave creases into the objects touching in it (the split rule)
      split_voxel_resolution = 0.004: m: the split rule's supervoxel voxel (at least voxel_size)
      split_seed_resolution = 0.015: m: the split rule's supervoxel seed spacing
      split_concavity_tolerance = 0.35: rad: a crease less concave than this is no cut (LCCP)
      split_min_points = 150: a split piece with fewer points goes back to the neighbour it touches most
      split_max_size = 0.15: m: one object's largest principal-box side; only larger clusters are cut, and pieces re-join within it
      split_named_max_size = 0.12: m: with a point target, its segment is tried again by the split rule gated at this size (split_object_near)
      visibility_tolerance = 0.008: m: Segmentation.visibility's surface_tolerance (within this of the observed surface is Surface)
      visibility_resolution = 0.005: rad: the bin of Segmentation.visibility's range images (VisibilitySettings.angular_resolution)
      visibility_median_window = 1: px: segment_depth's visibility model keeps the depth image median-filtered over (2 r + 1)^2 pixels
    (0: as it is), against lone outline pixels that see through an object
      image_stride = 0: px: segment_depth's block side, 0 = the largest within half a voxel_size at the median depth
      plane_image_stride = 4: px: segment_depth's block side for the support plane's search (at most image_stride: those)
      workspace = []: m: the world-frame box [x_min, y_min, z_min, x_max, y_max, z_max] the input is cropped to first; [] = none
    """
def segment_organized(points: typing.Any, T_world_camera: typing.Any, plane: typing.Any = None, *, height: typing.Any = None, width: typing.Any = None, camera: PinholeCamera | None = None, settings: typing.Any = None, **kwargs) -> Segmentation:
    """
    The support plane and the objects of an organized cloud in the sensor frame (x right, y down, z forward;
    NaN = no return), (H, W, 3) or (H * W, 3) with height and width, from a camera posed at T_world_camera: its
    intrinsics fitted (or `camera`, a PinholeCamera fitted already), then as segment_depth.
    Settings: settings= a SegmentationSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      voxel_size = 0.003: m: voxel-grid leaf size, 0 = off (CleanupSettings')
      plane_distance = 0.005: m: RANSAC inlier threshold
      plane_max_iterations = 1000: RANSAC iterations per candidate
      seed = 0: seeds RANSAC (None: 0)
      find_plane = True: search for the support plane (false: objects only)
      plane_candidates = 3: planes tried, each on the points the previous ones left
      plane_min_fraction = 0.05: rule 1: fraction of the voxelised points a candidate holds
      plane_behind_distance = 0.01: m, rule 3: how far behind the plane a point counts as behind it
      plane_max_behind_fraction = 0.05: rule 3: fraction of all points allowed behind the plane
      plane_margin = 0.01: m, rule 4: how far the plane's inliers must reach beyond the objects' footprint
      table_clearance = 0.005: m: points at most this far above the support plane (or behind it) are the table
      remove_outliers = True: statistical outlier removal on the object points
      outlier_neighbours = 20: k of the mean-distance statistic
      outlier_std_ratio = 2.0: drop points whose mean k-distance exceeds mean + ratio * std
      cluster_tolerance = 0.006: m: object points closer than this are one object (Euclidean clusters)
      min_cluster_size = 20: smaller clusters are noise, dropped
      max_cluster_size = 0: larger clusters are dropped; 0 = no limit
      merge_seen_through = True: a cluster seen through a larger one joins it (a container's inside seen over its rim)
      merge_through_fraction = 0.2: fraction of a cluster's lines of sight that must cross the larger one's envelope
      merge_inset = 0.006: m: the larger cluster's envelope is inset by this
      join_occluded = True: clusters whose gap the view leaves unseen (a shadow between them) join: pieces of one object
      join_max_gap = 0.03: m, join rule 1: clusters farther apart never join
      join_seen_margin = 0.005: m, join rule 2: the gap was seen empty when the views saw more than this beyond it (median)
      join_max_size = 0.15: m, join rule 3: the joined cluster's largest principal-box side
      split_touching = True: a cluster is cut along its concave creases into the objects touching in it (the split rule)
      split_voxel_resolution = 0.004: m: the split rule's supervoxel voxel (at least voxel_size)
      split_seed_resolution = 0.015: m: the split rule's supervoxel seed spacing
      split_concavity_tolerance = 0.35: rad: a crease less concave than this is no cut (LCCP)
      split_min_points = 150: a split piece with fewer points goes back to the neighbour it touches most
      split_max_size = 0.15: m: one object's largest principal-box side; only larger clusters are cut, and pieces re-join within it
      split_named_max_size = 0.12: m: with a point target, its segment is tried again by the split rule gated at this size (split_object_near)
      visibility_tolerance = 0.008: m: Segmentation.visibility's surface_tolerance (within this of the observed surface is Surface)
      visibility_resolution = 0.005: rad: the bin of Segmentation.visibility's range images (VisibilitySettings.angular_resolution)
      visibility_median_window = 1: px: segment_depth's visibility model keeps the depth image median-filtered over (2 r + 1)^2 pixels
    (0: as it is), against lone outline pixels that see through an object
      image_stride = 0: px: segment_depth's block side, 0 = the largest within half a voxel_size at the median depth
      plane_image_stride = 4: px: segment_depth's block side for the support plane's search (at most image_stride: those)
      workspace = []: m: the world-frame box [x_min, y_min, z_min, x_max, y_max, z_max] the input is cropped to first; [] = none
    """
def segment_scene(points: typing.Any, viewpoints: typing.Any = None, plane: typing.Any = None, *, settings: typing.Any = None, **kwargs) -> Segmentation:
    """
    The support plane and the objects of a scene cloud (N, 3) seen from viewpoints (None: a camera at the origin; (3,) or (N, 3)); plane [a, b, c, d] gives a known support. The rule that accepts a plane is in include/graspmix/perception/segmentation.hpp.
    Settings: settings= a SegmentationSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      voxel_size = 0.003: m: voxel-grid leaf size, 0 = off (CleanupSettings')
      plane_distance = 0.005: m: RANSAC inlier threshold
      plane_max_iterations = 1000: RANSAC iterations per candidate
      seed = 0: seeds RANSAC (None: 0)
      find_plane = True: search for the support plane (false: objects only)
      plane_candidates = 3: planes tried, each on the points the previous ones left
      plane_min_fraction = 0.05: rule 1: fraction of the voxelised points a candidate holds
      plane_behind_distance = 0.01: m, rule 3: how far behind the plane a point counts as behind it
      plane_max_behind_fraction = 0.05: rule 3: fraction of all points allowed behind the plane
      plane_margin = 0.01: m, rule 4: how far the plane's inliers must reach beyond the objects' footprint
      table_clearance = 0.005: m: points at most this far above the support plane (or behind it) are the table
      remove_outliers = True: statistical outlier removal on the object points
      outlier_neighbours = 20: k of the mean-distance statistic
      outlier_std_ratio = 2.0: drop points whose mean k-distance exceeds mean + ratio * std
      cluster_tolerance = 0.006: m: object points closer than this are one object (Euclidean clusters)
      min_cluster_size = 20: smaller clusters are noise, dropped
      max_cluster_size = 0: larger clusters are dropped; 0 = no limit
      merge_seen_through = True: a cluster seen through a larger one joins it (a container's inside seen over its rim)
      merge_through_fraction = 0.2: fraction of a cluster's lines of sight that must cross the larger one's envelope
      merge_inset = 0.006: m: the larger cluster's envelope is inset by this
      join_occluded = True: clusters whose gap the view leaves unseen (a shadow between them) join: pieces of one object
      join_max_gap = 0.03: m, join rule 1: clusters farther apart never join
      join_seen_margin = 0.005: m, join rule 2: the gap was seen empty when the views saw more than this beyond it (median)
      join_max_size = 0.15: m, join rule 3: the joined cluster's largest principal-box side
      split_touching = True: a cluster is cut along its concave creases into the objects touching in it (the split rule)
      split_voxel_resolution = 0.004: m: the split rule's supervoxel voxel (at least voxel_size)
      split_seed_resolution = 0.015: m: the split rule's supervoxel seed spacing
      split_concavity_tolerance = 0.35: rad: a crease less concave than this is no cut (LCCP)
      split_min_points = 150: a split piece with fewer points goes back to the neighbour it touches most
      split_max_size = 0.15: m: one object's largest principal-box side; only larger clusters are cut, and pieces re-join within it
      split_named_max_size = 0.12: m: with a point target, its segment is tried again by the split rule gated at this size (split_object_near)
      visibility_tolerance = 0.008: m: Segmentation.visibility's surface_tolerance (within this of the observed surface is Surface)
      visibility_resolution = 0.005: rad: the bin of Segmentation.visibility's range images (VisibilitySettings.angular_resolution)
      visibility_median_window = 1: px: segment_depth's visibility model keeps the depth image median-filtered over (2 r + 1)^2 pixels
    (0: as it is), against lone outline pixels that see through an object
      image_stride = 0: px: segment_depth's block side, 0 = the largest within half a voxel_size at the median depth
      plane_image_stride = 4: px: segment_depth's block side for the support plane's search (at most image_stride: those)
      workspace = []: m: the world-frame box [x_min, y_min, z_min, x_max, y_max, z_max] the input is cropped to first; [] = none
    """
def select_targets(scene: Segmentation, viewpoints: typing.Any, kind: str, *, index: typing.Any = None, point: typing.Any = None, camera: typing.Any = None) -> list[int]:
    """
    The object indices of a target (kind all, index, point, largest, nearest) in a Segmentation whose points were seen from viewpoints (M, 3) or None (include/graspmix/perception/targets.hpp).
    """
def sim_closing_speeds(hand: Hand, pregrasp: typing.Any, grasp: typing.Any, settings: typing.Any = None, **kwargs) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    The speed limit of every URDF joint (hand.joints order; m/s or rad/s, 0 for fixed joints) while the hand closes from pregrasp to grasp (arrays in hand.joint_names order): the fingertips move at close_speed m/s.
    """
def sim_execute(hand: Hand, object: SimObject, T_world_object: typing.Any, T_world_wrist: typing.Any, pregrasp: typing.Any, grasp: typing.Any, settings: typing.Any = None, **kwargs) -> SimResult:
    """
    Executes one grasp in Bullet (arrays in hand.joint_names order); see graspmix.sim.execute.
    Settings: settings= a SimSettings (None: its defaults), and/or its fields as keywords,
    which override it (an unknown keyword is a ValueError):
      gravity = array([ 0.  ,  0.  , -9.81]): m/s^2 (3,)
      time_step = 0.004166666666666667: s (pybullet's default)
      solver_iterations = 50: constraint solver iterations per step
      hand_friction = 1.0: lateral friction coefficient of every hand link
      object_friction = -1.0: < 0: the URDF's <contact><lateral_friction> (0.5 if absent)
      support_friction = 1.0: lateral friction of the support plane
      object_mass = -1.0: kg; < 0: the URDF's
      grip_force = 40.0: N (N m): force limit of every finger joint motor
      close_speed = 0.2: m/s: fingertip speed limit while closing (sim_closing_speeds)
      close_overshoot = 0.5: motor targets lie this fraction of (grasp - pregrasp) past the grasp joints
      close_time = 0.5: s spent closing before the lift
      position_gain = 20.0: 1/s: joint velocity command = gain * position error
      lift_height = 0.2: m
      lift_speed = 0.5: m/s
      lift_force = 1000.0: N: force limit of the lift joint
      hold_time = 0.5: s held at the top
      start_penetration = 0.002: m: a start penetrating deeper than this is 'start in collision'
      contact_distance = 0.001: m: contact points closer than this count as touching
      success_fraction = 0.5: the object must rise by this fraction of lift_height
    """
def sim_execute_scene(hand: Hand, objects: typing.Any, object_poses: typing.Any, T_world_wrist: typing.Any, pregrasp: typing.Any, grasp: typing.Any, settings: typing.Any = None, **kwargs) -> SceneSimResult:
    """
    Executes one grasp among several objects (link poses (N, 7)); see graspmix.sim.scenes.execute_in_scene.
    """
def sim_settle_scene(objects: typing.Any, object_poses: typing.Any, settings: typing.Any = None, seconds: typing.Any = 2.0, walls: typing.Any = None) -> SettleResult:
    """
    Simulates the objects without a hand until they rest (at most `seconds`); walls: [xmin, ymin, xmax, ymax, height] of a box standing around them, or None.
    """
def solid_volume(points: typing.Any, plane: typing.Any, *, resolution: typing.SupportsFloat | typing.SupportsIndex = 0.005, gap: typing.SupportsFloat | typing.SupportsIndex = 0.005) -> OccupancyMap:
    """
    The solid columns of objects (points (N, 3)) standing on plane [a, b, c, d]: an OccupancyMap whose occupied
    cells lie under the points' tops (the rule: include/graspmix/grasp/solid_volume.hpp); resolution, gap in m.
    """
def synthesize_scene(types: typing.Any, *, depth: typing.Any = None, organized: typing.Any = None, points: typing.Any = None, viewpoints: typing.Any = None, camera: PinholeCamera | None = None, T_world_camera: typing.Any = None, plane: typing.Any = None, target: str = 'all', target_index: typing.Any = None, target_point: typing.Any = None, approach_axis: typing.Any = None, reachable: typing.Any = None, experts: typing.Any = None, segmentation: typing.Any = None, completion: typing.Any = None, features: typing.Any = None, synthesizer: typing.Any = None, collision: typing.Any = None, occupancy: typing.Any = None, kinematic: typing.Any = None, axis_alignment: typing.Any = None, approach: typing.Any = None, contact_quality: typing.Any = None, grasp_depth: typing.Any = None) -> SceneSynthesis:
    """
    The whole path from one view or a cloud to ranked grasps (include/graspmix/grasp/scene_synthesis.hpp).
    types: [(GraspSynthesizer, name, log_reference or None)]; the input: depth (H, W) metres with camera and
    T_world_camera [x, y, z, qx, qy, qz, qw], or organized (H * W, 3) sensor frame with camera and the pose, or
    points (N, 3) world frame with viewpoints (None, (3,) or (N, 3)); target: all | index | point | largest |
    nearest (target_index, target_point); the settings of each part (completion, kinematic, approach,
    contact_quality and grasp_depth None: that step off; the others None: their defaults).
    """
COMPLETED_VIEW_DISTANCE: float = 1.0
MAX_OVERSAMPLE: int = 100
POINT_TARGET_MAX_DISTANCE: float = 0.05
TYPE_REFERENCE_TERM: str = 'type_reference'
URDF_AXES_ELEMENT: str = 'graspmix'
