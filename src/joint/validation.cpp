// asperity validate: the thesis's numbers recomputed (chapters 3-6).
#include "asperity/joint/validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/fretting.hpp"
#include "asperity/joint/interface.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::joint {

std::string ValidationRow::kind() const {
  if (verdict.find("model vs experiment") != std::string::npos) return "model vs experiment";
  if (source.find("(regression)") != std::string::npos) return "regression";
  return "reproduction";
}

double ValidationRow::relative_difference() const {
  return thesis != 0.0 ? (ours - thesis) / std::abs(thesis) : ours - thesis;
}

namespace {

using contact::ModelName;

// Relative band within which a model-versus-experiment row reads "agrees (model vs
// experiment)": indicative only (the preloads scatter by about 5 %, section 6.2); such
// rows never fail.
constexpr double kExperimentBand = 0.10;

}  // namespace

ValidationRow experiment_range_row(std::string source, std::string quantity, double lo, double hi,
                                   double ours, std::string note) {
  const double nearer = ours < lo ? lo : (ours > hi ? hi : ours);
  ValidationRow r{std::move(source), std::move(quantity), nearer, ours, 0.0, "", std::move(note)};
  r.range_low = lo;
  r.range_high = hi;
  r.verdict =
      (ours >= lo && ours <= hi) ? "agrees (model vs experiment)" : "differs (model vs experiment)";
  return r;
}

ValidationRow experiment_row(std::string source, std::string quantity, double measured, double ours,
                             std::string note) {
  ValidationRow r{std::move(source), std::move(quantity), measured, ours, kExperimentBand, "",
                  std::move(note)};
  r.verdict = std::abs(r.relative_difference()) <= kExperimentBand
                  ? "agrees (model vs experiment)"
                  : "differs (model vs experiment)";
  return r;
}

namespace {

struct Builder {
  std::vector<ValidationRow> rows;
  // tol: relative tolerance; known: a disagreement documented for this very row
  // (seed_notes.md); out of tolerance without it the row FAILs.
  void add(std::string source, std::string quantity, double thesis, double ours, double tol,
           std::string note = {}, bool known = false) {
    ValidationRow r{std::move(source), std::move(quantity), thesis, ours, tol, "", std::move(note)};
    const bool ok = std::isfinite(ours) && std::abs(r.relative_difference()) <= tol;
    r.verdict = ok ? "agrees" : (known ? "differs (documented)" : "FAIL");
    rows.push_back(std::move(r));
  }
  // ours against a measured range [lo, hi].
  void experiment_range(std::string source, std::string quantity, double lo, double hi, double ours,
                        std::string note) {
    rows.push_back(experiment_range_row(std::move(source), std::move(quantity), lo, hi, ours,
                                        std::move(note)));
  }
  void experiment(std::string source, std::string quantity, double measured, double ours,
                  std::string note) {
    rows.push_back(
        experiment_row(std::move(source), std::move(quantity), measured, ours, std::move(note)));
  }
};

const contact::Material kSteel420{.E = 200e9, .nu = 0.24, .G = 80.7e9, .H = 5.8e9};

void chapter3(Builder& b) {
  const contact::Material ball{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 6.83e9};
  const contact::Material flat{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 7.48e9};
  const auto pair = contact::ContactPair::combine(ball, flat, 2.5e-3);
  const auto c = pair.critical();
  b.add("Table 3.2", "omega_c [um]", 7.41, c.omega_c * 1e6, 5e-3, "section 3.5 text, 3 digits");
  b.add("Table 3.2", "a_c [mm]", 0.136, c.a_c * 1e3, 5e-3);
  b.add("Table 3.2", "P_c [N]", 152.8, c.P_c, 5e-3);
  const contact::FrictionParameters fp{.mu_cfc = 0.284};
  const char* names[] = {"CFC", "CEB", "KE", "BKE"};
  struct Row {
    double P;
    double mu[4];
    double k;
  };
  for (const Row& r : {Row{35.0, {0.284, 0.528, 0.858, 1.444}, 16.17},
                       Row{23.0, {0.284, 0.626, 0.992, 1.639}, 14.06}}) {
    const auto hertz = contact::PartialSlipModel::from_load(pair, ModelName::cfc, r.P, fp);
    for (int i = 0; i < 4; ++i) {
      const auto m = contact::PartialSlipModel::from_interference_star(pair, contact::kAllModels[i],
                                                                       hertz.omega_star(), fp);
      b.add("Table 3.2", fmt::format("mu {} at {} N", names[i], r.P), r.mu[i], m.mu(), 1e-2,
            i == 2 ? "the thesis's KE values are ~0.7 % below B.12" : "");
    }
    b.add("Table 3.2", fmt::format("8 G* a at {} N [N/um]", r.P), r.k, hertz.K_T() * 1e-6, 1e-2);
  }
  // Table 3.4 (nano-scale, silica on silicon).
  const contact::Material sphere{.E = 68.0e9, .nu = 0.19, .G = 28.0e9, .H = 4.8e9};
  const contact::Material si{.E = 112.4e9, .nu = 0.28, .G = 43.9e9, .H = 11.3e9};
  const auto npair = contact::ContactPair::combine(sphere, si, 1.55e-6);
  const contact::FrictionParameters np{.mu_cfc = 0.259};
  struct NRow {
    double P, w;
    double mu[4];
  };
  for (const NRow& r : {NRow{1.1, 0.048, {0.259, 1.769, 2.498, 3.077}},
                        NRow{1.2, 0.051, {0.259, 1.714, 2.424, 2.996}}}) {
    for (int i = 0; i < 4; ++i) {
      const auto m =
          contact::PartialSlipModel::from_interference_star(npair, contact::kAllModels[i], r.w, np);
      b.add("Table 3.4", fmt::format("mu {} at {} uN (omega* = {})", names[i], r.P, r.w), r.mu[i],
            m.mu(), 5e-2, "the thesis evidently used nu = 0.2 (docs/asperity_scale.md)");
    }
  }
}

// Q*_max/P* of a rough flat at P* by a quadrature independent of RoughFlat's: Eq. 4.4 and
// Eq. 4.7 summed over asperity heights with Boost's adaptive Gauss-Kronrod (RoughFlat uses
// tanh-sinh), split at the asperity laws' branch points, and the separation solved for P*
// by TOMS 748. Shares only the asperity laws (ch. 3, checked by Tables 3.2 and 3.4).
double independent_flat_mu(const surface::RoughFlatParameters& p, double P_star) {
  const contact::AsperityLaws laws(p.model, p.nu, p.friction);
  const double s_a = std::sqrt(1.0 - 3.717e-4 / (p.beta * p.beta));  // below Eq. 4.2
  const double wc = s_a / (p.psi * p.psi);                           // Eq. 4.5 on sigma_a
  const double pref = 2.0 * std::numbers::pi / 3.0 * p.beta * wc;    // Eq. 4.4
  const auto integral = [&](double d, bool friction) {
    // u = z* - d* > 0: asperities in contact; the Gaussian (Eq. 4.2) is negligible past
    // |z*| = 40 sigma_a.
    const double u_end = std::max(40.0 * s_a - d, 1e-9);
    std::vector<double> cuts{0.0};
    for (double w : laws.break_points()) {
      if (w * wc < u_end) cuts.push_back(w * wc);
    }
    cuts.push_back(u_end);
    std::sort(cuts.begin(), cuts.end());
    const auto f = [&](double u) {
      const double w = u / wc, z = (d + u) / s_a;
      const double phi = std::exp(-0.5 * z * z) / (std::sqrt(2.0 * std::numbers::pi) * s_a);
      return (friction ? laws.mu(w) : 1.0) * laws.load_star(w) * phi;
    };
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      if (cuts[i + 1] > cuts[i])
        sum += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
            f, cuts[i], cuts[i + 1], 15, 1e-11);
    }
    return pref * sum;
  };
  const auto g = [&](double d) { return std::log(integral(d, false)) - std::log(P_star); };
  double lo = -5.0 * s_a, hi = lo;
  while (g(hi) > 0.0) hi += s_a;
  std::uintmax_t it = 200;
  const auto [x0, x1] = boost::math::tools::toms748_solve(
      g, lo, hi, boost::math::tools::eps_tolerance<double>(44), it);
  const double d = 0.5 * (x0 + x1);
  return integral(d, true) / integral(d, false);
}

void chapter4(Builder& b) {
  const double P = 1e-3;
  const char* names[] = {"CFC", "CEB", "KE", "BKE"};
  const double table41[3][4] = {
      {0.3, 0.83, 1.02, 1.18}, {0.3, 0.29, 0.68, 0.94}, {0.3, 0.03, 0.29, 0.63}};
  // Rows of Table 4.1 we do not reproduce (seed_notes.md: the table does not follow from
  // the printed equations); every other row must agree.
  const bool documented[3][4] = {
      {false, false, true, true}, {false, true, true, true}, {false, true, true, false}};
  const double psis[] = {0.5, 1.0, 2.0};
  std::vector<std::pair<std::string, std::pair<double, double>>> regression;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) {
      const surface::RoughFlatParameters params{.model = contact::kAllModels[i],
                                                .beta = 0.04,
                                                .psi = psis[j],
                                                .nu = 0.3,
                                                .G_over_E = 0.7 / 3.4,
                                                .friction = {.mu_cfc = 0.3}};
      const surface::RoughFlat f(params);
      const double d = f.separation_star(P);
      const double ours = f.static_friction_star(d) / P;
      b.add("Table 4.1", fmt::format("mu {} psi = {}", names[i], psis[j]), table41[j][i], ours,
            5e-2,
            "preload and nu not stated in the thesis: P* = 1e-3, nu = 0.3 (Fig. 4.4); Table 4.1 "
            "does not follow from the printed equations (seed_notes.md)",
            documented[j][i]);
      regression.push_back({fmt::format("mu {} psi = {}", names[i], psis[j]),
                            {independent_flat_mu(params, P), ours}});
    }
  }
  // Our own values against an independent quadrature: these rows fail if the rough flat's
  // summation changes.
  for (const auto& [q, v] : regression) {
    b.add("Table 4.1 (regression)", q, v.first, v.second, 1e-6,
          "reference: Eq. 4.4/4.7 by an independent adaptive Gauss-Kronrod quadrature");
  }
  // Fig. 4.4 statements (beta = 0.04, psi = 0.5, P* = 1e-3, nu = 0.3).
  const auto flat = [&](ModelName m) {
    return surface::RoughFlat({.model = m,
                               .beta = 0.04,
                               .psi = 0.5,
                               .nu = 0.3,
                               .G_over_E = 0.7 / 3.4,
                               .friction = {.mu_cfc = 0.3}});
  };
  const auto cfc = flat(ModelName::cfc);
  const double d = cfc.separation_star(P);
  b.add("Fig. 4.4", "CFC Q*_max / P*", 0.3, cfc.static_friction_star(d) / P, 1e-9);
  b.add("Fig. 4.4", "CFC Q*_l(0.6) / Q*_max (>= 0.997)", 0.997,
        std::min(0.997, cfc.loading_force_star(0.6, d) / cfc.static_friction_star(d)), 1e-12,
        "our value is capped at the statement's bound: the row agrees iff the statement holds");
  double W[4];
  for (int i = 1; i < 4; ++i) {
    const auto f = flat(contact::kAllModels[i]);
    W[i] = f.energy_star(0.6, f.separation_star(P));
  }
  b.add("Fig. 4.4", "loop area CEB > KE > BKE (1 = holds)", 1.0,
        (W[1] > W[2] && W[2] > W[3]) ? 1.0 : 0.0, 0.0,
        fmt::format("energy* per cycle {:.3g} > {:.3g} > {:.3g}", W[1], W[2], W[3]));
}

void roughness_rows(Builder& b, const std::string& source, const std::string& label,
                    const contact::Material& mat, const double half1[3], const double half2[3],
                    const double comb[3], bool with_R, const double* psi = nullptr) {
  const auto m1 =
      surface::SpectralMoments::from_parameters(half1[0] * 1e-6, half1[1] * 1e12, half1[2] * 1e-6);
  const auto m2 =
      surface::SpectralMoments::from_parameters(half2[0] * 1e-6, half2[1] * 1e12, half2[2] * 1e-6);
  const auto c = surface::combine(m1, m2);
  // Printed to 3 decimals: half a unit of the last digit of the result and of each input
  // (d sigma = (s1 ds1 + s2 ds2)/sigma).
  b.add(source, label + " combined sigma [um]", comb[0], c.sigma() * 1e6,
        (0.5e-3 + 0.5e-3 * (half1[0] + half2[0]) / comb[0]) / comb[0],
        "rounding of the printed inputs and result");
  b.add(source, label + " combined eta [um^-2]", comb[1], c.eta() * 1e-12, 0.5e-6 / comb[1] + 2e-3,
        with_R ? ""
               : fmt::format("the halves' R is not legible in the thesis: ASSUMED {} and {} um "
                             "(beta = 0.024 like the other rough halves); R not compared",
                             half1[2], half2[2]));
  if (with_R) b.add(source, label + " combined R [um]", comb[2], c.R() * 1e6, 1e-3);
  if (psi) {
    const auto pair = contact::ContactPair::combine(mat, mat, 1.0);
    const char* note = "H = 5.8 GPa (Table 7.2), psi on sigma_a; 1 %: the thesis's H is not stated";
    b.add(source, label + " psi PZT half", psi[0], surface::plasticity_index(pair, m1), 1e-2, note);
    b.add(source, label + " psi LC half", psi[1], surface::plasticity_index(pair, m2), 1e-2, note);
    b.add(source, label + " psi combined", psi[2], surface::plasticity_index(pair, c), 1e-2, note);
  }
}

// Table 6.2: roughness of the PZT and load-cell halves (sigma [um], eta [um^-2], R [um])
// and of their combination, before and after the experiments.
struct T62 {
  const char* label;
  double h1[3], h2[3], c[3];
  bool R;
};
const T62 kTable62[] = {
    {"smooth Al before",
     {0.507, 3.87e-4, 129.451},
     {0.655, 3.26e-4, 152.867},
     {0.828, 3.59e-4, 98.788},
     true},
    {"smooth Al after",
     {0.506, 4.09e-4, 130.186},
     {0.537, 3.58e-4, 138.147},
     {0.738, 3.83e-4, 94.745},
     true},
    {"rough Al before",
     {2.243, 3.00e-4, 39.119},
     {1.791, 3.35e-4, 40.071},
     {2.870, 3.16e-4, 27.992},
     true},
    {"rough Al after",
     {1.903, 3.12e-4, 41.142},
     {1.812, 3.28e-4, 43.410},
     {2.628, 3.20e-4, 29.862},
     true},
    {"smooth steel before",
     {0.387, 3.63e-4, 194.631},
     {0.424, 3.56e-4, 163.532},
     {0.574, 3.59e-4, 125.204},
     true},
    {"smooth steel after",
     {0.357, 3.68e-4, 210.931},
     {0.438, 3.55e-4, 167.981},
     {0.566, 3.60e-4, 131.403},
     true},
    // R of the rough steel is not legible in the thesis text: sigma and eta only (eta
    // of the combination needs R of the halves: beta = 0.024 assumed, see the example).
    {"rough steel before",
     {1.848, 3.23e-4, 40.2},
     {1.863, 3.05e-4, 42.2},
     {2.624, 3.14e-4, 0.0},
     false},
};

// Table 6.1 (E, nu, G) with the hardness we assume (the thesis gives none for ch. 6):
// aluminium 6061-T6 0.93 GPa (Brinell 95 HB), steel 420 5.8 GPa (Table 7.2).
const contact::Material kAl6061{.E = 69e9, .nu = 0.33, .G = 26.2e9, .H = 0.93e9};

// Table 6.4, dry: average mu = Q_max^av/P (Eq. 6.1) at 0.192/0.305/0.418 N m.
struct T64 {
  const char* joint;  // example file stem
  const char* label;
  double mu[3];
};
const T64 kTable64[] = {{"aluminium_smooth", "smooth Al", {0.31, 0.61, 0.52}},
                        {"aluminium_rough", "rough Al", {0.32, 0.59, 0.54}},
                        {"steel_smooth", "smooth St", {0.42, 0.47, 0.57}},
                        {"steel_rough", "rough St", {0.68, 0.72, 0.53}}};

void chapter5_6(Builder& b) {
  {
    const double h1[] = {1.763, 3.34e-4, 40.76}, h2[] = {2.015, 2.51e-4, 44.77},
                 c[] = {2.677, 2.91e-4, 30.14};
    const double psi[] = {3.374, 3.230, 4.725};
    roughness_rows(b, "Table 5.4", "before", kSteel420, h1, h2, c, true, psi);
    const double a1[] = {1.859, 2.87e-4, 44.75}, a2[] = {1.847, 2.68e-4, 47.37},
                 ac[] = {2.620, 2.77e-4, 32.53};
    const double apsi[] = {3.284, 3.122, 4.534};
    roughness_rows(b, "Table 5.4", "after", kSteel420, a1, a2, ac, true, apsi);
  }
  for (const auto& t : kTable62)
    roughness_rows(b, "Table 6.2", t.label, kSteel420, t.h1, t.h2, t.c, t.R);

  // Eq. 5.2 tables.
  const double lbf_in = 0.112984829;  // N m
  {
    const double T[] = {0.5, 1.5, 5.0}, P[] = {99, 298, 993};
    for (int i = 0; i < 3; ++i) {
      b.add("Table 5.2", fmt::format("preload at {} lb-in [N]", T[i]), P[i],
            bolt_preload(T[i] * lbf_in, 0.2, 2.845e-3), 5e-3, "#4-48 UNF, D = 2.845 mm, k = 0.2");
    }
  }
  {
    const double T[] = {1.2, 1.7, 2.7, 3.7}, P[] = {234, 331, 526, 721}, p[] = {1.4, 2.0, 3.2, 4.4};
    for (int i = 0; i < 4; ++i) {
      const double F = bolt_preload(T[i] * lbf_in, 0.2, 2.9e-3);
      b.add("Table 5.5", fmt::format("preload at {} lb-in total [N]", T[i]), P[i], F, 2.5e-3,
            "total torque of the two M3 bolts, D = 2.9 mm, k = 0.2");
      b.add("Table 5.5", fmt::format("p_mean at {} lb-in [MPa], A0 = 165 mm^2", T[i]), p[i],
            F / 165e-6 * 1e-6, 0.05 / p[i] + 1e-3,
            "the printed p_mean use 165 mm^2 (ch. 6), not the 170 mm^2 of this joint");
    }
  }
  {
    const double T[] = {0.192, 0.305, 0.418}, P[] = {331, 526, 721};
    for (int i = 0; i < 3; ++i) {
      b.add("Table 6.3", fmt::format("preload at {} N m [N]", T[i]), P[i],
            bolt_preload(T[i], 0.2, 2.9e-3), 2.5e-3);
    }
  }
  // Chapter 5 BKE friction coefficients (section 5.3).
  const auto ch5 = chapter5_joint();
  const auto flat = ch5.rough_flat();
  const double* const P = ch5.reference->preloads.data();  // 234, 331, 526, 721 N
  const double* const mu = ch5.reference->mu.data();
  for (int i = 0; i < 4; ++i) {
    const auto lp = predict_load(flat, P[i], {});
    b.add("Ch. 5 mu (BKE)", fmt::format("mu at {} N", P[i]), mu[i], lp.mu, 5e-2,
          "issue 5 asks for 5 %; ours falls slowly with preload, the thesis's is not monotone");
  }
  // Table 5.6: the model in the apparatus (Fig. 5.7) against the measurements: the
  // joint amplitude of a steady cycle from delta + c Q_l(delta) = 6.75 um.
  const double dmax[] = {4.26, 2.69, 1.32, 0.79}, mu_exp[] = {0.479, 0.508, 0.420, 0.323};
  const Apparatus app{};
  for (int i = 0; i < 4; ++i) {
    const auto lp = predict_load(flat, P[i], {}, {6.75e-6}, app.compliance());
    const auto& a = lp.amplitudes.front();
    b.experiment("Table 5.6", fmt::format("delta_max at {} N [um] (PZT 6.75 um)", P[i]), dmax[i],
                 a.delta_max * 1e6, "model in series with the 38 N/um PZT side (Fig. 5.7)");
    b.experiment("Table 5.6", fmt::format("mu = Q_max/P at {} N", P[i]), mu_exp[i], a.Q_peak / P[i],
                 "measured mu against the BKE loop's peak force");
  }
  // Table 6.4: the chapter 6 joints' static friction coefficient (Eq. 4.7) against the
  // measured dry mu of Eq. 6.1 (which equals it in gross slip, section 6.3).
  const auto joints = chapter6_joints();
  for (std::size_t k = 0; k < joints.size(); ++k) {
    const auto f = joints[k].rough_flat();
    for (std::size_t i = 0; i < 3; ++i) {
      const double Pi = joints[k].preloads[i];
      const auto& sc = *f.scales();
      const double mu_ours =
          f.static_friction_star(f.separation_star(Pi / sc.force)) * sc.force / Pi;
      b.experiment("Table 6.4",
                   fmt::format("{} dry mu at {:.3g} N m ({:.0f} N)", kTable64[k].label,
                               joints[k].bolts->torques[i] * 2.0, Pi),
                   kTable64[k].mu[i], mu_ours,
                   "BKE static mu of the ch. 6 example (assumed hardness, docs/joints.md) "
                   "against the measured dry mu");
    }
  }
}

// A model variant of issue 11: the interface's pressure (uniform or under the bolts) and
// the stiffness between the measurement points (interface alone or with the halves).
struct Variant {
  const char* name;
  bool bolts;
  bool halves;
};
const Variant kVariants[] = {{"uniform", false, false},
                             {"bolt field", true, false},
                             {"uniform + halves", false, true},
                             {"bolt field + halves", true, true}};

const char* kBoltNote =
    "bolt field: pressure cones (Rotscher/Shigley, 30 deg) with ASSUMED geometry (bolts at the "
    "quarter points of the centre line, d_w 5.5 mm, hole 3.4 mm, halves 5 mm thick)";
const char* kHalvesNote =
    "halves: ASSUMED 5 mm free length, 5 mm thick, 10 mm wide each, C = sum L/(E w t) in "
    "series";

// The case of a variant: the bolt field and/or the halves in series ([interface]).
JointCase variant_case(const JointCase& base, const Variant& v) {
  JointCase c = v.bolts ? with_assumed_bolt_field(base) : base;
  if (v.halves) c.interface.halves = assumed_halves();
  return c;
}

// Stiffness, Table 5.6's displacement and the energy-force exponent for every variant,
// against the measurements (issue 11, item 4). No constant is adjusted to them.
void variant_rows(Builder& out, std::vector<VariantPoint>* points) {
  Builder b;
  const auto ch5 = chapter5_joint();
  const double dmax[] = {4.26, 2.69, 1.32, 0.79};
  for (const auto& v : kVariants) {
    const auto c = variant_case(ch5, v);
    for (std::size_t i = 0; i < ch5.preloads.size(); ++i) {
      const double P = ch5.preloads[i];
      // The PZT tip's 6.75 um through the apparatus (Fig. 5.7); with the halves the joint's
      // displacement (and stiffness) is that between the measurement points.
      const auto lp = predict_case_load(c, P, {}, {6.75e-6});
      const auto& a = lp.amplitudes.front();
      if (points) points->push_back({"ch. 5", v.name, P, lp.stiffness, 10e6, 300e6, std::nullopt});
      std::string note = v.bolts ? kBoltNote : "uniform P/A0 (today's model)";
      if (v.halves) note += std::string("; ") + kHalvesNote;
      b.experiment_range(
          "Ch. 5 stiffness (section 5.2: 10-300 N/um)",
          fmt::format("k at {:.0f} N [N/um], {}", P, v.name), 10.0, 300.0, lp.stiffness * 1e-6,
          note + "; the range is the text's for all the joints tested (section 5.2)");
      b.experiment("Table 5.6 by variant", fmt::format("delta_max at {:.0f} N [um], {}", P, v.name),
                   dmax[i], a.delta_max * 1e6,
                   note + "; PZT 6.75 um through the 38 N/um apparatus (Fig. 5.7)");
    }
  }
  // Chapter 6: Fig. 6.11 (dry stiffness: steel about 200-275, aluminium about 30-65 N/um,
  // section 6.3 text) and Fig. 6.12-6.14 (energy ~ Q^n with n between 2 and 3 except in
  // gross slip).
  const auto joints = chapter6_joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const bool steel = j >= 2;
    const double lo = steel ? 200.0 : 30.0, hi = steel ? 275.0 : 65.0;
    for (const auto& v : kVariants) {
      const auto c = variant_case(joints[j], v);
      for (std::size_t i = 0; i < c.preloads.size(); ++i) {
        const double P = c.preloads[i];
        const auto lp = predict_case_load(c, P, {}, {2.25e-6});
        std::string note = v.bolts ? kBoltNote : "uniform P/A0";
        if (v.halves) note += std::string("; ") + kHalvesNote;
        if (!steel) note += "; aluminium hardness ASSUMED 0.93 GPa";
        if (j == 3) note += "; rough steel R ASSUMED (Table 6.2 illegible)";
        b.experiment_range("Fig. 6.11 stiffness (dry; steel 200-275, Al 30-65 N/um)",
                           fmt::format("{} k at {:.0f} N [N/um], {}", kTable64[j].label, P, v.name),
                           lo, hi, lp.stiffness * 1e-6,
                           note + "; ranges read from the text of section 6.3, not the figure");
        const auto& a = lp.amplitudes.front();
        if (points) {
          points->push_back({kTable64[j].label, v.name, P, lp.stiffness, lo * 1e6, hi * 1e6,
                             v.halves ? std::nullopt : a.exponent});
        }
        if (v.halves) continue;  // a series spring leaves W(Q_peak) unchanged
        if (!a.exponent) continue;
        b.experiment_range(
            "Fig. 6.12-6.14 energy-force exponent (2-3)",
            fmt::format("{} n at {:.0f} N, PZT 2.25 um (Q/Q_max = {:.2f}), {}", kTable64[j].label,
                        P, a.Q_ratio, v.name),
            2.0, 3.0, *a.exponent,
            note + "; local d ln W/d ln Q_peak at the smallest imposed amplitude of section 6.2");
      }
    }
  }
  // One section per source, in the order the sources first appear.
  std::vector<std::string> order;
  for (const auto& r : b.rows)
    if (std::find(order.begin(), order.end(), r.source) == order.end()) order.push_back(r.source);
  for (const auto& src : order)
    for (auto& r : b.rows)
      if (r.source == src) out.rows.push_back(std::move(r));
}

JointCase chapter6_joint(const char* name, const char* title, const contact::Material& m,
                         const T62& t) {
  JointCase c;
  c.name = title;
  c.source = fmt::format("chapter 6 (built in, = examples/joints/{}.toml)", name);
  c.area = 165e-6;  // section 6.2: 165 mm^2
  for (int h = 0; h < 2; ++h) {
    const double* v = h == 0 ? t.h1 : t.h2;
    c.halves[h] = {
        m,
        {surface::SpectralMoments::from_parameters(v[0] * 1e-6, v[1] * 1e12, v[2] * 1e-6), {}, {}}};
  }
  Bolts bolts{.count = 2, .nut_factor = 0.2, .diameter = 2.9e-3, .torques = {}};
  for (double T : {0.192, 0.305, 0.418}) {  // Table 6.3, total over the two bolts
    bolts.torques.push_back(T / 2.0);
    c.preloads.push_back(bolts.preload(T / 2.0));
  }
  c.bolts = bolts;
  c.amplitudes = {0.02e-6, 0.05e-6, 0.1e-6, 0.25e-6};
  c.imposed = {2.25e-6, 4.5e-6, 6.75e-6, 9e-6, 11.25e-6, 13.5e-6, 15.75e-6, 18e-6};
  return c;
}

}  // namespace

std::vector<JointCase> chapter6_joints() {
  return {chapter6_joint("aluminium_smooth", "smooth aluminium 6061-T6 lap joint (thesis ch. 6)",
                         kAl6061, kTable62[0]),
          chapter6_joint("aluminium_rough", "rough aluminium 6061-T6 lap joint (thesis ch. 6)",
                         kAl6061, kTable62[2]),
          chapter6_joint("steel_smooth", "smooth steel 420 lap joint (thesis ch. 6)", kSteel420,
                         kTable62[4]),
          chapter6_joint("steel_rough", "rough steel 420 lap joint (thesis ch. 6)", kSteel420,
                         kTable62[6])};
}

JointCase chapter5_joint() {
  JointCase c;
  c.name = "steel 420 lap joint, two bolts (thesis ch. 5)";
  c.source = "chapter 5 (built in, = examples/joints/steel420_two_bolts.toml)";
  c.area = 170e-6;  // 10 x 17 mm^2 (section 5.5)
  c.halves[0] = {kSteel420,
                 {surface::SpectralMoments::from_parameters(1.763e-6, 3.34e8, 40.76e-6), {}, {}}};
  c.halves[1] = {kSteel420,
                 {surface::SpectralMoments::from_parameters(2.015e-6, 2.51e8, 44.77e-6), {}, {}}};
  // Table 5.5: total torque on the two M3 bolts [lbf in], Eq. 5.2 with k = 0.2, D = 2.9 mm.
  Bolts bolts{.count = 2, .nut_factor = 0.2, .diameter = 2.9e-3, .torques = {}};
  const double lbf_in = 4.4482216152605 * 0.0254;  // N m: the exact lbf and inch
  for (double T : {1.2, 1.7, 2.7, 3.7}) {
    bolts.torques.push_back(T * lbf_in / 2.0);
    c.preloads.push_back(bolts.preload(T * lbf_in / 2.0));
  }
  c.bolts = bolts;
  c.amplitudes = {0.05e-6, 0.1e-6, 0.25e-6, 0.5e-6, 1e-6, 2e-6, 4e-6};
  // Section 5.3: the thesis's BKE mu at the four preloads (also a row of validation_rows).
  c.reference = ReferenceMu{.source = "thesis section 5.3 (BKE)",
                            .preloads = {234, 331, 526, 721},
                            .mu = {0.354, 0.334, 0.335, 0.347}};
  return c;
}

JointCase with_assumed_bolt_field(JointCase c) {
  const double Ly = 10e-3, Lx = c.area / Ly;
  c.interface.pressure = PressureKind::bolted;
  c.interface.outline = std::array<double, 2>{Lx, Ly};
  c.interface.patches = {static_cast<int>(std::lround(Lx * 1e3)), 10};
  c.interface.bolts.positions = {{0.25 * Lx, 0.5 * Ly}, {0.75 * Lx, 0.5 * Ly}};
  c.interface.bolts.head_diameter = 5.5e-3;
  c.interface.bolts.hole_diameter = 3.4e-3;
  c.interface.bolts.thickness = {5e-3, 5e-3};
  return c;
}

HalvesGeometry assumed_halves() {
  return {{5e-3, 5e-3}, {5e-3, 5e-3}, 10e-3};
}

std::vector<ValidationRow> validation_rows(std::vector<VariantPoint>* points) {
  Builder b;
  chapter3(b);
  chapter4(b);
  chapter5_6(b);
  variant_rows(b, points);
  return b.rows;
}

std::string validation_markdown(const std::vector<ValidationRow>& rows) {
  std::string s = "# Validation against the thesis\n\n";
  s += "Generated by `asperity validate` (the test suite runs it and checks this file is\n"
       "current). Each row recomputes one number of Eriten (2012) with the library. The\n"
       "`reference` column is the thesis's value; in `(regression)` sections it is our own\n"
       "value by an independent quadrature, and in model-versus-experiment rows (Tables 5.6,\n"
       "6.4, and the sections per model variant: stiffness, Table 5.6 by variant, energy-force\n"
       "exponent) the measurement, a value or a range `lo-hi` read from the thesis's text.\n"
       "Variants (docs/joints.md, \"The interface as a pressure field\"): `uniform` (P/A0,\n"
       "the chapter 4 rough flat), `bolt field` (pressure cones under the two bolts, patches\n"
       "each a rough flat at its own pressure), each also `+ halves` (the halves' elastic\n"
       "compliance in series); the geometry these need is not printed in the thesis and is\n"
       "ASSUMED as each row's note says. No constant is adjusted to a measurement.\n"
       "Verdicts: `agrees` (within the row's relative tolerance),\n"
       "`differs (documented)` (a disagreement documented for that row in docs/seed_notes.md\n"
       "and the linked docs), `FAIL` (anything else: `asperity validate` exits 1), and for\n"
       "model-versus-experiment rows, which are not reproductions and never fail, `agrees\n"
       "(model vs experiment)` within an indicative 10 % (inside the range, for a range) or\n"
       "`differs (model vs experiment)`. The summary counts the three kinds of row apart.\n"
       "`asperity validate --fem examples/lap_joint_ch5/lap_joint_ch5.toml` adds the chapter 5\n"
       "joint with its bodies in the fretting apparatus (finite elements with the rough\n"
       "contact at every interface element, several minutes; docs/structures.md): its\n"
       "stiffness, Table 5.6's delta_max and the energy-force exponent at the four preloads,\n"
       "twelve more model-versus-experiment rows (not in this file).\n\n";
  std::map<std::string, std::map<std::string, int>> count;  // kind -> verdict -> rows
  for (const auto& r : rows) ++count[r.kind()][r.verdict];
  s +=
      "Figures (`asperity validate --out DIR` writes them next to validation.md): the chapter 5\n"
      "joint's loops at 4 um (`ch5_loops.png`), energy per cycle against peak force with slope-2\n"
      "and slope-3 guides (`ch5_energy_vs_force.png`, cf. Fig. 6.12-6.14), mu and stiffness\n"
      "against preload (`ch5_mu_vs_preload.png`, `ch5_stiffness_vs_preload.png`); per model\n"
      "variant with the measured ranges: stiffness against preload (`ch5_stiffness_variants.png`,\n"
      "`ch6_stiffness_variants.png`) and the ch. 6 energy-force exponent\n"
      "(`ch6_exponent_vs_preload.png`).\n\n";
  // Reproductions of the thesis's numbers, regressions (our own value by an independent
  // method), and the model against measurements, counted apart.
  s += "Summary:";
  for (const char* kind : {"reproduction", "regression", "model vs experiment"}) {
    int n = 0;
    for (const auto& [v, k] : count[kind]) n += k;
    s += fmt::format(" {} {} rows (", n,
                     kind == std::string("reproduction") ? "reproduction"
                     : kind == std::string("regression") ? "regression (our own reference)"
                                                         : "model-versus-experiment");
    std::string parts;
    for (const auto& [v, k] : count[kind])
      parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", k, v);
    s += parts + ");";
  }
  s.back() = '\n';
  s += "\n";
  std::string current;
  for (const auto& r : rows) {
    if (r.source != current) {
      current = r.source;
      s += fmt::format(
          "\n## {}\n\n| quantity | reference | ours | rel. diff. | tolerance | verdict | note |\n"
          "| --- | --- | --- | --- | --- | --- | --- |\n",
          current);
    }
    // A difference that rounds to 0.00 % is printed unsigned: its sign is round-off and
    // would make the report differ between machines.
    const double d = 100.0 * r.relative_difference();
    const bool range = r.range_high > 0.0;
    s += fmt::format("| {} | {} | {:.5g} | {} % | {} | {} | {} |\n", r.quantity,
                     range ? fmt::format("{:.5g}-{:.5g}", r.range_low, r.range_high)
                           : fmt::format("{:.5g}", r.thesis),
                     r.ours, std::abs(d) < 0.005 ? std::string("0.00") : fmt::format("{:+.2f}", d),
                     range ? std::string("range") : fmt::format("{:.3g} %", 100.0 * r.tolerance),
                     r.verdict, r.note);
  }
  return s;
}

}  // namespace asperity::joint
