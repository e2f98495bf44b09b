// dynamics/: friction-force models, the base-excited single-DOF system of Eq. 7.1, its
// integration (simulate) and the analysis of the time histories (thesis ch. 7).
// Everything here is in the non-dimensional variables of section 7.2 (u = x/A,
// tau = sqrt(k/m) t, forces over k A) except DimensionalScales and the SI backbones.
#include <nanobind/ndarray.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/unique_ptr.h>
#include <nanobind/stl/variant.h>
#include <nanobind/stl/vector.h>

#include <fmt/format.h>

#include <cstddef>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/core/error.hpp"
#include "asperity/dynamics/analysis.hpp"
#include "asperity/dynamics/case.hpp"
#include "asperity/dynamics/epb.hpp"
#include "asperity/dynamics/friction_model.hpp"
#include "asperity/dynamics/integrator.hpp"
#include "asperity/dynamics/system.hpp"
#include "bindings.hpp"
#include "vectorize.hpp"

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::dynamics;

namespace {

using Array1 = nb::ndarray<const double, nb::ndim<1>, nb::c_contig>;

hysteresis::MemoryRule parse_memory(const std::string& name) {
  if (name == "masing") return hysteresis::MemoryRule::masing;
  if (name == "reset_at_reversal") return hysteresis::MemoryRule::reset_at_reversal;
  throw InvalidInput(
      "memory rule \"" + name +
      "\" is unknown: allowed are masing (default) and reset_at_reversal (Eq. 7.10)");
}

// A 1-D numpy bool array holding a copy of `v`.
nb::object bool_array_of(const std::vector<bool>& v) {
  nb::module_ np = nb::module_::import_("numpy");
  return np.attr("array")(array_of(std::vector<double>(v.begin(), v.end())), "dtype"_a = "bool");
}

// atol: one number or one per state.
std::vector<double> parse_atol(const nb::handle& atol) {
  double x = 0.0;
  if (detail::python_number(atol, x)) return {x};
  std::vector<double> out;
  try {
    for (nb::handle item : atol) out.push_back(nb::cast<double>(item));
  } catch (const nb::python_error&) {
    throw;
  } catch (const std::exception&) {
    throw InvalidInput("atol must be a number or a sequence of numbers (one per state)");
  }
  return out;
}

// A run summary as Python objects (dict, list, float, int, str, bool, None).
nb::object to_python(const SummaryValue& v) {
  return std::visit(
      [](const auto& x) -> nb::object {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::nullptr_t>) {
          return nb::none();
        } else if constexpr (std::is_same_v<T, SummaryArray>) {
          nb::list l;
          for (const auto& e : x) l.append(to_python(e));
          return l;
        } else if constexpr (std::is_same_v<T, SummaryObject>) {
          nb::dict d;
          for (const auto& [k, e] : x) d[k.c_str()] = to_python(e);
          return d;
        } else {
          return nb::cast(x);
        }
      },
      v.data);
}

// run_case as a dict: summary (the summary.json content), arrays (the timeseries.csv
// columns as numpy arrays, names without their units), spectrum, warnings, trajectory.
nb::dict case_dict(const DynamicsCase& c) {
  CaseResult r = [&] {
    nb::gil_scoped_release release;
    return run_case(c);
  }();
  nb::dict out;
  out["summary"] = to_python(SummaryValue(r.summary));
  nb::dict arrays;
  for (const auto& col : time_history_columns(c, r.trajectory)) {
    const std::string name = col.name.substr(0, col.name.find('['));
    if (name == "event") {
      arrays[name.c_str()] = bool_array_of(r.trajectory.is_event);
    } else {
      arrays[name.c_str()] = array_of(col.values);
    }
  }
  out["arrays"] = arrays;
  if (r.spectrum) {
    nb::dict sp;
    sp["frequency"] = array_of(r.spectrum->frequency);
    sp["power"] = array_of(r.spectrum->power);
    out["spectrum"] = sp;
  } else {
    out["spectrum"] = nb::none();
  }
  nb::list w;
  for (const auto& s : r.warnings) w.append(s);
  out["warnings"] = w;
  out["trajectory"] = nb::cast(std::move(r.trajectory));
  return out;
}

}  // namespace

void bind_dynamics(nb::module_& m) {
  // ---- friction models ----------------------------------------------------------
  nb::class_<FrictionModel>(
      m, "FrictionModel",
      "A friction-force model inside a time integration (non-dimensional, section 7.2): the "
      "force F_s from the committed state and the current displacement u, velocity v and "
      "internal states z; hysteretic models commit their memory at velocity reversals.")
      .def_prop_ro("name", &FrictionModel::name)
      .def_prop_ro("internal_states", &FrictionModel::internal_states,
                   "number of internal ODE states (Dankowicz: 1)")
      .def_prop_ro("uses_reversal_events", &FrictionModel::uses_reversal_events,
                   "True if the integrator must stop at velocity reversals")
      .def_prop_ro("max_force", &FrictionModel::max_force,
                   "the largest force the model can carry (F_max, or the backbone's limit)")
      .def(
          "force",
          [](const FrictionModel& f, const ArrayLike& u, const ArrayLike& v,
             const nb::object& z) -> FloatOrArray {
            const std::size_t n = f.internal_states();
            if (n == 0) {
              if (!z.is_none()) {
                throw InvalidInput("friction model \"" + f.name() +
                                   "\" has no internal state: omit z");
              }
              return vectorize([&f](double a, double b) { return f.force(a, b, {}); }, u, v);
            }
            if (n != 1) {
              throw InvalidInput("force() of Python supports at most one internal state");
            }
            if (z.is_none()) {
              throw InvalidInput("friction model \"" + f.name() + "\" needs its internal state z");
            }
            return vectorize(
                [&f](double a, double b, double c) {
                  const double zz[1] = {c};
                  return f.force(a, b, zz);
                },
                u, v, ArrayLike{z});
          },
          "u"_a, "v"_a, "z"_a = nb::none(),
          "F_s at displacement u and velocity v (and internal state z for Dankowicz), from the "
          "committed state; does not change it.")
      .def(
          "internal_rates",
          [](const FrictionModel& f, double u, double v, const std::vector<double>& z) {
            if (z.size() != f.internal_states()) {
              throw InvalidInput(fmt::format("z has {} entries; the model has {} internal states",
                                             z.size(), f.internal_states()));
            }
            std::vector<double> dz(z.size());
            f.internal_rates(u, v, z, dz);
            return dz;
          },
          "u"_a, "v"_a, "z"_a, "dz/dtau of the internal states.")
      .def("commit_reversal", &FrictionModel::commit_reversal, "u"_a,
           "An event: the motion reverses at u (v = 0); commits the memory.")
      .def("reset", &FrictionModel::reset, "Back to the virgin state.")
      .def("copy", &FrictionModel::clone, "A copy with the same parameters and committed state.")
      .def("__repr__",
           [](const FrictionModel& f) { return "<asperity.FrictionModel " + f.name() + ">"; });

  nb::class_<NoFriction, FrictionModel>(m, "NoFriction", "No friction: F_s = 0.").def(nb::init<>());

  nb::class_<RegularizedCoulomb, FrictionModel>(
      m, "RegularizedCoulomb",
      "Regularized Coulomb friction F_s = F_max tanh(k_tan v) (Eq. 7.2-7.3).")
      .def(
          "__init__",
          [](RegularizedCoulomb* self, double F_max, double k_tan) {
            new (self) RegularizedCoulomb({.F_max = F_max, .k_tan = k_tan});
          },
          "F_max"_a = 1.5, "k_tan"_a = 6.32,
          "F_max: sliding force over k A; k_tan: slope at v = 0 over F_max (k_tan A sqrt(k/m)).")
      .def_prop_ro("F_max", [](const RegularizedCoulomb& c) { return c.parameters().F_max; })
      .def_prop_ro("k_tan", [](const RegularizedCoulomb& c) { return c.parameters().k_tan; });

  nb::class_<Dankowicz, FrictionModel>(
      m, "Dankowicz",
      "Dankowicz friction (Eq. 7.4-7.7): z' = v (1 - z/delta sgn v), F_s = F_max z/delta; "
      "|F_s| <= F_max.")
      .def(
          "__init__",
          [](Dankowicz* self, double F_max, double delta) {
            new (self) Dankowicz({.F_max = F_max, .delta = delta});
          },
          "F_max"_a = 1.5, "delta"_a = 0.011,
          "F_max: sliding force over k A; delta: largest pre-sliding displacement over A.")
      .def_prop_ro("F_max", [](const Dankowicz& d) { return d.parameters().F_max; })
      .def_prop_ro("delta", [](const Dankowicz& d) { return d.parameters().delta; });

  nb::class_<HysteresisFriction, FrictionModel>(
      m, "HysteresisFriction",
      "Any Masing backbone as a friction force (Hysteresis between events, a commit at each "
      "velocity reversal). memory='masing' (default) or 'reset_at_reversal' (Eq. 7.10).")
      .def(
          "__init__",
          [](HysteresisFriction* self, std::shared_ptr<const hysteresis::Backbone> backbone,
             const std::string& memory, const std::string& name) {
            new (self) HysteresisFriction(std::move(backbone), parse_memory(memory), name);
          },
          "backbone"_a, "memory"_a = "masing", "name"_a = "hysteresis")
      .def_prop_ro("hysteresis", &HysteresisFriction::hysteresis, nb::rv_policy::reference_internal,
                   "the Masing engine and its committed reversals");

  nb::class_<SegalmanBackbone, hysteresis::Backbone>(
      m, "SegalmanBackbone",
      "Virgin curve of Segalman's four-parameter Iwan model (Segalman 2005).")
      .def(
          "__init__",
          [](SegalmanBackbone* self, double F_S, double K_T, double chi, double beta) {
            new (self) SegalmanBackbone({.F_S = F_S, .K_T = K_T, .chi = chi, .beta = beta});
          },
          "F_S"_a, "K_T"_a, "chi"_a, "beta"_a,
          "F_S force at macro-slip, K_T stiffness at zero load, chi in (-1, 0], beta >= 0 (all "
          "four required: no default is a property of a joint).")
      .def_prop_ro("phi_max", &SegalmanBackbone::phi_max)
      .def_prop_ro("R", &SegalmanBackbone::R)
      .def_prop_ro("S", &SegalmanBackbone::S);

  m.def("make_jenkins", &make_jenkins, "stiffness"_a, "F_max"_a,
        "Jenkins element (spring in series with a Coulomb slider) as a friction model.");
  m.def(
      "make_segalman_iwan",
      [](double F_S, double K_T, double chi, double beta) {
        return make_segalman_iwan({.F_S = F_S, .K_T = K_T, .chi = chi, .beta = beta});
      },
      "F_S"_a, "K_T"_a, "chi"_a, "beta"_a,
      "Segalman's four-parameter Iwan model: F_S force at macro-slip, K_T stiffness at zero "
      "load, chi in (-1, 0], beta >= 0 (all four required; e.g. chi = -0.5, beta = 0.1).");
  m.def(
      "make_physics_based",
      [](std::shared_ptr<const hysteresis::Backbone> backbone_si, double k, double A,
         const std::string& memory) {
        return make_physics_based(std::move(backbone_si), k, A, parse_memory(memory));
      },
      "backbone_si"_a, "k"_a, "A"_a, "memory"_a = "masing",
      "The physics-based (EPB) model from a backbone in SI units (Q [N] against displacement "
      "[m]) seen in the variables of section 7.2: F_s(u) = Q(A u)/(k A); k [N/m], A [m].");

  nb::class_<EpbContact>(
      m, "EpbContact",
      "Combined properties and roughness as Table 7.2 gives them (SI): E_star, G_star, H [Pa], "
      "nu, sigma [m], R [m], eta [1/m^2], A0 [m^2], P [N], asperity model, mu_cfc, zeta.")
      .def(
          "__init__",
          [](EpbContact* self, double E_star, double G_star, double H, double nu, double sigma,
             double R, double eta, double A0, double P, const std::string& model, double mu_cfc,
             double zeta) {
            new (self) EpbContact{.E_star = E_star,
                                  .G_star = G_star,
                                  .H = H,
                                  .nu = nu,
                                  .sigma = sigma,
                                  .R = R,
                                  .eta = eta,
                                  .A0 = A0,
                                  .P = P,
                                  .model = contact::parse_model_name(model),
                                  .friction = {.mu_cfc = mu_cfc, .zeta = zeta}};
          },
          "E_star"_a = 106e9, "G_star"_a = 22.9e9, "H"_a = 5.8e9, "nu"_a = 0.3, "sigma"_a = 2.7e-6,
          "R"_a = 30.1e-6, "eta"_a = 2.9e8, "A0"_a = 0.0, "P"_a = 0.0, "model"_a = "bke",
          "mu_cfc"_a = 0.3, "zeta"_a = 0.48)
      .def_rw("E_star", &EpbContact::E_star)
      .def_rw("G_star", &EpbContact::G_star)
      .def_rw("H", &EpbContact::H)
      .def_rw("nu", &EpbContact::nu)
      .def_rw("sigma", &EpbContact::sigma)
      .def_rw("R", &EpbContact::R)
      .def_rw("eta", &EpbContact::eta)
      .def_rw("A0", &EpbContact::A0)
      .def_rw("P", &EpbContact::P)
      .def_prop_rw(
          "model", [](const EpbContact& c) { return std::string(contact::to_string(c.model)); },
          [](EpbContact& c, const std::string& s) { c.model = contact::parse_model_name(s); })
      .def("validate", &EpbContact::validate);
  m.def("table_7_2_rough", &table_7_2_rough, "Table 7.2's rough contact (A0 and P left to set).");
  m.def("table_7_2_smooth", &table_7_2_smooth,
        "Table 7.2's smooth contact (A0 and P left to set).");
  m.def("epb_backbone", &epb_backbone, "contact"_a,
        "The rough flat's virgin loading curve Q(delta) in SI units [N over m] (section 7.3).");

  // ---- excitations and the system -------------------------------------------------
  nb::class_<FreeVibration>(m, "FreeVibration", "No base motion: free vibration from u0, v0.")
      .def(nb::init<>())
      .def("__repr__", [](const FreeVibration&) { return std::string("FreeVibration()"); });
  nb::class_<ImpulseExcitation>(
      m, "ImpulseExcitation",
      "Half-sine pulse y = amplitude sin(Omega tau), 0 <= tau < pi/Omega (Table 7.1).")
      .def(
          "__init__",
          [](ImpulseExcitation* self, double Omega, double amplitude) {
            const ImpulseExcitation e{.Omega = Omega, .amplitude = amplitude};
            validate(Excitation{e});
            new (self) ImpulseExcitation(e);
          },
          "Omega"_a = 10.0 * std::numbers::pi, "amplitude"_a = 1.0)
      .def_ro("Omega", &ImpulseExcitation::Omega)
      .def_ro("amplitude", &ImpulseExcitation::amplitude)
      .def("__repr__", [](const ImpulseExcitation& e) {
        return fmt::format("ImpulseExcitation(Omega={}, amplitude={})", e.Omega, e.amplitude);
      });
  nb::class_<RampExcitation>(m, "RampExcitation",
                             "Ramp y = alpha tau (Table 7.1), alpha = beta sqrt(m/k)/A.")
      .def(
          "__init__",
          [](RampExcitation* self, double alpha) {
            const RampExcitation e{.alpha = alpha};
            validate(Excitation{e});
            new (self) RampExcitation(e);
          },
          "alpha"_a = 1.0)
      .def_ro("alpha", &RampExcitation::alpha)
      .def("__repr__", [](const RampExcitation& e) {
        return fmt::format("RampExcitation(alpha={})", e.alpha);
      });
  nb::class_<HarmonicExcitation>(
      m, "HarmonicExcitation",
      "Harmonic y = amplitude sin(2 pi frequency tau), frequency = sqrt(m/k) f (Table 7.1).")
      .def(
          "__init__",
          [](HarmonicExcitation* self, double frequency, double amplitude) {
            const HarmonicExcitation e{.frequency = frequency, .amplitude = amplitude};
            validate(Excitation{e});
            new (self) HarmonicExcitation(e);
          },
          "frequency"_a = 1.0, "amplitude"_a = 1.0)
      .def_ro("frequency", &HarmonicExcitation::frequency)
      .def_ro("amplitude", &HarmonicExcitation::amplitude)
      .def("__repr__", [](const HarmonicExcitation& e) {
        return fmt::format("HarmonicExcitation(frequency={}, amplitude={})", e.frequency,
                           e.amplitude);
      });

  m.def(
      "base_motion",
      [](const Excitation& e, const ArrayLike& tau) {
        auto y = vectorize([&e](double t) { return base_motion(e, t).y; }, tau);
        auto dy = vectorize([&e](double t) { return base_motion(e, t).dy; }, tau);
        return std::make_pair(y, dy);
      },
      "excitation"_a, "tau"_a, "(y, dy/dtau) of the base at tau.");
  m.def("breakpoints", &breakpoints, "excitation"_a,
        "Times where the base velocity jumps (the end of an impulse).");

  nb::class_<DimensionalScales>(
      m, "DimensionalScales",
      "SI <-> non-dimensional variables of section 7.2: mass m [kg], stiffness k [N/m], "
      "displacement scale A [m].")
      .def(
          "__init__",
          [](DimensionalScales* self, double m_, double k, double A) {
            const DimensionalScales s{.m = m_, .k = k, .A = A};
            s.validate();
            new (self) DimensionalScales(s);
          },
          "m"_a, "k"_a, "A"_a)
      .def_ro("m", &DimensionalScales::m)
      .def_ro("k", &DimensionalScales::k)
      .def_ro("A", &DimensionalScales::A)
      .def_prop_ro("time", &DimensionalScales::time, "sqrt(m/k) [s]: t = time tau")
      .def_prop_ro("force", &DimensionalScales::force, "k A [N]")
      .def_prop_ro("energy", &DimensionalScales::energy, "k A^2 [J]")
      .def("epsilon", &DimensionalScales::epsilon, "c"_a,
           "eps = c/sqrt(m k) for a damping coefficient c [N s/m].")
      .def(
          "coulomb",
          [](const DimensionalScales& s, double F_max, double k_tan) {
            return RegularizedCoulomb(s.coulomb(F_max, k_tan));
          },
          "F_max"_a, "k_tan"_a,
          "Regularized Coulomb model from F_max [N] and k_tan [s/m] (Eq. 7.3).")
      .def(
          "dankowicz",
          [](const DimensionalScales& s, double F_max, double delta) {
            return Dankowicz(s.dankowicz(F_max, delta));
          },
          "F_max"_a, "delta"_a, "Dankowicz model from F_max [N] and delta [m] (Eq. 7.6-7.7).");

  // ---- trajectories ----------------------------------------------------------------
  auto traj = nb::class_<Trajectory>(
      m, "Trajectory",
      "A recorded time history of Eq. 7.1 in non-dimensional variables. Arrays are read-only "
      "views owned by this object (np.array(...) copies). Energies are per unit k A^2.");
#define ASPERITY_TRAJECTORY_ARRAY(field, doc)                       \
  traj.def_prop_ro(                                                 \
      #field, [](const Trajectory& t) { return view_of(t.field); }, \
      nb::rv_policy::reference_internal, doc)
  ASPERITY_TRAJECTORY_ARRAY(tau, "time tau = sqrt(k/m) t");
  ASPERITY_TRAJECTORY_ARRAY(u, "displacement u = x/A");
  ASPERITY_TRAJECTORY_ARRAY(v, "velocity du/dtau");
  ASPERITY_TRAJECTORY_ARRAY(y, "base displacement / A");
  ASPERITY_TRAJECTORY_ARRAY(dy, "base velocity dy/dtau");
  ASPERITY_TRAJECTORY_ARRAY(friction, "friction force F_s = f_s/(k A)");
  ASPERITY_TRAJECTORY_ARRAY(work_base, "work of the base on the system");
  ASPERITY_TRAJECTORY_ARRAY(dissipated_damper, "energy dissipated by the damper");
  ASPERITY_TRAJECTORY_ARRAY(work_friction, "work against friction");
  ASPERITY_TRAJECTORY_ARRAY(energy, "mechanical energy u'^2/2 + (u - y)^2/2");
  ASPERITY_TRAJECTORY_ARRAY(event_tau, "times of the located velocity reversals");
  ASPERITY_TRAJECTORY_ARRAY(event_u, "displacements at the located velocity reversals");
#undef ASPERITY_TRAJECTORY_ARRAY
  traj.def_prop_ro(
          "internal",
          [](const Trajectory& t) {
            // (n, n_internal) copy: the friction model's internal states (Dankowicz: z).
            const std::size_t n = t.size(), k = t.internal.size();
            std::unique_ptr<double[]> data(new double[n * k > 0 ? n * k : 1]);
            for (std::size_t i = 0; i < n; ++i) {
              for (std::size_t j = 0; j < k; ++j) data[i * k + j] = t.internal[j][i];
            }
            return detail::make_array(std::move(data), {n, k});
          },
          "the friction model's internal states, shape (len, n_internal) (Dankowicz: z in "
          "column 0; a copy)")
      .def_prop_ro(
          "stiff_steps", [](const Trajectory& t) { return t.stats.stiff_steps; },
          "accepted steps held by stability rather than accuracy (Dormand-Prince stiffness "
          "test)")
      .def_prop_ro(
          "is_event", [](const Trajectory& t) { return bool_array_of(t.is_event); },
          "per sample: the sample is a located reversal (a bool array copy)")
      .def_prop_ro(
          "steps", [](const Trajectory& t) { return t.stats.steps; }, "accepted steps")
      .def_prop_ro("rejected_steps", [](const Trajectory& t) { return t.stats.rejected_steps; })
      .def_prop_ro("rhs_evaluations", [](const Trajectory& t) { return t.stats.rhs_evaluations; })
      .def_prop_ro(
          "events", [](const Trajectory& t) { return t.stats.events; }, "located reversals")
      .def_ro("force_evaluations", &Trajectory::force_evaluations)
      .def_ro("friction_model", &Trajectory::friction_model)
      .def("energy_balance_error", &Trajectory::energy_balance_error,
           "|E_end - E_0 - (W_base - D_damper - W_friction)| over the energy put in.")
      .def("__len__", &Trajectory::size);

  m.def(
      "simulate",
      [](const Excitation& excitation, const FrictionModel* friction, double epsilon,
         double duration, double u0, double v0, const std::string& method, double rtol,
         const nb::object& atol, double max_step, double initial_step, double min_step,
         std::size_t max_steps, double output_interval, bool locate_reversals) {
        SimulationOptions o;
        o.duration = duration;
        o.u0 = u0;
        o.v0 = v0;
        o.integrator.method = parse_method(method);
        o.integrator.rtol = rtol;
        o.integrator.atol = parse_atol(atol);
        o.integrator.max_step = max_step;
        o.integrator.initial_step = initial_step;
        o.integrator.min_step = min_step;
        o.integrator.max_steps = max_steps;
        o.output_interval = output_interval;
        o.locate_reversals = locate_reversals;
        // Own copy of the model, taken with the GIL held; the run itself releases it.
        std::unique_ptr<FrictionModel> model =
            friction ? friction->clone() : std::make_unique<NoFriction>();
        nb::gil_scoped_release release;
        return simulate(SystemParameters{.epsilon = epsilon}, excitation, *model, o);
      },
      "excitation"_a, "friction"_a = nb::none(), nb::kw_only(), "epsilon"_a = 0.032,
      "duration"_a = 100.0, "u0"_a = 0.0, "v0"_a = 0.0, "method"_a = "dp54", "rtol"_a = 1e-6,
      "atol"_a = 1e-7, "max_step"_a = 0.0, "initial_step"_a = 0.0, "min_step"_a = 0.0,
      "max_steps"_a = std::size_t{50'000'000}, "output_interval"_a = 0.0,
      "locate_reversals"_a = false,
      "Integrates u'' + eps u' + u = y + eps y' - F_s (Eq. 7.1, non-dimensional) from (u0, v0) "
      "over [0, duration] with a copy of `friction` (None: no friction). method 'dp54' "
      "(Dormand-Prince 5(4), default) or 'bs23' (MATLAB ode23); atol one number or one per "
      "state [u, v, internal..., W_base, D_damper, W_friction]; max_step 0: a tenth of the "
      "interval; min_step: the step-collapse threshold (NumericalError below it); "
      "output_interval 0 records every accepted step, > 0 uniform samples plus every event.");

  // ---- analysis --------------------------------------------------------------------
  nb::class_<Periodogram>(
      m, "Periodogram",
      "Power spectrum P(f) = |dt sum (x_n - mean) exp(-2 pi i f t_n)|^2 of a uniformly sampled "
      "signal: at any frequency by Goertzel's recurrence (exact DTFT in double precision); "
      "power_spectrum gives it on an FFT grid (KISS FFT).")
      .def(
          "__init__",
          [](Periodogram* self, const Array1& x, double dt) {
            new (self) Periodogram(std::span<const double>(x.data(), x.shape(0)), dt);
          },
          "x"_a, "dt"_a)
      .def(
          "__call__",
          [](const Periodogram& p, const ArrayLike& f) {
            return vectorize([&p](double v) { return p(v); }, f);
          },
          "f"_a)
      .def_prop_ro("dt", &Periodogram::dt)
      .def("__len__", &Periodogram::size);
  m.def(
      "power_spectrum",
      [](const Periodogram& p, double f_min, double f_max, std::size_t bins) {
        const Spectrum s = power_spectrum(p, f_min, f_max, bins);
        return std::make_pair(FloatOrArray{array_of(s.frequency)}, FloatOrArray{array_of(s.power)});
      },
      "periodogram"_a, "f_min"_a, "f_max"_a, "min_bins"_a = std::size_t{0},
      "(frequency, power) on the FFT grid k/(n_fft dt) inside [f_min, f_max], by KISS FFT of the "
      "signal zero-padded to n_fft >= 4 len (and fine enough for at least min_bins points in "
      "the range); each value equals the periodogram at that frequency.");

  nb::class_<ModalEstimate>(m, "ModalEstimate", "The main spectral peak and its half-power points.")
      .def_ro("frequency", &ModalEstimate::frequency, "peak frequency")
      .def_ro("damping_ratio", &ModalEstimate::damping_ratio,
              "(f_high - f_low)/(2 frequency): half-power bandwidth")
      .def_ro("peak_power", &ModalEstimate::peak_power)
      .def_ro("undamped_frequency", &ModalEstimate::undamped_frequency,
              "frequency/sqrt(1 - 2 damping_ratio^2): the undamped natural frequency of a "
              "viscously damped mode whose displacement spectrum peaks at `frequency`")
      .def_ro("f_low", &ModalEstimate::f_low)
      .def_ro("f_high", &ModalEstimate::f_high)
      .def("__repr__", [](const ModalEstimate& e) {
        return fmt::format("ModalEstimate(frequency={:.6g}, damping_ratio={:.6g})", e.frequency,
                           e.damping_ratio);
      });
  m.def("modal_estimate", &modal_estimate, "periodogram"_a, "f_min"_a, "f_max"_a,
        "bins"_a = std::size_t{4000},
        "Largest interior peak of power_spectrum in [f_min, f_max], refined by Brent's method on "
        "the exact periodogram, and its half-power points (root finding on it); NumericalError "
        "if one lies outside the range.");
  m.def(
      "run_dynamics_case", [](const std::string& path) { return case_dict(read_case_file(path)); },
      "path"_a,
      "Runs a dynamics case file (the TOML of `asperity dynamics`, docs/dynamics.md) and "
      "returns a dict: summary (the content of summary.json: modal_frequency, "
      "modal_frequency_undamped, modal_damping, energy_balance_error, friction, warnings, ...), "
      "arrays (the timeseries.csv columns as numpy arrays: tau, u, v, y, friction, z, "
      "work_base, dissipated_damper, work_friction, energy, event (bool), and with the scales "
      "t [s], x [m], xdot [m/s], base [m], f_s [N]), spectrum (dict of frequency, power for "
      "decays, else None), warnings (list of str) and trajectory (the Trajectory).");
  m.def(
      "run_dynamics_case_text",
      [](const std::string& text, const std::string& base_dir) {
        return case_dict(parse_case_text(text, "<string>", base_dir));
      },
      "text"_a, "base_dir"_a = ".",
      "run_dynamics_case for case-file text (base_dir resolves a [joint]'s profile paths).");
  m.def(
      "uniform_samples",
      [](const Trajectory& tr, double output_interval, double tau_start) {
        return array_of(uniform_samples(tr, output_interval, tau_start));
      },
      "trajectory"_a, "output_interval"_a, "tau_start"_a = 0.0,
      "The uniformly sampled displacement of a run with output_interval > 0 (events skipped).");
  m.def(
      "extrema",
      [](const Trajectory& tr, double tau_start) {
        const auto e = extrema(tr, tau_start);
        std::vector<double> t(e.size()), u(e.size());
        for (std::size_t i = 0; i < e.size(); ++i) {
          t[i] = e[i].tau;
          u[i] = e[i].u;
        }
        return std::make_pair(FloatOrArray{array_of(t)}, FloatOrArray{array_of(u)});
      },
      "trajectory"_a, "tau_start"_a = 0.0, "(tau, u) of the displacement's extrema.");
  m.def(
      "free_decay",
      [](const Trajectory& tr, double tau_start, double floor) {
        const auto d = free_decay(tr, tau_start, floor);
        std::vector<double> t, a, f, z;
        for (const auto& p : d) {
          t.push_back(p.tau);
          a.push_back(p.amplitude);
          f.push_back(p.frequency);
          z.push_back(p.damping_ratio);
        }
        nb::dict out;
        out["tau"] = array_of(t);
        out["amplitude"] = array_of(a);
        out["frequency"] = array_of(f);
        out["damping_ratio"] = array_of(z);
        return out;
      },
      "trajectory"_a, "tau_start"_a = 0.0, "floor"_a = 1e-4,
      "Amplitude-dependent frequency and damping of a free decay by the logarithmic decrement "
      "over full cycles of successive swings: a dict of arrays tau, amplitude, frequency, "
      "damping_ratio (one entry per cycle).");
  m.def(
      "stick_slip_intervals",
      [](const Trajectory& tr, double velocity_threshold) {
        const auto iv = stick_slip_intervals(tr, velocity_threshold);
        std::vector<double> b, e;
        std::vector<bool> s;
        for (const auto& i : iv) {
          b.push_back(i.begin);
          e.push_back(i.end);
          s.push_back(i.stick);
        }
        nb::dict out;
        out["begin"] = array_of(b);
        out["end"] = array_of(e);
        out["stick"] = bool_array_of(s);
        return out;
      },
      "trajectory"_a, "velocity_threshold"_a,
      "Stick (|v| < velocity_threshold) and slip intervals: a dict of arrays begin, end, stick.");

  nb::class_<LoopSummary>(m, "LoopSummary", "The friction loop of a steady harmonic response.")
      .def_ro("energy_per_cycle", &LoopSummary::energy_per_cycle,
              "closed integral of F_s du, per cycle")
      .def_ro("displacement_amplitude", &LoopSummary::displacement_amplitude)
      .def_ro("force_amplitude", &LoopSummary::force_amplitude)
      .def_ro("mean_displacement", &LoopSummary::mean_displacement);
  m.def("steady_loop", &steady_loop, "trajectory"_a, "period"_a, "cycles"_a = 1,
        "The friction loop over the last `cycles` periods of a harmonic response.");
}

}  // namespace asperity::python
