// vibration/: structures, joint elements, harmonic balance (AFT) and its analyses
// (nonlinear modes by EPMC, forced response curves, the quasi-static modal estimate).
// SI throughout. The friendly Python face is python/asperity/vibration.py; this file
// binds the C++ objects into asperity._core._vibration.
#include <nanobind/eigen/dense.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/dynamics/case.hpp"
#include "asperity/hysteresis/backbone.hpp"
#include "asperity/vibration/analysis.hpp"
#include "asperity/vibration/case.hpp"
#include "asperity/vibration/contact_elements.hpp"
#include "asperity/vibration/continuation.hpp"
#include "asperity/vibration/elements.hpp"
#include "asperity/vibration/force_response.hpp"
#include "asperity/vibration/harmonic_balance.hpp"
#include "asperity/vibration/loop_fit.hpp"
#include "asperity/vibration/mode_rom.hpp"
#include "asperity/vibration/response_control.hpp"
#include "asperity/vibration/structure.hpp"
#include "bindings.hpp"

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::vibration;

namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// A summary (an element's describe(), a case's summary.json) as dict, list, float, int,
// str, bool, None: the conversion of dynamics.cpp's case summaries.
nb::object summary_to_python(const dynamics::SummaryValue& v) {
  return std::visit(
      [](const auto& x) -> nb::object {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::nullptr_t>) {
          return nb::none();
        } else if constexpr (std::is_same_v<T, dynamics::SummaryArray>) {
          nb::list l;
          for (const auto& e : x) l.append(summary_to_python(e));
          return l;
        } else if constexpr (std::is_same_v<T, dynamics::SummaryObject>) {
          nb::dict d;
          for (const auto& [k, e] : x) d[k.c_str()] = summary_to_python(e);
          return d;
        } else {
          return nb::cast(x);
        }
      },
      v.data);
}

// HarmonicBalance keeps scratch space in its const evaluations (one object per thread):
// a mutex makes one Python object safe when the GIL is released.
struct PyHarmonicBalance {
  HarmonicBalance hb;
  mutable std::mutex mutex;
  PyHarmonicBalance(Structure s, std::vector<PlacedElement> e, const HarmonicBalanceOptions& o)
      : hb(std::move(s), std::move(e), o) {}
};

template <class F>
auto locked(const PyHarmonicBalance& p, F&& f) {
  nb::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(p.mutex);
  return f(p.hb);
}

Vector check_unknowns(const PyHarmonicBalance& p, const Vector& U, const char* name) {
  if (U.size() != p.hb.unknowns()) {
    throw InvalidInput(fmt::format("{} has {} entries: the system has {} unknowns (n_c x dofs)",
                                   name, U.size(), p.hb.unknowns()));
  }
  if (!U.allFinite()) throw InvalidInput(fmt::format("{} holds a NaN or infinity", name));
  return U;
}

void check_omega(double omega) {
  if (!(std::isfinite(omega) && omega > 0.0)) {
    throw InvalidInput(fmt::format("omega = {}: must be finite and > 0 [rad/s]", omega));
  }
}

std::vector<Eigen::Index> dof_list(const std::vector<long>& v) {
  return std::vector<Eigen::Index>(v.begin(), v.end());
}

// Overrides of an analysis's default continuation settings from a dict with the keys of a
// case file's `continuation` table; unknown keys are errors.
ContinuationOptions continuation_options(ContinuationOptions c, const nb::dict& kw) {
  for (auto [k, v] : kw) {
    const std::string key = nb::cast<std::string>(nb::str(k));
    auto number = [&] {
      double x = 0.0;
      if (!nb::try_cast<double>(v, x)) {
        throw InvalidInput(fmt::format("continuation.{} must be a number", key));
      }
      return x;
    };
    auto integer = [&](double largest = 1e6) {
      const double x = number();
      if (!(x >= 1.0 && x <= largest) || x != std::floor(x)) {
        throw InvalidInput(fmt::format("continuation.{} = {}: must be a whole number in [1, {}]",
                                       key, x, largest));
      }
      return x;
    };
    if (key == "step") {
      c.step = number();
    } else if (key == "min_step") {
      c.min_step = number();
    } else if (key == "max_step") {
      c.max_step = number();
    } else if (key == "max_points") {
      c.max_points = static_cast<std::size_t>(integer());
    } else if (key == "target_iterations") {
      c.target_iterations = static_cast<int>(integer());
    } else if (key == "max_angle") {
      c.max_angle = number();
    } else if (key == "max_iterations") {
      c.newton.max_iterations = static_cast<int>(integer());
    } else if (key == "step_tolerance") {
      c.newton.step_tolerance = number();
    } else if (key == "residual_tolerance") {
      c.newton.residual_tolerance = number();
    } else if (key == "chord_unknowns") {
      c.chord_unknowns = static_cast<std::size_t>(integer(1e9));
    } else {
      throw InvalidInput(fmt::format(
          "continuation option \"{}\" is unknown: allowed are step, min_step, max_step, "
          "max_points, target_iterations, max_angle, max_iterations, step_tolerance, "
          "residual_tolerance, chord_unknowns",
          key));
    }
  }
  c.validate();
  return c;
}

Matrix stack(const std::vector<Vector>& v, Eigen::Index cols) {
  Matrix m(static_cast<Eigen::Index>(v.size()), cols);
  for (std::size_t k = 0; k < v.size(); ++k) m.row(static_cast<Eigen::Index>(k)) = v[k];
  return m;
}

nb::dict continuation_dict(const ContinuationResult& c) {
  nb::dict d;
  d["points"] = static_cast<std::size_t>(c.points.size());
  d["newton_iterations"] = c.newton_iterations;
  d["rejected_steps"] = c.rejected_steps;
  d["turning_points"] = c.turning_points;
  d["complete"] = c.complete;
  d["stop_reason"] = c.stop_reason;
  return d;
}

template <class Derived>
nb::object copy_of(const Eigen::MatrixBase<Derived>& x) {
  using Plain = typename Derived::PlainObject;
  return nb::cast(Plain(x), nb::rv_policy::move);
}

nb::list string_list(const std::vector<std::string>& v) {
  nb::list l;
  for (const auto& s : v) l.append(s);
  return l;
}

nb::dict mode_dict(const NonlinearModeResult& r, Eigen::Index unknowns) {
  nb::dict d;
  d["log10_amplitude"] = copy_of(r.log10_amplitude);
  d["amplitude"] = copy_of(r.amplitude);
  d["omega"] = copy_of(r.omega);
  d["frequency_hz"] = copy_of(r.frequency_hz);
  d["xi"] = copy_of(r.xi);
  d["damping_ratio"] = copy_of(r.damping_ratio);
  d["output_amplitude"] = copy_of(r.output_amplitude);
  d["harmonics"] = copy_of(stack(r.harmonics, unknowns));
  d["linear_omega"] = r.linear_omega;
  d["linear_damping_ratio"] = r.linear_damping_ratio;
  d["continuation"] = continuation_dict(r.continuation);
  d["warnings"] = string_list(r.warnings);
  return d;
}

nb::dict curve_dict(const FrequencyResponseCurve& c, Eigen::Index unknowns) {
  nb::dict d;
  d["force_scale"] = c.force_scale;
  d["omega"] = copy_of(c.omega);
  nb::list ha;
  for (const Matrix& h : c.harmonic_amplitude) ha.append(copy_of(h));
  d["harmonic_amplitude"] = ha;
  d["output_amplitude"] = copy_of(c.output_amplitude);
  d["max_displacement"] = copy_of(c.max_displacement);
  d["harmonics"] = copy_of(stack(c.harmonics, unknowns));
  d["continuation"] = continuation_dict(c.continuation);
  d["warnings"] = string_list(c.warnings);
  if (!c.stability.empty()) {
    // Hill's stability per point; exponents as points x reported (real and imaginary).
    const auto np = static_cast<Eigen::Index>(c.stability.size());
    const Eigen::Index ne = c.stability.front().exponents.size();
    Matrix re(np, ne), im(np, ne);
    Vector max_re(np), max_mu(np);
    std::vector<bool> stable;
    std::vector<std::string> kind;
    for (Eigen::Index k = 0; k < np; ++k) {
      const PeriodicStability& p = c.stability[static_cast<std::size_t>(k)];
      re.row(k) = p.exponents.real().transpose();
      im.row(k) = p.exponents.imag().transpose();
      max_re(k) = p.max_real_exponent;
      max_mu(k) = p.max_multiplier_modulus;
      stable.push_back(p.stable);
      kind.push_back(p.instability);
    }
    nb::dict s;
    s["stable"] = stable;
    s["max_real_exponent"] = copy_of(max_re);
    s["max_multiplier_modulus"] = copy_of(max_mu);
    s["instability"] = kind;
    s["exponents_real"] = copy_of(re);
    s["exponents_imag"] = copy_of(im);
    d["stability"] = s;
  }
  return d;
}

nb::dict force_curve_dict(const ForceResponseCurve& c, Eigen::Index unknowns) {
  nb::dict d;
  d["omega"] = c.omega;
  d["force_scale"] = copy_of(c.force_scale);
  nb::list ha;
  for (const Matrix& h : c.harmonic_amplitude) ha.append(copy_of(h));
  d["harmonic_amplitude"] = ha;
  d["output_amplitude"] = copy_of(c.output_amplitude);
  d["max_displacement"] = copy_of(c.max_displacement);
  d["harmonics"] = copy_of(stack(c.harmonics, unknowns));
  nb::list folds;
  for (const ForceResponseFold& f : c.folds) {
    nb::dict fd;
    fd["force_scale"] = f.force_scale;
    fd["output_amplitude"] = copy_of(f.output_amplitude);
    fd["harmonics"] = copy_of(f.harmonics);
    folds.append(fd);
  }
  d["folds"] = folds;
  d["continuation"] = continuation_dict(c.continuation);
  d["warnings"] = string_list(c.warnings);
  return d;
}

nb::dict quasi_static_dict(const QuasiStaticModeResult& r) {
  nb::dict d;
  d["amplitude"] = copy_of(r.amplitude);
  d["omega"] = copy_of(r.omega);
  d["frequency_hz"] = copy_of(r.frequency_hz);
  d["damping_ratio"] = copy_of(r.damping_ratio);
  d["modal_force"] = copy_of(r.modal_force);
  d["dissipation"] = copy_of(r.dissipation);
  d["linear_omega"] = r.linear_omega;
  d["newton_iterations"] = r.newton_iterations;
  d["warnings"] = string_list(r.warnings);
  return d;
}

// The case's system as the pieces of a Python HarmonicBalance.
nb::dict case_system(const VibrationCase& c) {
  nb::dict d;
  d["structure"] = nb::cast(c.structure);
  nb::list elements;
  for (const PlacedElement& pe : c.elements) {
    elements.append(nb::make_tuple(nb::cast(pe.element), copy_of(pe.T), pe.name));
  }
  d["elements"] = elements;
  d["harmonics"] = c.harmonic_balance.harmonics;
  d["time_points"] = c.harmonic_balance.time_points;
  d["output_dofs"] = std::vector<long>(c.output_dofs.begin(), c.output_dofs.end());
  return d;
}

// run_case as a dict: summary (summary.json), the analyses' arrays, complete, warnings.

nb::dict superharmonic_dict(const SuperharmonicResonanceResult& r, Eigen::Index nu) {
  nb::dict d;
  d["harmonic"] = r.harmonic;
  d["force_scale"] = copy_of(r.force_scale);
  d["omega"] = copy_of(r.omega);
  d["output_amplitude"] = copy_of(r.output_amplitude);
  d["output_harmonic_amplitude"] = copy_of(r.output_harmonic_amplitude);
  d["harmonics"] = copy_of(stack(r.harmonics, nu));
  d["continuation"] = continuation_dict(r.continuation);
  d["warnings"] = string_list(r.warnings);
  return d;
}

nb::dict case_result(VibrationCase c, bool stability) {
  if (stability) {
    for (auto& fr : c.frequency_responses) fr.options.stability = true;
  }
  const VibrationResult r = [&] {
    nb::gil_scoped_release release;
    return run_case(c);
  }();
  const auto nu = static_cast<Eigen::Index>(HarmonicBasis(c.harmonic_balance).coefficients() *
                                            static_cast<std::size_t>(c.structure.dofs()));
  nb::dict d;
  d["summary"] = summary_to_python(dynamics::SummaryValue(r.summary));
  d["nonlinear_mode"] =
      r.nonlinear_mode ? nb::object(mode_dict(*r.nonlinear_mode, nu)) : nb::none();
  nb::list curves;
  for (std::size_t k = 0; k < r.frequency_response.size(); ++k) {
    nb::dict cd = curve_dict(r.frequency_response[k], nu);
    cd["table"] = r.frequency_response_table[k] + 1;
    curves.append(cd);
  }
  d["frequency_response"] = curves;
  nb::list force_curves;
  for (std::size_t k = 0; k < r.force_response.size(); ++k) {
    nb::dict cd = force_curve_dict(r.force_response[k], nu);
    cd["table"] = r.force_response_table[k] + 1;
    force_curves.append(cd);
  }
  d["force_response"] = force_curves;
  nb::list amplitude_controls, phase_resonances;
  for (std::size_t k = 0; k < r.amplitude_control.size(); ++k) {
    const AmplitudeControlResult& a = r.amplitude_control[k];
    nb::dict cd;
    cd["table"] = r.amplitude_control_table[k] + 1;
    cd["omega"] = copy_of(a.omega);
    cd["force_scale"] = copy_of(a.force_scale);
    cd["output_amplitude"] = copy_of(a.output_amplitude);
    cd["harmonics"] = copy_of(stack(a.harmonics, nu));
    cd["continuation"] = continuation_dict(a.continuation);
    cd["warnings"] = string_list(a.warnings);
    amplitude_controls.append(cd);
  }
  for (std::size_t k = 0; k < r.phase_resonance.size(); ++k) {
    const PhaseResonanceResult& p = r.phase_resonance[k];
    nb::dict cd;
    cd["table"] = r.phase_resonance_table[k] + 1;
    cd["amplitude"] = copy_of(p.amplitude);
    cd["omega"] = copy_of(p.omega);
    cd["force_scale"] = copy_of(p.force_scale);
    cd["output_amplitude"] = copy_of(p.output_amplitude);
    cd["harmonics"] = copy_of(stack(p.harmonics, nu));
    cd["continuation"] = continuation_dict(p.continuation);
    cd["warnings"] = string_list(p.warnings);
    phase_resonances.append(cd);
  }
  nb::list superharmonics;
  for (std::size_t k = 0; k < r.superharmonic_resonance.size(); ++k) {
    nb::dict cd = superharmonic_dict(r.superharmonic_resonance[k], nu);
    cd["table"] = r.superharmonic_resonance_table[k] + 1;
    superharmonics.append(cd);
  }
  d["amplitude_control"] = amplitude_controls;
  d["phase_resonance"] = phase_resonances;
  d["superharmonic_resonance"] = superharmonics;
  d["quasi_static_mode"] =
      r.quasi_static_mode ? nb::object(quasi_static_dict(*r.quasi_static_mode)) : nb::none();
  d["complete"] = r.complete;
  d["stop_reason"] = r.stop_reason;
  d["remedy"] = r.remedy;
  d["failures"] = r.failures;
  d["warnings"] = string_list(r.warnings);
  d["system"] = case_system(c);
  return d;
}

}  // namespace

void bind_vibration(nb::module_& parent) {
  nb::module_ m = parent.def_submodule(
      "_vibration",
      "C++ objects of the vibration layer; use asperity.vibration (the friendly face).");

  // ---- structure --------------------------------------------------------------------
  nb::class_<Structure>(m, "Structure",
                        "M x'' + C x' + K x = f(t): dense mass, damping and stiffness (SI).")
      .def(
          "__init__",
          [](Structure* self, const Matrix& M, const Matrix& K, const Matrix& C) {
            Structure s{M, K, C};
            s.validate();
            new (self) Structure(std::move(s));
          },
          "M"_a, "K"_a, "C"_a = Matrix(),
          "Validates: square, same sizes, finite, M and K symmetric, M positive definite; an "
          "empty C is zero. Raises InvalidInput naming the matrix.")
      .def_ro("M", &Structure::M)
      .def_ro("K", &Structure::K)
      .def_ro("C", &Structure::C)
      .def_prop_ro("dofs", &Structure::dofs);

  m.def(
      "rayleigh",
      [](const Matrix& M, const Matrix& K, double alpha, double beta) {
        const RayleighDamping d{.alpha = alpha, .beta = beta};
        d.validate();
        if (M.rows() != K.rows() || M.cols() != K.cols()) {
          throw InvalidInput(fmt::format("rayleigh: M is {}x{}, K is {}x{}: sizes differ", M.rows(),
                                         M.cols(), K.rows(), K.cols()));
        }
        return rayleigh(M, K, d);
      },
      "M"_a, "K"_a, "alpha"_a, "beta"_a, "C = alpha M + beta K (alpha, beta >= 0).");
  m.def(
      "read_matrix_market",
      [](const std::string& path) {
        nb::gil_scoped_release release;
        return read_matrix_market(path);
      },
      "path"_a,
      "A MatrixMarket file (coordinate or array, general or symmetric) as a dense array.");
  m.def(
      "linear_modes",
      [](const Matrix& K, const Matrix& M) {
        Structure s{M, K, Matrix()};
        s.validate();  // square, same sizes, finite, symmetric, M positive definite
        const LinearModes lm = [&] {
          nb::gil_scoped_release release;
          return linear_modes(K, M);
        }();
        return std::make_pair(lm.omega, lm.shapes);
      },
      "K"_a, "M"_a,
      "(omega [rad/s] ascending, shapes as columns, mass-normalized, largest entry positive).");

  // ---- elements ---------------------------------------------------------------------
  nb::class_<Element>(m, "Element",
                      "A joint element acting on u = T x and returning T^T f to the structure.")
      .def_prop_ro("type", &Element::type)
      .def_prop_ro("directions", &Element::directions)
      .def_prop_ro("velocity_dependent", &Element::velocity_dependent)
      .def_prop_ro("slip_force", &Element::slip_force, "[N]; inf when unbounded")
      .def_prop_ro("initial_stiffness", &Element::initial_stiffness,
                   "tangent stiffness at rest (directions x directions) [N/m]")
      .def(
          "describe", [](const Element& e) { return summary_to_python(e.describe()); },
          "The parameters in SI as a dict.")
      .def(
          "static_response",
          [](const Element& e, const Vector& u) {
            if (u.size() != static_cast<Eigen::Index>(e.directions())) {
              throw InvalidInput(fmt::format("u has {} entries: the element has {} directions",
                                             u.size(), e.directions()));
            }
            Vector f;
            Matrix K;
            e.static_response(u, f, K);
            return std::make_pair(f, K);
          },
          "u"_a, "(f, df/du) after a monotone push from rest to u.")
      .def(
          "periodic_response",
          [](const Element& e, const Matrix& u, const Matrix& v, bool tangent) {
            const auto D = static_cast<Eigen::Index>(e.directions());
            if (u.cols() != D || u.rows() < 2) {
              throw InvalidInput(
                  fmt::format("u is {}x{}: expected N x {} (samples of one period, N >= 2)",
                              u.rows(), u.cols(), D));
            }
            Matrix vv = v;
            if (vv.size() == 0) vv = Matrix::Zero(u.rows(), D);
            if (vv.rows() != u.rows() || vv.cols() != D) {
              throw InvalidInput(fmt::format("v is {}x{}: expected {}x{} like u", vv.rows(),
                                             vv.cols(), u.rows(), D));
            }
            PeriodicResponse r;
            {
              nb::gil_scoped_release release;
              e.periodic_response(u, vv, tangent, r);
            }
            nb::dict d;
            d["f"] = copy_of(r.f);
            d["du"] = copy_of(r.du);
            d["dv"] = copy_of(r.dv);
            const auto nh = static_cast<Eigen::Index>(r.history.size());
            Eigen::MatrixXd h(nh, 5);
            for (Eigen::Index k = 0; k < nh; ++k) {
              const HistoryTerm& t = r.history[static_cast<std::size_t>(k)];
              h.row(k) << t.i, t.j, t.d, t.d_src, t.value;
            }
            d["history"] = copy_of(h);
            return d;
          },
          "u"_a, "v"_a = Matrix(), "tangent"_a = true,
          "Steady response over one period to samples u, v (N x directions): dict with f, du, "
          "dv (N x directions^2, column d + D e) and history (rows i, j, d, d_src, value).")
      .def("__repr__",
           [](const Element& e) { return "<asperity.vibration element " + e.type() + ">"; });

  m.def("jenkins", &make_jenkins_element, "k_t"_a, "F_s"_a,
        "Jenkins element: spring k_t [N/m] in series with a slider of slip force F_s [N].");
  m.def(
      "iwan4",
      [](double F_S, double K_T, double chi, double beta) {
        return make_iwan4_element({.F_S = F_S, .K_T = K_T, .chi = chi, .beta = beta});
      },
      "F_S"_a, "K_T"_a, "chi"_a, "beta"_a,
      "Segalman's four-parameter Iwan model (SI): F_S [N], K_T [N/m], chi in (-1, 0], beta >= 0.");
  m.def(
      "fit_loops",
      [](const std::vector<std::pair<Vector, Vector>>& loops, const std::string& model) {
        std::vector<MeasuredLoop> ml;
        for (std::size_t k = 0; k < loops.size(); ++k) {
          const auto& [d, q] = loops[k];
          ml.push_back({.delta = std::vector<double>(d.data(), d.data() + d.size()),
                        .Q = std::vector<double>(q.data(), q.data() + q.size()),
                        .unloading = static_cast<std::size_t>(d.size()) / 2,
                        .source = fmt::format("loop {}", k + 1)});
        }
        const auto kind = parse_loop_model(model, "model");
        LoopFit f;
        {
          nb::gil_scoped_release release;
          f = fit_loops(ml, kind);
        }
        nb::dict params;
        for (const auto& p : f.parameters) {
          nb::dict d;
          d["value"] = p.value;
          d["standard_error"] = p.standard_error;
          d["unit"] = p.unit;
          params[p.name.c_str()] = d;
        }
        nb::list qm;
        for (const auto& q : f.Q_model) {
          Vector v = Eigen::Map<const Vector>(q.data(), static_cast<Eigen::Index>(q.size()));
          qm.append(v);
        }
        nb::dict out;
        out["model"] = std::string(to_string(f.model));
        out["parameters"] = params;
        out["residual_rms"] = f.residual_rms;
        out["relative_residual"] = f.relative_residual;
        out["points"] = f.points;
        out["Q_offsets"] = f.Q_offsets;
        out["Q_model"] = qm;
        out["element_toml"] = f.case_toml();
        out["element"] = f.element();
        return out;
      },
      "loops"_a, "model"_a,
      "Least-squares fit of closed loops [(delta, Q), ...] (each: the unloading branch from the\n"
      "largest displacement, then the reloading branch, equal halves, as analyze_fretting's\n"
      "loop_delta, loop_Q) by \"jenkins\" or \"iwan4\" (vibration/loop_fit.hpp).");
  m.def(
      "masing_table",
      [](const Vector& x, const Vector& Q, const std::string& source) {
        return make_masing_table_element(std::vector<double>(x.data(), x.data() + x.size()),
                                         std::vector<double>(Q.data(), Q.data() + Q.size()),
                                         source);
      },
      "x"_a, "Q"_a, "source"_a = "table",
      "Masing element on a backbone table: force Q [N] against displacement x [m], checked\n"
      "monotone and through the origin, monotone cubic interpolation, constant beyond the\n"
      "last point (hysteresis/table_backbone.hpp).");
  m.def("coulomb", &make_coulomb_element, "F_s"_a, "k_tan"_a,
        "Regularized Coulomb f = F_s tanh(k_tan v) (Eq. 7.3 in SI): F_s [N], k_tan [s/m].");
  m.def(
      "elastic_dry_friction_2d",
      [](double k_t, double k_n, double mu, double N0) {
        return make_elastic_dry_friction_2d_element({.k_t = k_t, .k_n = k_n, .mu = mu, .N0 = N0});
      },
      "k_t"_a, "k_n"_a, "mu"_a, "N0"_a = 0.0,
      "Tangential (direction 0) Jenkins slider slipping at mu f_n, normal (direction 1) "
      "unilateral spring f_n = max(N0 + k_n u_n, 0).");
  m.def(
      "polynomial_stiffness",
      [](double k1, double k2, double k3) {
        return make_polynomial_stiffness_element({.k1 = k1, .k2 = k2, .k3 = k3});
      },
      "k1"_a = 0.0, "k2"_a = 0.0, "k3"_a = 0.0,
      "Polynomial stiffness f = k1 u + k2 u^2 + k3 u^3 (Duffing: k3) [N/m, N/m^2, N/m^3].");
  m.def("cubic_damping", &make_cubic_damping_element, "c3"_a,
        "Cubic damping f = c3 v^3, c3 [N s^3/m^3].");
  m.def(
      "elastic_dry_friction_3d",
      [](double k_t, double k_n, double mu, double N0) {
        return make_elastic_dry_friction_3d_element({.k_t = k_t, .k_n = k_n, .mu = mu, .N0 = N0});
      },
      "k_t"_a, "k_n"_a, "mu"_a, "N0"_a = 0.0,
      "Tangential (directions 0, 1) isotropic slider slipping at |f_t| = mu f_n (radial\n"
      "return), normal (direction 2) unilateral spring f_n = max(N0 + k_n u_n, 0).");
  m.def(
      "unilateral_spring",
      [](double k, double gap, double N0) {
        return make_unilateral_spring_element({.k = k, .gap = gap, .N0 = N0});
      },
      "k"_a, "gap"_a = 0.0, "N0"_a = 0.0,
      "Unilateral spring f_c = max(N0 + k (u - gap), 0) (u > 0 closes): k [N/m], a gap [m]\n"
      "or a preload N0 [N] carried outside the model (the structure receives f_c - N0).");
  m.def(
      "masing",
      [](std::shared_ptr<const hysteresis::Backbone> backbone, const std::string& type,
         const nb::dict& parameters) {
        if (!backbone) throw InvalidInput("backbone is None");
        dynamics::SummaryObject p;
        for (auto [k, v] : parameters) {
          const std::string key = nb::cast<std::string>(nb::str(k));
          double x = 0.0;
          if (nb::try_cast<double>(v, x)) {
            p.emplace_back(key, dynamics::SummaryValue{x});
          } else {
            p.emplace_back(key, dynamics::SummaryValue{nb::cast<std::string>(nb::str(v))});
          }
        }
        if (type == "rough_flat") return make_rough_flat_element(std::move(backbone), p);
        return std::shared_ptr<const Element>(
            std::make_shared<MasingElement>(std::move(backbone), type, p));
      },
      "backbone"_a, "type"_a = "rough_flat", "parameters"_a = nb::dict(),
      "Any SI backbone (Q [N] against x [m]) under Masing's rules as an element.");
  m.def(
      "odfalk_vingsbo",
      [](std::shared_ptr<const hysteresis::Backbone> backbone, double fretting_yield_point,
         double hardening_coefficient, const std::string& type) {
        if (!backbone) throw InvalidInput("backbone is None");
        return make_odfalk_vingsbo_element(
            std::move(backbone), {fretting_yield_point, hardening_coefficient}, {{"type", type}});
      },
      "backbone"_a, "fretting_yield_point"_a, "hardening_coefficient"_a, "type"_a = "rough_flat",
      "Eq. 3.10: Masing's loop on the elastic backbone (Q [N] against x [m]) with the\n"
      "parallelogram of plastic slip in series; Q_ty [N] and k_p [N/m] measured.");

  // ---- harmonic balance ---------------------------------------------------------------
  nb::class_<PyHarmonicBalance>(
      m, "HarmonicBalance",
      "The AFT harmonic-balance system of a structure with elements. Unknowns "
      "U[dof * n_c + c], coefficients per DOF [a_0, a_h1, b_h1, ...].")
      .def(
          "__init__",
          [](PyHarmonicBalance* self, const Structure& s,
             const std::vector<std::shared_ptr<const Element>>& elements,
             const std::vector<Matrix>& T, const std::vector<std::string>& names,
             const std::vector<int>& harmonics, std::size_t time_points) {
            if (T.size() != elements.size() || names.size() != elements.size()) {
              throw InvalidInput(fmt::format("{} elements but {} T matrices and {} names",
                                             elements.size(), T.size(), names.size()));
            }
            std::vector<PlacedElement> placed;
            for (std::size_t k = 0; k < elements.size(); ++k) {
              if (!elements[k]) throw InvalidInput(fmt::format("element {} is None", k));
              placed.push_back({elements[k], T[k], names[k]});
            }
            const HarmonicBalanceOptions o{harmonics, time_points};
            o.validate();
            new (self) PyHarmonicBalance(s, std::move(placed), o);
          },
          "structure"_a, "elements"_a, "T"_a, "names"_a, "harmonics"_a, "time_points"_a)
      .def_prop_ro("dofs", [](const PyHarmonicBalance& p) { return p.hb.dofs(); })
      .def_prop_ro("unknowns", [](const PyHarmonicBalance& p) { return p.hb.unknowns(); })
      .def_prop_ro("harmonics", [](const PyHarmonicBalance& p) { return p.hb.basis().harmonics(); })
      .def_prop_ro("coefficients",
                   [](const PyHarmonicBalance& p) { return p.hb.basis().coefficients(); })
      .def_prop_ro("time_points",
                   [](const PyHarmonicBalance& p) { return p.hb.basis().time_points(); })
      .def_prop_ro(
          "synthesis", [](const PyHarmonicBalance& p) { return p.hb.basis().synthesis(); },
          "E (N_t x n_c): samples of one DOF from its coefficients")
      .def_prop_ro(
          "projection", [](const PyHarmonicBalance& p) { return p.hb.basis().projection(); },
          "P (n_c x N_t): coefficients from samples")
      .def(
          "index",
          [](const PyHarmonicBalance& p, long dof, int h, int kind) {
            if (dof < 0 || dof >= p.hb.dofs()) {
              throw InvalidInput(
                  fmt::format("dof = {}: DOFs are numbered 0 .. {}", dof, p.hb.dofs() - 1));
            }
            const long c = p.hb.basis().index_of(h, kind);
            if (c < 0 || kind < 0 || kind > 1 || (h == 0 && kind == 1)) {
              throw InvalidInput(fmt::format(
                  "harmonic {} kind {} is not among the coefficients (harmonics kept: {}; kind 0 "
                  "cosine, 1 sine)",
                  h, kind, fmt::join(p.hb.basis().harmonics(), ", ")));
            }
            return p.hb.index(dof, static_cast<std::size_t>(c));
          },
          "dof"_a, "h"_a, "kind"_a = 0,
          "Index in U of harmonic h of `dof`, cosine (kind 0) or sine (kind 1).")
      .def(
          "residual",
          [](const PyHarmonicBalance& p, const Vector& U, double omega, const Vector& F_ex,
             bool jacobian) {
            check_unknowns(p, U, "U");
            check_omega(omega);
            Vector F = F_ex.size() == 0 ? Vector::Zero(p.hb.unknowns()) : F_ex;
            check_unknowns(p, F, "F_ex");
            Vector R, dRw;
            Matrix dR;
            locked(p, [&](const HarmonicBalance& hb) {
              hb.residual(U, omega, F, R, jacobian ? &dR : nullptr, jacobian ? &dRw : nullptr);
              return 0;
            });
            nb::dict d;
            d["R"] = copy_of(R);
            if (jacobian) {
              d["dR_dU"] = copy_of(dR);
              d["dR_domega"] = copy_of(dRw);
            }
            return d;
          },
          "U"_a, "omega"_a, "F_ex"_a = Vector(), "jacobian"_a = true,
          "dict R, and with jacobian dR_dU, dR_domega (analytic).")
      .def(
          "nonlinear_force",
          [](const PyHarmonicBalance& p, const Vector& U, double omega) {
            check_unknowns(p, U, "U");
            check_omega(omega);
            Vector F;
            locked(p, [&](const HarmonicBalance& hb) {
              hb.nonlinear_force(U, omega, F, nullptr, nullptr);
              return 0;
            });
            return F;
          },
          "U"_a, "omega"_a, "Coefficients of sum_e T_e^T f_e(T_e x(t)).")
      .def(
          "dynamic_stiffness",
          [](const PyHarmonicBalance& p, double omega) {
            return p.hb.dynamic_stiffness(omega, p.hb.structure().C);
          },
          "omega"_a, "A(omega) with the structure's damping.")
      .def(
          "stuck_stiffness", [](const PyHarmonicBalance& p) { return p.hb.stuck_stiffness(); },
          "K plus every element's initial stiffness.")
      .def(
          "time_history",
          [](const PyHarmonicBalance& p, const Vector& U, long dof, std::size_t samples) {
            check_unknowns(p, U, "U");
            if (dof < 0 || dof >= p.hb.dofs()) {
              throw InvalidInput(
                  fmt::format("dof = {}: DOFs are numbered 0 .. {}", dof, p.hb.dofs() - 1));
            }
            return p.hb.time_history(U, dof, samples);
          },
          "U"_a, "dof"_a, "samples"_a = 0,
          "x_dof(t) over one period (N_t samples, or `samples` equally spaced).")
      .def(
          "harmonic_amplitude",
          [](const PyHarmonicBalance& p, const Vector& U, long dof, int h) {
            check_unknowns(p, U, "U");
            if (dof < 0 || dof >= p.hb.dofs()) {
              throw InvalidInput(
                  fmt::format("dof = {}: DOFs are numbered 0 .. {}", dof, p.hb.dofs() - 1));
            }
            return p.hb.harmonic_amplitude(U, dof, h);
          },
          "U"_a, "dof"_a, "h"_a = 1)
      .def_prop_ro("counters", [](const PyHarmonicBalance& p) {
        nb::dict d;
        d["residual_evaluations"] = p.hb.counters().residual_evaluations;
        d["jacobian_evaluations"] = p.hb.counters().jacobian_evaluations;
        return d;
      });

  // ---- analyses -----------------------------------------------------------------------
  m.def(
      "nonlinear_mode",
      [](const PyHarmonicBalance& p, int mode, double log10_from, double log10_to,
         const std::vector<long>& outputs, const nb::dict& continuation) {
        NonlinearModeOptions o;
        o.mode = mode;
        o.log10_amplitude_from = log10_from;
        o.log10_amplitude_to = log10_to;
        o.continuation = continuation_options(o.continuation, continuation);
        const NonlinearModeResult r = locked(
            p, [&](const HarmonicBalance& hb) { return nonlinear_mode(hb, o, dof_list(outputs)); });
        return mode_dict(r, p.hb.unknowns());
      },
      "hb"_a, "mode"_a, "log10_from"_a, "log10_to"_a, "output_dofs"_a, "continuation"_a);

  m.def(
      "frequency_response",
      [](const PyHarmonicBalance& p, const Vector& force, const Vector& force_per_omega,
         const Vector& force_per_omega2, const std::vector<double>& scales, double omega_from,
         double omega_to, const std::vector<long>& outputs, const nb::dict& continuation,
         bool stability) {
        FrequencyResponseOptions o;
        o.stability = stability;
        o.force = force;
        o.force_per_omega = force_per_omega;
        o.force_per_omega2 = force_per_omega2;
        o.force_scales = scales;
        o.omega_from = omega_from;
        o.omega_to = omega_to;
        o.continuation = continuation_options(o.continuation, continuation);
        const std::vector<FrequencyResponseCurve> curves =
            locked(p, [&](const HarmonicBalance& hb) {
              return frequency_response(hb, o, dof_list(outputs));
            });
        nb::list out;
        for (const FrequencyResponseCurve& c : curves) out.append(curve_dict(c, p.hb.unknowns()));
        return out;
      },
      "hb"_a, "force"_a, "force_per_omega"_a, "force_per_omega2"_a, "force_scales"_a,
      "omega_from"_a, "omega_to"_a, "output_dofs"_a, "continuation"_a, "stability"_a = false,
      "F_ex(omega) = force + omega force_per_omega + omega^2 force_per_omega2 (the last two may "
      "be empty).");

  m.def(
      "nonlinear_mode_rom",
      [](const PyHarmonicBalance& p, const Vector& amplitude, const Vector& omega, const Vector& xi,
         const Matrix& harmonics, const Vector& force, const std::vector<long>& outputs,
         int subdivisions) {
        NonlinearModeResult mode;
        mode.amplitude = amplitude;
        mode.omega = omega;
        mode.xi = xi;
        if (omega.size() != amplitude.size() || xi.size() != amplitude.size() ||
            harmonics.rows() != amplitude.size()) {
          throw InvalidInput(
              "nonlinear_mode_rom: amplitude, omega, xi and the rows of harmonics must have one "
              "entry per backbone point");
        }
        for (Eigen::Index k = 0; k < harmonics.rows(); ++k) {
          mode.harmonics.emplace_back(harmonics.row(k).transpose());
        }
        const ModeRomCurve c = locked(p, [&](const HarmonicBalance& hb) {
          return nonlinear_mode_rom(hb, mode, force, dof_list(outputs), subdivisions);
        });
        nb::dict d;
        d["omega"] = copy_of(c.omega);
        d["amplitude"] = copy_of(c.amplitude);
        d["output_amplitude"] = copy_of(c.output_amplitude);
        d["low_side_points"] = c.low_side_points;
        d["peak_amplitude"] = c.peak_amplitude;
        d["warnings"] = string_list(c.warnings);
        return d;
      },
      "hb"_a, "amplitude"_a, "omega"_a, "xi"_a, "harmonics"_a, "force"_a, "output_dofs"_a,
      "subdivisions"_a,
      "Forced response from one nonlinear mode's backbone (single nonlinear mode theory).");
  m.def(
      "amplitude_control",
      [](const PyHarmonicBalance& p, const Vector& force, long dof, double amplitude,
         double omega_from, double omega_to, const std::vector<long>& outputs,
         const nb::dict& continuation) {
        AmplitudeControlOptions o;
        o.force = force;
        o.dof = dof;
        o.amplitude = amplitude;
        o.omega_from = omega_from;
        o.omega_to = omega_to;
        o.continuation = continuation_options(o.continuation, continuation);
        const AmplitudeControlResult r = locked(p, [&](const HarmonicBalance& hb) {
          return amplitude_controlled_response(hb, o, dof_list(outputs));
        });
        nb::dict d;
        d["omega"] = copy_of(r.omega);
        d["force_scale"] = copy_of(r.force_scale);
        d["output_amplitude"] = copy_of(r.output_amplitude);
        d["harmonics"] = copy_of(stack(r.harmonics, p.hb.unknowns()));
        d["continuation"] = continuation_dict(r.continuation);
        d["warnings"] = string_list(r.warnings);
        return d;
      },
      "hb"_a, "force"_a, "dof"_a, "amplitude"_a, "omega_from"_a, "omega_to"_a, "output_dofs"_a,
      "continuation"_a, "First harmonic of `dof` held at `amplitude`; continuation in omega.");
  m.def(
      "phase_resonance",
      [](const PyHarmonicBalance& p, const Vector& force, long dof, int mode, double log10_from,
         double log10_to, const std::vector<long>& outputs, const nb::dict& continuation) {
        PhaseResonanceOptions o;
        o.force = force;
        o.dof = dof;
        o.mode = mode;
        o.log10_amplitude_from = log10_from;
        o.log10_amplitude_to = log10_to;
        o.continuation = continuation_options(o.continuation, continuation);
        const PhaseResonanceResult r = locked(p, [&](const HarmonicBalance& hb) {
          return phase_resonance(hb, o, dof_list(outputs));
        });
        nb::dict d;
        d["amplitude"] = copy_of(r.amplitude);
        d["omega"] = copy_of(r.omega);
        d["force_scale"] = copy_of(r.force_scale);
        d["output_amplitude"] = copy_of(r.output_amplitude);
        d["harmonics"] = copy_of(stack(r.harmonics, p.hb.unknowns()));
        d["continuation"] = continuation_dict(r.continuation);
        d["warnings"] = string_list(r.warnings);
        return d;
      },
      "hb"_a, "force"_a, "dof"_a, "mode"_a, "log10_from"_a, "log10_to"_a, "output_dofs"_a,
      "continuation"_a,
      "First harmonic of `dof` lagging the force there by 90 degrees; continuation in log10 of "
      "its amplitude.");
  m.def(
      "superharmonic_resonance",
      [](const PyHarmonicBalance& p, const Vector& force, int harmonic, int mode, double log10_from,
         double log10_to, const std::vector<long>& outputs, const nb::dict& continuation) {
        SuperharmonicResonanceOptions o;
        o.force = force;
        o.harmonic = harmonic;
        o.mode = mode;
        o.log10_force_from = log10_from;
        o.log10_force_to = log10_to;
        o.continuation = continuation_options(o.continuation, continuation);
        const SuperharmonicResonanceResult r = locked(p, [&](const HarmonicBalance& hb) {
          return superharmonic_resonance(hb, o, dof_list(outputs));
        });
        return superharmonic_dict(r, p.hb.unknowns());
      },
      "hb"_a, "force"_a, "harmonic"_a, "mode"_a, "log10_from"_a, "log10_to"_a, "output_dofs"_a,
      "continuation"_a,
      "The harmonic:1 superharmonic resonance (VPRNM); continuation in log10 of the force "
      "scale.");
  m.def(
      "force_response",
      [](const PyHarmonicBalance& p, const Vector& force, const Vector& force_per_omega,
         const Vector& force_per_omega2, double omega, double scale_from, double scale_to,
         const std::vector<long>& outputs, const nb::dict& continuation) {
        ForceResponseOptions o;
        o.force = force;
        o.force_per_omega = force_per_omega;
        o.force_per_omega2 = force_per_omega2;
        o.omega = omega;
        o.scale_from = scale_from;
        o.scale_to = scale_to;
        o.continuation = continuation_options(o.continuation, continuation);
        const ForceResponseCurve c = locked(
            p, [&](const HarmonicBalance& hb) { return force_response(hb, o, dof_list(outputs)); });
        return force_curve_dict(c, p.hb.unknowns());
      },
      "hb"_a, "force"_a, "force_per_omega"_a, "force_per_omega2"_a, "omega"_a, "scale_from"_a,
      "scale_to"_a, "output_dofs"_a, "continuation"_a,
      "Continuation in the force scale lambda at fixed omega: R = A U + F_nl - lambda F_ex.");

  m.def(
      "quasi_static_mode",
      [](const PyHarmonicBalance& p, int mode, double amplitude_from, double amplitude_to,
         std::size_t points) {
        QuasiStaticModeOptions o;
        o.mode = mode;
        o.amplitude_from = amplitude_from;
        o.amplitude_to = amplitude_to;
        o.points = points;
        const QuasiStaticModeResult r =
            locked(p, [&](const HarmonicBalance& hb) { return quasi_static_mode(hb, o); });
        return quasi_static_dict(r);
      },
      "hb"_a, "mode"_a, "amplitude_from"_a, "amplitude_to"_a, "points"_a);

  // ---- case files (shared with `asperity vibration`) -------------------------------------
  m.def(
      "run_case",
      [](const std::string& path, bool stability) {
        VibrationCase c = [&] {
          nb::gil_scoped_release release;
          return read_case_file(path);
        }();
        return case_result(std::move(c), stability);
      },
      "path"_a, "stability"_a = false,
      "Runs a vibration case file: dict summary, nonlinear_mode, frequency_response, "
      "quasi_static_mode, complete, stop_reason, warnings, system.");
  m.def(
      "run_case_text",
      [](const std::string& text, const std::string& base_dir, bool stability) {
        VibrationCase c = [&] {
          nb::gil_scoped_release release;
          return parse_case_text(text, "<string>", base_dir);
        }();
        return case_result(std::move(c), stability);
      },
      "text"_a, "base_dir"_a = ".", "stability"_a = false, "run_case for case-file text.");
  m.def(
      "check_case_text",
      [](const std::string& text, const std::string& base_dir) {
        nb::gil_scoped_release release;
        (void)parse_case_text(text, "<string>", base_dir);
      },
      "text"_a, "base_dir"_a = ".",
      "Parses and validates vibration case text without running it (raises InvalidInput).");
  m.def(
      "case_system",
      [](const std::string& path) {
        const VibrationCase c = [&] {
          nb::gil_scoped_release release;
          return read_case_file(path);
        }();
        return case_system(c);
      },
      "path"_a, "A case file's structure, placed elements and harmonic-balance settings.");
}

}  // namespace asperity::python
