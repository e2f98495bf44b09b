// joint/: case files, predictions, fretting-data analysis, synthetic experiments and the
// validation report (thesis ch. 5-6). Results are plain dicts of floats, strings and
// numpy arrays (SI units).
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "asperity/core/error.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/fretting.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"
#include "bindings.hpp"
#include "vectorize.hpp"

namespace asperity::python {

using namespace nb::literals;
using namespace asperity::joint;

namespace {

using Array1 = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

std::vector<double> vec(const Array1& a) {
  return std::vector<double>(a.data(), a.data() + a.shape(0));
}

nb::dict cycle_dict(const CycleMetrics& c) {
  nb::dict d;
  d["t_start"] = c.t_start;
  d["t_end"] = c.t_end;
  d["energy"] = c.energy;
  d["Q_max"] = c.Q_max;
  d["delta_max"] = c.delta_max;
  d["stiffness"] = c.stiffness;
  d["stiffness_resolved"] = c.stiffness_resolved;
  d["stiffness_unloading"] = c.stiffness_unloading;
  d["stiffness_reloading"] = c.stiffness_reloading;
  d["sliding"] = c.sliding;
  d["partial_slip"] = c.partial_slip;
  d["Q_center"] = c.Q_center;
  d["delta_center"] = c.delta_center;
  return d;
}

nb::dict prediction_dict(const JointCase& c, const JointPrediction& p, std::size_t loop_points) {
  nb::dict out;
  out["name"] = c.name;
  out["case"] = c.source;
  out["model"] = std::string(contact::to_string(c.model));
  out["area"] = c.area;
  nb::dict r;
  r["sigma"] = p.sigma;
  r["eta"] = p.eta;
  r["R"] = p.R;
  r["beta"] = p.beta;
  r["psi"] = p.psi;
  nb::list halves;  // per half: where the roughness came from and its parameters
  for (const auto& h : c.halves) {
    nb::dict hd;
    hd["source"] = h.roughness.profiles.empty() ? "parameters" : "profiles";
    hd["profiles"] = h.roughness.profiles;
    hd["directions"] = h.roughness.directions;
    hd["sigma"] = h.roughness.moments.sigma();
    hd["eta"] = h.roughness.moments.eta();
    hd["R"] = h.roughness.moments.R();
    halves.append(hd);
  }
  r["halves"] = halves;
  out["roughness"] = r;
  std::vector<double> P, mu, k, Qm, d;
  nb::list loads;
  for (const auto& l : p.loads) {
    nb::dict ld;
    ld["preload"] = l.preload;
    ld["torque_per_bolt"] = l.torque;
    ld["mean_pressure"] = l.mean_pressure;
    ld["separation"] = l.separation;
    ld["mu"] = l.mu;
    ld["Q_max"] = l.Q_max;
    ld["stiffness"] = l.stiffness;
    ld["contact_area_ratio"] = l.contact_area_ratio;
    ld["backbone"] = nb::cast(std::shared_ptr<const hysteresis::Backbone>(l.backbone));
    // tangential = "odfalk_vingsbo": its measured parameters (`backbone` is then the elastic
    // part, in series with Eq. 3.10's plastic slip); None for Cattaneo-Mindlin.
    if (l.odfalk_vingsbo) {
      nb::dict ov;
      ov["fretting_yield_point"] = l.odfalk_vingsbo->fretting_yield_point;
      ov["hardening_coefficient"] = l.odfalk_vingsbo->hardening_coefficient;
      ld["odfalk_vingsbo"] = ov;
    } else {
      ld["odfalk_vingsbo"] = nb::none();
    }
    ld["gross_slip_amplitude"] = l.gross_slip_amplitude;
    std::vector<double> a, q, e, imp, n, slip;
    nb::list regimes, loops;
    for (const auto& am : l.amplitudes) {
      a.push_back(am.delta_max);
      // Local energy-force exponent; NaN in gross slip (Q_peak no longer grows).
      n.push_back(am.exponent.value_or(std::numeric_limits<double>::quiet_NaN()));
      slip.push_back(am.gross_slip_area_fraction);
      // NaN: the joint amplitude was given directly (no imposed PZT amplitude).
      imp.push_back(am.imposed.value_or(std::numeric_limits<double>::quiet_NaN()));
      q.push_back(am.Q_peak);
      e.push_back(am.energy);
      regimes.append(am.regime);
      // The load case's own law: Masing, or Odfalk-Vingsbo's steady loop (Eq. 3.10).
      const auto [x, Q] = steady_loop(l, am.delta_max, loop_points);
      nb::dict lp;
      lp["delta"] = array_of(x);
      lp["Q"] = array_of(Q);
      loops.append(lp);
    }
    ld["delta_max"] = array_of(a);
    ld["imposed"] = array_of(imp);
    ld["Q_peak"] = array_of(q);
    ld["energy"] = array_of(e);
    ld["regime"] = regimes;
    ld["loops"] = loops;
    ld["exponent"] = array_of(n);
    ld["gross_slip_area_fraction"] = array_of(slip);
    // The interface's patches (one, the whole area, without [interface]).
    std::vector<double> px0, py0, px1, py1, pa, pf, pg;
    for (const auto& pp : l.patches) {
      px0.push_back(pp.patch.x0);
      py0.push_back(pp.patch.y0);
      px1.push_back(pp.patch.x1);
      py1.push_back(pp.patch.y1);
      pa.push_back(pp.patch.area);
      pf.push_back(pp.patch.force);
      pg.push_back(pp.gross_slip_amplitude);
    }
    nb::dict patches;
    patches["x0"] = array_of(px0);
    patches["y0"] = array_of(py0);
    patches["x1"] = array_of(px1);
    patches["y1"] = array_of(py1);
    patches["area"] = array_of(pa);
    patches["force"] = array_of(pf);
    patches["gross_slip_amplitude"] = array_of(pg);
    ld["patches"] = patches;
    loads.append(ld);
    P.push_back(l.preload);
    mu.push_back(l.mu);
    k.push_back(l.stiffness);
    Qm.push_back(l.Q_max);
    d.push_back(l.separation);
  }
  out["loads"] = loads;
  out["preload"] = array_of(P);
  out["mu"] = array_of(mu);
  out["stiffness"] = array_of(k);
  out["Q_max"] = array_of(Qm);
  out["separation"] = array_of(d);
  return out;
}

}  // namespace

void bind_joint(nb::module_& m) {
  m.def("bolt_preload", &bolt_preload, "torque"_a, "nut_factor"_a = 0.2, "diameter"_a,
        "Bolt preload F = T/(k D) [N] from the input torque T [N m], nut factor k and nominal "
        "diameter D [m] (Eq. 5.2).");
  m.def(
      "predict",
      [](const std::string& case_path, std::size_t loop_points) {
        std::optional<joint::JointCase> c;
        std::optional<joint::JointPrediction> p;
        {
          nb::gil_scoped_release release;  // reading, roughness and the sweep: C++ only
          c.emplace(read_case_file(case_path));
          p.emplace(joint::predict(*c));
        }
        return prediction_dict(*c, *p, loop_points);
      },
      "case_path"_a, "loop_points"_a = 100,
      "Predictions for a joint case file (TOML, see docs/joints.md): a dict with name, model, "
      "area, roughness {sigma, eta, R, beta, psi, halves: per half {source, profiles, "
      "directions, sigma, eta, R}}, arrays preload, mu, stiffness, Q_max, "
      "separation (one entry per load case), and loads: a list of dicts per load case with "
      "the same scalars, arrays delta_max, Q_peak, energy, imposed (the PZT tip amplitude "
      "each delta_max came from; NaN where the amplitude was given directly), a list regime, "
      "loops (dicts of arrays delta, Q: steady loops per amplitude) and backbone (SI). SI "
      "units.");
  m.def(
      "predict_case_text",
      [](const std::string& text, const std::string& base_dir, std::size_t loop_points) {
        // Parsing and predicting touch no Python object: other threads (Dask workers
        // with several threads, asperity.sweep) run meanwhile.
        auto solved = [&] {
          nb::gil_scoped_release release;
          auto c = parse_case(text, "<string>", base_dir);
          auto p = joint::predict(c);
          return std::make_pair(std::move(c), std::move(p));
        }();
        return prediction_dict(solved.first, solved.second, loop_points);
      },
      "text"_a, "base_dir"_a = ".", "loop_points"_a = 100,
      "predict() for case-file text (the GIL is released while parsing and predicting).");
  m.def(
      "check_case_text",
      [](const std::string& text, const std::string& base_dir) {
        const auto c = [&] {
          nb::gil_scoped_release release;
          auto parsed = parse_case(text, "<string>", base_dir);
          parsed.validate();
          return parsed;
        }();
        nb::dict out;
        out["loads"] = c.preloads.size();
        out["amplitudes"] = c.amplitudes.size();
        out["imposed"] = c.imposed.size();
        return out;
      },
      "text"_a, "base_dir"_a = ".",
      "Parses and validates case-file text without predicting (InvalidInput as predict() "
      "would raise it): a dict with the number of load cases, amplitudes and imposed "
      "amplitudes.");
  m.def(
      "analyze_fretting",
      [](const Array1& t, const Array1& delta, const Array1& Q, double P,
         std::optional<Array1> Delta, double stiffness_window, int stiffness_degree,
         bool stiffness_from_imposed) {
        FrettingData d;
        d.source = "data";
        d.t = vec(t);
        d.delta = vec(delta);
        d.Q = vec(Q);
        if (Delta) d.Delta = vec(*Delta);
        const auto a = joint::analyze_fretting(d, P,
                                               {.stiffness_window = stiffness_window,
                                                .stiffness_degree = stiffness_degree,
                                                .stiffness_from_imposed = stiffness_from_imposed});
        nb::dict out;
        out["P"] = a.P;
        out["cycles"] = a.cycles.size();
        nb::list pc;
        for (const auto& c : a.cycles) pc.append(cycle_dict(c));
        out["per_cycle"] = pc;
        out["mean"] = cycle_dict(a.mean);
        out["mu"] = a.mu;
        nb::dict se;
        se["energy"] = a.energy_standard_error;
        se["stiffness"] = a.stiffness_standard_error;
        out["standard_error"] = se;
        out["noise_delta"] = a.noise_delta;
        out["noise_Q"] = a.noise_Q;
        out["energy_noise_floor"] = a.energy_noise_floor;
        out["energy_resolved"] = a.energy_resolved;
        out["stiffness_window_motion"] = a.stiffness_window_motion;
        out["stiffness_noise"] = a.stiffness_noise;
        nb::list warnings;
        for (const auto& w : a.warnings) warnings.append(w);
        out["warnings"] = warnings;
        out["loop_delta"] = array_of(a.loop_delta);
        out["loop_Q"] = array_of(a.loop_Q);
        out["loop_energy"] = a.loop_energy;
        out["stiffness_from_imposed"] = a.stiffness_from_imposed;
        if (a.stiffness_from_imposed) {
          out["apparatus_compliance"] = a.apparatus_compliance;
          out["apparatus_residual_rms"] = a.apparatus_residual_rms;
        }
        return out;
      },
      "t"_a, "delta"_a, "Q"_a, "P"_a, "Delta"_a = nb::none(),
      "stiffness_window"_a = AnalysisOptions{}.stiffness_window,
      "stiffness_degree"_a = AnalysisOptions{}.stiffness_degree, "stiffness_from_imposed"_a = true,
      "Fretting-data analysis (time [s], joint displacement [m], force [N], optional imposed "
      "displacement [m]): cycles, per_cycle and mean metrics (energy, Q_max, delta_max, "
      "stiffness, stiffness_resolved, sliding, partial_slip), mu = Q_max/P (Eq. 6.1), "
      "standard_error {energy, stiffness}, the estimated noise (noise_delta, noise_Q), "
      "energy_noise_floor and energy_resolved, warnings, the averaged loop. The stiffness is "
      "a pooled fit after each reversal (window: fraction of the peak-to-peak force; degree "
      "of the common polynomial), its mean 1/mean(1/k_i). With Delta it comes from Q(Delta) "
      "and the fitted apparatus compliance (apparatus_compliance [m/N], "
      "apparatus_residual_rms [m]) unless stiffness_from_imposed=False.");
  m.def(
      "power_law_exponent",
      [](const Array1& Q_max, const Array1& energy) {
        const auto f = fit_power_law(vec(Q_max), vec(energy));
        nb::dict out;
        out["exponent"] = f.exponent;
        out["standard_error"] = f.standard_error;
        out["ci95"] = nb::make_tuple(f.ci_low, f.ci_high);
        out["runs"] = f.runs;
        return out;
      },
      "Q_max"_a, "energy"_a,
      "Exponent n of energy = c Q_max^n over runs (least squares in log-log; Fig. 6.12-6.14): "
      "a dict with exponent, standard_error and ci95 (95 % Student-t interval; NaN with two "
      "runs) and runs. Leave out runs whose energy is not resolved (analyze_fretting's "
      "energy_resolved).");
  m.def(
      "read_fretting_csv",
      [](const std::string& path) {
        const auto d = read_fretting_csv(path);
        nb::dict out;
        out["t"] = array_of(d.t);
        out["delta"] = array_of(d.delta);
        out["Q"] = array_of(d.Q);
        if (!d.Delta.empty()) out["Delta"] = array_of(d.Delta);
        return out;
      },
      "path"_a,
      "Reads fretting data (columns t, delta, Q, optional Delta; units in the header), SI.");
  m.def(
      "synthetic_experiment",
      [](const std::string& case_path, double preload, double imposed, double frequency, int cycles,
         double sample_rate, double noise_delta, double noise_Q, double k_pzt, double k_lc,
         std::uint64_t seed) {
        const auto c = read_case_file(case_path);
        const auto lp = predict_case_load(c, preload);  // with the case's [interface]
        SyntheticOptions o;
        o.excitation = {.amplitude = imposed, .frequency = frequency, .cycles = cycles};
        o.sample_rate = sample_rate;
        o.noise_delta = noise_delta;
        o.noise_Q = noise_Q;
        o.pzt_stiffness = k_pzt;
        o.load_cell_stiffness = k_lc;
        o.seed = seed;
        const auto d = joint::synthetic_experiment(lp.backbone, o);
        nb::dict out;
        out["t"] = array_of(d.t);
        out["delta"] = array_of(d.delta);
        out["Q"] = array_of(d.Q);
        out["Delta"] = array_of(d.Delta);
        return out;
      },
      "case_path"_a, "preload"_a, "imposed"_a, "frequency"_a = 1.0, "cycles"_a = 10,
      "sample_rate"_a = 1000.0, "noise_delta"_a = 0.1e-6, "noise_Q"_a = 1.0, "k_pzt"_a = 38e6,
      "k_lc"_a = 1462e6, "seed"_a = 1,
      "A synthetic fretting experiment: Eq. 5.3 excitation of half peak-to-peak `imposed` [m], the "
      "joint in series with the apparatus springs of Fig. 5.7, Gaussian noise (seeded). A dict of "
      "arrays t, delta, Q, Delta (SI).");
  m.def(
      "validation_report",
      [] {
        const auto rows = validation_rows();
        nb::list out;
        for (const auto& r : rows) {
          nb::dict d;
          d["source"] = r.source;
          d["quantity"] = r.quantity;
          d["thesis"] = r.thesis;
          d["ours"] = r.ours;
          d["relative_difference"] = r.relative_difference();
          d["tolerance"] = r.tolerance;
          d["verdict"] = r.verdict;
          d["note"] = r.note;
          out.append(d);
        }
        return nb::make_tuple(out, validation_markdown(rows));
      },
      "The thesis's numbers recomputed (asperity validate): (rows, markdown).");
}

}  // namespace asperity::python
