#include <random>

#include "common.hpp"
#include "graspmix/density/gmm.hpp"
#include "graspmix/density/kde.hpp"
#include "graspmix/density/pose_mixture.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

py::array_t<double> covariances_array(const std::vector<Eigen::MatrixXd>& covs) {
  const py::ssize_t K = static_cast<py::ssize_t>(covs.size());
  const py::ssize_t d = K ? covs[0].rows() : 0;
  py::array_t<double> out({K, d, d});
  auto r = out.mutable_unchecked<3>();
  for (py::ssize_t k = 0; k < K; ++k)
    for (py::ssize_t i = 0; i < d; ++i)
      for (py::ssize_t j = 0; j < d; ++j) r(k, i, j) = covs[k](i, j);
  return out;
}

std::vector<Eigen::MatrixXd> covariances_from(const py::object& obj, Eigen::Index K, Eigen::Index d) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a || a.ndim() != 3 || a.shape(0) != K || a.shape(1) != d || a.shape(2) != d) {
    throw py::value_error("covariances: expected shape (" + std::to_string(K) + ", " + std::to_string(d) + ", " +
                          std::to_string(d) + ")");
  }
  std::vector<Eigen::MatrixXd> covs(K, Eigen::MatrixXd(d, d));
  auto r = a.unchecked<3>();
  for (Eigen::Index k = 0; k < K; ++k)
    for (Eigen::Index i = 0; i < d; ++i)
      for (Eigen::Index j = 0; j < d; ++j) covs[k](i, j) = r(k, i, j);
  return covs;
}

GaussianMixture mixture_from(const py::object& weights, const py::object& means, const py::object& covariances) {
  const Eigen::VectorXd w = to_vector(weights, "weights");
  const RowMatrixXd mu = to_matrix(means, "means");
  return GaussianMixture::from_parameters(w, mu, covariances_from(covariances, w.size(), mu.cols()));
}

std::vector<int> to_dims(const py::object& obj, const char* name) {
  try {
    return obj.cast<std::vector<int>>();
  } catch (const py::cast_error&) {
    throw py::value_error(std::string(name) + ": expected a sequence of integer dimensions");
  }
}

/// Checked before the features, whose expected width an unfitted density does not know yet.
void require_fitted(const PoseDensity& d, const char* what) {
  if (!d.fitted()) {
    const bool kde = d.kind() == "kde";
    throw py::value_error(std::string(kde ? "PoseKDE." : "PoseMixture.") + what + ": the density is not fitted yet (" +
                          (kde ? "call fit)" : "call fit, or make it with from_parameters)"));
  }
}

/// The methods every PoseDensity shares, bound once on the base class.
void bind_pose_density_base(py::module_& m) {
  py::class_<PoseDensity, std::shared_ptr<PoseDensity>>(
      m, "PoseDensity", "A density over poses given features: PoseMixture (the paper's) or PoseKDE (the baseline).")
      .def_property_readonly("fitted", &PoseDensity::fitted)
      .def_property_readonly("n_features", &PoseDensity::n_features)
      .def_property_readonly("n_kernels", &PoseDensity::n_kernels, "Components (GMM) or kernels (KDE).")
      .def_property_readonly("kind", &PoseDensity::kind, "'gmm' or 'kde'.")
      .def(
          "log_density",
          [](const PoseDensity& d, const py::object& poses, const py::object& features) {
            require_fitted(d, "log_density");
            const PoseArray P = to_poses(poses, "log_density: poses");
            return d.log_density(P, to_features(features, P.rows(), d.n_features(), "log_density: features"));
          },
          py::arg("poses"), py::arg("features") = py::none(),
          "log p(u | r) per row (eq:density_mixture_rigid_body). features: (N, n), or (n,) for every pose.")
      .def(
          "feature_log_density",
          [](const PoseDensity& d, const py::object& features) {
            require_fitted(d, "feature_log_density");
            return d.feature_log_density(to_matrix(features, "feature_log_density: features", d.n_features(), true));
          },
          py::arg("features"), "log p(r) per row (eq:density_mixture_features).")
      .def(
          "sample",
          [](const PoseDensity& d, const py::object& n_obj, const py::object& features, const py::object& seed) {
            const int n = to_count(n_obj, "sample: n", 0, kMaxDraws);
            require_fitted(d, "sample");
            std::mt19937_64 rng(to_seed(seed));
            return d.sample(to_features(features, n, d.n_features(), "sample: features"), rng);
          },
          py::arg("n"), py::arg("features") = py::none(), py::arg("seed") = py::none(),
          "n poses (n, 7) drawn from p(u | r); features (n_features,) for all draws or (n, n_features) one per draw.");
}

}  // namespace

void bind_density(py::module_& m) {
  SettingsClass<GmmSettings>(m, "GmmSettings", "How a GaussianMixture (or PoseMixture) is fitted by EM.")
      .field("n_components", &GmmSettings::n_components, "K, the number of components")
      .field("reg_covar", &GmmSettings::reg_covar, "added to every covariance diagonal (units of the data squared)")
      .field("max_iter", &GmmSettings::max_iter, "EM iterations per initialisation")
      .field("tol", &GmmSettings::tol, "convergence threshold on the change of the mean log-likelihood")
      .field("n_init", &GmmSettings::n_init, "initialisations; the best lower bound wins")
      .seed("seed", &GmmSettings::seed, "seeds the k-means++ initialisation (None: 0; never the clock)")
      .done();

  SettingsClass<KdeSettings>(m, "KdeSettings", "Kernel bandwidths of a PoseKDE (Kopicki et al. 2015).")
      .field("position_bandwidth", &KdeSettings::position_bandwidth, "m: std of the position kernel")
      .field("orientation_bandwidth", &KdeSettings::orientation_bandwidth,
             "rad: approximate std of the rotation angle of the kernel")
      .property(
          "feature_bandwidth", [](const KdeSettings& s) { return s.feature_bandwidth; },
          [](KdeSettings& s, const py::object& v) {
            s.feature_bandwidth = v.is_none() ? Eigen::VectorXd() : to_vector(v, "feature_bandwidth");
          },
          "std per feature (units of the features): one value for all, one per feature, or empty (None) for 0.01")
      .done();

  py::class_<GaussianMixture>(m, "GaussianMixture",
                              "Full-covariance Gaussian mixture fitted by weighted EM, named as scikit-learn's.")
      .def(py::init([](const py::object& settings, const py::kwargs& kw) {
             return GaussianMixture(settings_from<GmmSettings>(settings, kw, "GaussianMixture"));
           }),
           py::arg("settings") = py::none(),
           ("An unfitted mixture, e.g. GaussianMixture(n_components=3, seed=0).\n" + settings_doc<GmmSettings>())
               .c_str())
      .def_property_readonly(
          "settings", [](const GaussianMixture& g) { return GmmSettings(g.settings()); },
          "The GmmSettings it fits with (a copy).")
      .def_static("from_parameters", &mixture_from, py::arg("weights"), py::arg("means"), py::arg("covariances"),
                  "A mixture from weights (K,), means (K, d), covariances (K, d, d).")
      .def(
          "fit",
          [](GaussianMixture& g, const py::object& X, const py::object& weights,
             const py::object& means_init) -> GaussianMixture& {
            const RowMatrixXd x = to_matrix(X, "fit: X");
            const RowMatrixXd mi =
                means_init.is_none() ? RowMatrixXd() : to_matrix(means_init, "fit: means_init", x.cols());
            py::gil_scoped_release release;
            g.fit(x, to_weights(weights, "fit: weights"), mi);
            return g;
          },
          py::arg("X"), py::arg("weights") = py::none(), py::arg("means_init") = py::none(),
          py::return_value_policy::reference_internal, "Weighted EM; returns self.")
      .def(
          "score_samples",
          [](const GaussianMixture& g, const py::object& X) {
            return g.score_samples(to_matrix(X, "score_samples: X"));
          },
          py::arg("X"), "Log density of every row.")
      .def(
          "score",
          [](const GaussianMixture& g, const py::object& X, const py::object& w) {
            return g.score(to_matrix(X, "score: X"), to_weights(w, "score: weights"));
          },
          py::arg("X"), py::arg("weights") = py::none(), "(Weighted) mean log density.")
      .def(
          "predict_proba",
          [](const GaussianMixture& g, const py::object& X) {
            return g.predict_proba(to_matrix(X, "predict_proba: X"));
          },
          py::arg("X"))
      .def(
          "predict",
          [](const GaussianMixture& g, const py::object& X) {
            const RowMatrixXd p = g.predict_proba(to_matrix(X, "predict: X"));
            Eigen::VectorXi out(p.rows());
            for (Eigen::Index i = 0; i < p.rows(); ++i) p.row(i).maxCoeff(&out[i]);
            return out;
          },
          py::arg("X"))
      .def(
          "sample",
          [](const GaussianMixture& g, const py::object& n, const py::object& seed) {
            return g.sample(to_count(n, "sample: n", 0, kMaxDraws), to_seed(seed));
          },
          py::arg("n"), py::arg("seed") = py::none(), "n draws, (n, d).")
      .def(
          "marginal",
          [](const GaussianMixture& g, const py::object& dims) { return g.marginal(to_dims(dims, "marginal: dims")); },
          py::arg("dims"))
      .def(
          "condition",
          [](const GaussianMixture& g, const py::object& dims, const py::object& values) {
            const std::vector<int> d = to_dims(dims, "condition: given_dims");
            return g.condition(d, to_vector(values, "condition: values", static_cast<Eigen::Index>(d.size())));
          },
          py::arg("given_dims"), py::arg("values"),
          "The mixture over the other dimensions (increasing order) given x[given_dims] = values.")
      .def_property_readonly("n_components", &GaussianMixture::n_components)
      .def_property_readonly("weights_", &GaussianMixture::weights)
      .def_property_readonly("means_", &GaussianMixture::means)
      .def_property_readonly("covariances_",
                             [](const GaussianMixture& g) { return covariances_array(g.covariances()); })
      .def_property_readonly("converged_", [](const GaussianMixture& g) { return g.result().converged; })
      .def_property_readonly("n_iter_", [](const GaussianMixture& g) { return g.result().n_iter; })
      .def_property_readonly("lower_bound_", [](const GaussianMixture& g) { return g.result().lower_bound; })
      .def_property_readonly("lower_bound_history_", [](const GaussianMixture& g) { return g.result().history; })
      .def(py::pickle(
          // An unfitted mixture is its settings (as scikit-learn pickles an unfitted estimator's parameters).
          [](const GaussianMixture& g) -> py::tuple {
            if (!g.fitted()) return py::make_tuple(GmmSettings(g.settings()));
            return py::make_tuple(g.weights(), g.means(), covariances_array(g.covariances()));
          },
          [](const py::tuple& t) {
            if (t.size() == 1) return GaussianMixture(t[0].cast<GmmSettings>());
            if (t.size() != 3) throw py::value_error("GaussianMixture: a pickled state has 1 or 3 entries");
            return mixture_from(t[0], t[1], t[2]);
          }))
      .def("__repr__", [](const GaussianMixture& g) {
        return "GaussianMixture(n_components=" + std::to_string(g.settings().n_components) +
               (g.fitted() ? ", dim=" + std::to_string(g.dim()) + ")" : ", not fitted)");
      });

  bind_pose_density_base(m);

  py::class_<PoseMixture, PoseDensity, std::shared_ptr<PoseMixture>>(
      m, "PoseMixture",
      "The paper's mixture over (p, q, r), fitted in (p, log q, r): p(u|r) by conditioning, p(r) by marginalising.")
      .def(py::init([](const py::object& settings, const py::kwargs& kw) {
             return PoseMixture(
                 settings_from<GmmSettings>(settings, kw, "PoseMixture", PoseMixture::default_settings()));
           }),
           py::arg("settings") = py::none(),
           ("An unfitted pose mixture. Its defaults are PoseMixture.default_settings() (the paper's K = 2), not\n"
            "GmmSettings()'s.\n" +
            settings_doc<GmmSettings>(PoseMixture::default_settings()))
               .c_str())
      .def_static("default_settings", &PoseMixture::default_settings, "GmmSettings with the paper's K = 2 components.")
      .def_property_readonly(
          "settings", [](const PoseMixture& d) { return GmmSettings(d.settings()); },
          "The GmmSettings it fits with (a copy).")
      .def(
          "fit",
          [](PoseMixture& d, const py::object& poses, const py::object& features,
             const py::object& weights) -> PoseMixture& {
            const PoseArray P = to_poses(poses, "fit: poses");
            const RowMatrixXd F = features.is_none() ? RowMatrixXd(P.rows(), 0) : to_matrix(features, "fit: features");
            const Eigen::VectorXd w = to_weights(weights, "fit: weights");
            py::gil_scoped_release release;
            d.fit(P, F, w);
            return d;
          },
          py::arg("poses"), py::arg("features") = py::none(), py::arg("weights") = py::none(),
          py::return_value_policy::reference_internal,
          "Fits to poses (N, 7), features (N, n), weights (N,); returns self.")
      .def_static(
          "from_parameters",
          [](const py::object& reference, const GaussianMixture& joint) {
            const Eigen::VectorXd q = to_vector(reference, "reference", 4);
            return PoseMixture::from_parameters(Eigen::Quaterniond(q[3], q[0], q[1], q[2]), joint);
          },
          py::arg("reference"), py::arg("joint"))
      .def_property_readonly("joint", &PoseMixture::joint, "The mixture over (p, log(q_ref^-1 q), r).")
      .def_property_readonly(
          "reference",
          [](const PoseMixture& d) {
            const auto& q = d.reference();
            return Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
          },
          "The chart's reference rotation [x, y, z, w].")
      .def(py::pickle(
          [](const PoseMixture& d) {
            const auto& q = d.reference();
            return py::make_tuple(Eigen::Vector4d(q.x(), q.y(), q.z(), q.w()), d.joint());
          },
          [](const py::tuple& t) {
            const Eigen::VectorXd q = to_vector(t[0], "reference", 4);
            return PoseMixture::from_parameters(Eigen::Quaterniond(q[3], q[0], q[1], q[2]),
                                                t[1].cast<GaussianMixture>());
          }));

  py::class_<PoseKDE, PoseDensity, std::shared_ptr<PoseKDE>>(
      m, "PoseKDE", "Kopicki et al. 2015's non-parametric density: one weighted kernel per data point.")
      .def(py::init([](const py::object& settings, const py::kwargs& kw) {
             return PoseKDE(settings_from<KdeSettings>(settings, kw, "PoseKDE"));
           }),
           py::arg("settings") = py::none(), ("An unfitted KDE.\n" + settings_doc<KdeSettings>()).c_str())
      .def_property_readonly(
          "settings", [](const PoseKDE& d) { return KdeSettings(d.settings()); },
          "The KdeSettings it was made with (a copy).")
      .def(
          "fit",
          [](PoseKDE& d, const py::object& poses, const py::object& features, const py::object& weights) -> PoseKDE& {
            const PoseArray P = to_poses(poses, "fit: poses");
            const RowMatrixXd F = features.is_none() ? RowMatrixXd(P.rows(), 0) : to_matrix(features, "fit: features");
            d.fit(P, F, to_weights(weights, "fit: weights"));
            return d;
          },
          py::arg("poses"), py::arg("features") = py::none(), py::arg("weights") = py::none(),
          py::return_value_policy::reference_internal)
      .def_property_readonly("concentration", &PoseKDE::concentration)
      .def_property_readonly("positions", &PoseKDE::positions)
      .def_property_readonly("orientations", &PoseKDE::orientations)
      .def_property_readonly("features", &PoseKDE::features)
      .def_property_readonly("weights", &PoseKDE::weights)
      .def_property_readonly("position_bandwidth", [](const PoseKDE& d) { return d.settings().position_bandwidth; })
      .def_property_readonly("orientation_bandwidth",
                             [](const PoseKDE& d) { return d.settings().orientation_bandwidth; })
      .def_property_readonly("feature_bandwidth", &PoseKDE::feature_bandwidth);

  m.def(
      "log_vmf_s3_normaliser", [](const py::object& kappa) { return log_vmf_s3_normaliser(to_number(kappa, "kappa")); },
      py::arg("kappa"), "log of the hemisphere-restricted antipodal vMF normaliser on S^3 used by PoseKDE.");
}

}  // namespace graspmix::py_bind
