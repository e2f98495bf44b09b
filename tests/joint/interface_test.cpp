// The interface as a pressure field in patches (issue 11): joint/interface.hpp,
// surface/patched_flat.hpp, hysteresis/sum_backbone.hpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "../support.hpp"
#include "asperity/dynamics/case.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "asperity/hysteresis/sum_backbone.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/interface.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"
#include "asperity/surface/patched_flat.hpp"
#include "asperity/vibration/case.hpp"

namespace {

using namespace asperity;
using asperity::testing::invalid_input_message;
using asperity::testing::rel;
namespace fs = std::filesystem;

const double kAmplitudes[] = {0.01e-6, 0.05e-6, 0.1e-6, 0.25e-6, 0.5e-6, 1e-6, 2e-6, 4e-6};

// The chapter 5 joint (Tables 5.3-5.5) with the assumed two-bolt geometry of
// examples/joints/steel420_bolt_field.toml.
joint::JointCase bolted_case(int nx = 17, int ny = 10) {
  auto c = joint::chapter5_joint();
  c.interface.pressure = joint::PressureKind::bolted;
  c.interface.outline = std::array<double, 2>{17e-3, 10e-3};
  c.interface.patches = {nx, ny};
  c.interface.bolts.positions = {{4.25e-3, 5e-3}, {12.75e-3, 5e-3}};
  c.interface.bolts.head_diameter = 5.5e-3;
  c.interface.bolts.hole_diameter = 3.4e-3;
  c.interface.bolts.thickness = {5e-3, 5e-3};
  return c;
}

std::vector<double> amplitudes() {
  return {std::begin(kAmplitudes), std::end(kAmplitudes)};
}

// A uniform field in any number of patches gives today's (one rough flat over A0) results:
// every patch sits at the same P*, so the patches' sum is the one flat's. 1e-12: the
// patch pressures P/n over A0/n round differently from P/A0 in the last bits, and the
// patched path takes Q_max and the stiffness from the table's one-pass asperity sum
// (rough_flat.hpp: ~1e-13) where today's takes them from the adaptive quadrature. (A case
// without [interface] runs today's code itself: no difference at all.)
TEST(InterfacePatches, UniformFieldOfAnyPatchCountIsTodaysJoint) {
  auto c = joint::chapter5_joint();
  const auto flat = c.rough_flat();
  for (const auto& [nx, ny] : {std::pair{1, 1}, {2, 3}, {7, 5}, {17, 10}}) {
    c.interface.pressure = joint::PressureKind::uniform;
    c.interface.patches = {nx, ny};
    for (double P : c.preloads) {
      const auto today = joint::predict_load(flat, P, amplitudes(), {6.75e-6}, 2.7e-8);
      const auto patches = joint::case_patches(c, P);
      ASSERT_EQ(patches.size(), static_cast<std::size_t>(nx * ny));
      const auto field = joint::predict_load(flat, P, patches, amplitudes(), {6.75e-6}, 2.7e-8);
      EXPECT_EQ(field.distinct_patch_sums, 1u);
      EXPECT_LT(rel(field.mu, today.mu), 1e-12);
      EXPECT_LT(rel(field.stiffness, today.stiffness), 1e-12);
      EXPECT_LT(rel(field.Q_max, today.Q_max), 1e-12);
      EXPECT_LT(rel(field.d_star, today.d_star), 1e-12);
      EXPECT_LT(rel(field.gross_slip_amplitude, today.gross_slip_amplitude), 1e-12);
      ASSERT_EQ(field.amplitudes.size(), today.amplitudes.size());
      for (std::size_t i = 0; i < today.amplitudes.size(); ++i) {
        const auto &a = field.amplitudes[i], &b = today.amplitudes[i];
        EXPECT_LT(rel(a.delta_max, b.delta_max), 1e-12);
        EXPECT_LT(rel(a.Q_peak, b.Q_peak), 1e-12) << nx << "x" << ny << " " << P;
        // W = 8 Int Q_l - 4 x Q_l loses the digits of 8 x Q_l / W to cancellation.
        EXPECT_LT(rel(a.energy, b.energy), 1e-12 * 8.0 * b.delta_max * b.Q_peak / b.energy);
        EXPECT_EQ(a.regime, b.regime);
      }
    }
  }
}

// The total normal force of the patches is the preload: every field kind.
TEST(InterfacePatches, TotalNormalForceIsThePreload) {
  for (const auto& c : {bolted_case(), bolted_case(8, 5), bolted_case(34, 10)}) {
    for (double P : c.preloads) {
      double F = 0.0;
      for (const auto& p : joint::case_patches(c, P)) {
        EXPECT_GE(p.force, 0.0);
        F += p.force;
      }
      EXPECT_LT(rel(F, P), 1e-12);  // rounding of a sum of 40-340 terms
    }
  }
}

// Rotscher's cone at the interface: r_c = d_w/2 + min(t1, t2) tan(alpha); one bolt far
// from the edges spreads its force uniformly over the annulus r_h <= r <= r_c, so a patch
// wholly inside the annulus carries F/(pi (r_c^2 - r_h^2)) per unit area. The annulus's
// area is found by midpoint sampling (16 x 16 per patch), whose error at the two circles
// is a fraction of a sample row: 1 % covers it at 0.25 mm patches (a row of samples
// around r_c = 5.6 mm is 0.016 mm wide: 0.3 % of the area).
TEST(InterfacePatches, PressureConeOfOneBoltIsItsClosedForm) {
  joint::InterfaceSpec s;
  s.pressure = joint::PressureKind::bolted;
  s.outline = std::array<double, 2>{20e-3, 20e-3};
  s.patches = {80, 80};
  s.bolts.positions = {{10e-3, 10e-3}};
  s.bolts.head_diameter = 5.5e-3;
  s.bolts.hole_diameter = 3.4e-3;
  s.bolts.thickness = {5e-3, 8e-3};
  const double rc = 2.75e-3 + 5e-3 * std::tan(std::numbers::pi / 6.0);
  EXPECT_LT(rel(s.bolts.footprint_radius(), rc), 1e-15);
  const double P = 500.0;
  const double p_cone = P / (std::numbers::pi * (rc * rc - 1.7e-3 * 1.7e-3));
  std::size_t inside = 0, outside = 0;
  for (const auto& p : joint::interface_patches(s, 400e-6, P)) {
    const double cx = 0.5 * (p.x0 + p.x1) - 10e-3, cy = 0.5 * (p.y0 + p.y1) - 10e-3;
    const double r = std::hypot(cx, cy), half_diag = 0.25e-3 * std::sqrt(0.5);
    if (r - half_diag > 1.7e-3 && r + half_diag < rc) {
      EXPECT_LT(rel(p.pressure(), p_cone), 1e-2);
      ++inside;
    } else if (r - half_diag > rc) {
      EXPECT_EQ(p.force, 0.0);
      ++outside;
    }
  }
  EXPECT_GT(inside, 100u);
  EXPECT_GT(outside, 100u);
}

// Masing's rules of the summed backbone equal the sum of every patch's Masing response
// along the same random displacement histories (with reversals, inner loops and loop
// closing). The sum is exact in exact arithmetic (sum_backbone.hpp); 1e-12 of the joint's
// static friction covers the rounding of summing ~50 patch forces.
TEST(InterfacePatches, SummedBackboneLoopsArePatchByPatchMasingSum) {
  const auto c = bolted_case();
  const auto flat = c.rough_flat();
  const auto& sc = *flat.scales();
  const double P = c.preloads[2];
  const auto lp = joint::predict_load(flat, P, joint::case_patches(c, P), {}, {}, 0.0);
  ASSERT_GT(lp.patches.size(), 100u);
  ASSERT_GT(lp.distinct_patch_sums, 10u);
  std::vector<std::shared_ptr<const hysteresis::Backbone>> parts;
  for (const auto& p : lp.patches) {
    const auto one = std::make_shared<const surface::PatchedRoughFlatBackbone>(
        flat, std::vector<surface::FlatPatch>{{p.patch.area / sc.A0, p.d_star}});
    parts.push_back(std::make_shared<hysteresis::ScaledBackbone>(one, sc.sigma, sc.force));
  }
  const auto sum = std::make_shared<const hysteresis::SumBackbone>(parts);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> step(-0.4e-6, 0.4e-6);
  for (int run = 0; run < 5; ++run) {
    std::vector<double> x{0.0};
    for (int i = 0; i < 400; ++i) x.push_back(x.back() + step(gen) * (1.0 + run));
    const auto Q_sum = hysteresis::Hysteresis(sum).forces(x);
    std::vector<double> Q_parts(x.size(), 0.0);
    for (const auto& part : parts) {
      const auto q = hysteresis::Hysteresis(part).forces(x);
      for (std::size_t i = 0; i < x.size(); ++i) Q_parts[i] += q[i];
    }
    for (std::size_t i = 0; i < x.size(); ++i)
      ASSERT_LT(std::abs(Q_sum[i] - Q_parts[i]), 1e-12 * sum->limit()) << run << " " << i;
    // The tabulated sum (what predict, flat, dynamics use) follows the same loops within
    // its verified bound (3x: the patch tables' own bounds add to the sum's).
    const auto Q_table = hysteresis::Hysteresis(lp.backbone).forces(x);
    const auto& table = dynamic_cast<const hysteresis::ScaledBackbone&>(*lp.backbone).inner();
    const double bound =
        3.0 * dynamic_cast<const hysteresis::TabulatedBackbone&>(table).verified_error();
    ASSERT_LT(bound, 1e-8);
    for (std::size_t i = 0; i < x.size(); ++i)
      ASSERT_LT(std::abs(Q_table[i] - Q_sum[i]), 4.0 * bound * sum->limit()) << run << " " << i;
  }
  EXPECT_LT(rel(sum->limit(), lp.Q_max), 1e-12);
  EXPECT_LT(rel(sum->initial_stiffness(), lp.stiffness), 1e-12);
}

// All the pressure on one patch: the joint is that patch's rough flat (area A_i at P).
TEST(InterfacePatches, AllPressureOnOnePatchIsThatPatchsFlat) {
  const auto c = joint::chapter5_joint();
  const auto flat = c.rough_flat();
  const double A_i = c.area / 4.0, P = 200.0;
  std::vector<joint::InterfacePatch> patches{
      {0, 0, 1, 1, A_i, 0.0}, {1, 0, 2, 1, A_i, P}, {0, 1, 1, 2, A_i, 0.0}, {1, 1, 2, 2, A_i, 0.0}};
  const auto field = joint::predict_load(flat, P, patches, amplitudes(), {}, 0.0);
  const auto cm = c.combined_roughness();
  const auto one = surface::RoughFlat::from_dimensional(c.halves[0].material, c.halves[1].material,
                                                        cm.sigma(), cm.eta(), cm.R(), A_i, c.model);
  const auto ref = joint::predict_load(one, P, amplitudes());
  ASSERT_EQ(field.patches.size(), 1u);  // the unloaded patches are out of contact
  // 1e-12: the same P* (P/(K H A0 w) against P/(K H A_i)) to rounding.
  EXPECT_LT(rel(field.mu, ref.mu), 1e-12);
  EXPECT_LT(rel(field.stiffness, ref.stiffness), 1e-12);
  for (std::size_t i = 0; i < ref.amplitudes.size(); ++i) {
    EXPECT_LT(rel(field.amplitudes[i].Q_peak, ref.amplitudes[i].Q_peak), 1e-12);
    EXPECT_LT(rel(field.amplitudes[i].energy, ref.amplitudes[i].energy), 1e-12);
  }
}

// Low-pressure patches slip first: a patch in gross slip at some amplitude means every
// patch at a lower pressure is too, and the slipping share grows with the amplitude.
TEST(InterfacePatches, SlipMapLowPressureFirst) {
  const auto c = bolted_case();
  const auto flat = c.rough_flat();
  const double P = c.preloads[1];
  std::vector<double> amps;
  for (double a = 2.5e-6; a < 4.5e-6; a += 0.1e-6) amps.push_back(a);
  const auto lp = joint::predict_load(flat, P, joint::case_patches(c, P), amps, {}, 0.0);
  double previous = 0.0;
  bool some_partial = false, some_gross = false;
  for (const auto& a : lp.amplitudes) {
    EXPECT_GE(a.gross_slip_area_fraction, previous);
    previous = a.gross_slip_area_fraction;
    for (std::size_t i = 0; i < lp.patches.size(); ++i) {
      some_partial |= a.patch_gross_slip[i] == 0;
      some_gross |= a.patch_gross_slip[i] == 1;
      if (!a.patch_gross_slip[i]) continue;
      for (std::size_t k = 0; k < lp.patches.size(); ++k) {
        if (lp.patches[k].patch.pressure() < lp.patches[i].patch.pressure()) {
          EXPECT_EQ(a.patch_gross_slip[k], 1) << k << " slips later than " << i;
        }
      }
    }
    EXPECT_EQ(a.regime == "gross slip", a.gross_slip_area_fraction == 1.0);
  }
  EXPECT_TRUE(some_partial && some_gross);  // the sweep crosses the slip front
}

// At small amplitude the energy-force exponent tends to 3 (Masing on a backbone whose
// first departure from linear is quadratic, as Mindlin's sphere): 3.007 at 1 nm is in
// docs/joints.md for the uniform joint; with the bolt field too.
TEST(InterfacePatches, EnergyExponentTendsToThreeAtSmallAmplitude) {
  const auto c = bolted_case();
  const auto flat = c.rough_flat();
  const double P = c.preloads[2];
  const auto uniform = joint::predict_load(flat, P, {1e-9, 0.25e-6}, {}, 0.0);
  const auto field =
      joint::predict_load(flat, P, joint::case_patches(c, P), {1e-9, 0.25e-6}, {}, 0.0);
  for (const auto* lp : {&uniform, &field}) {
    ASSERT_TRUE(lp->amplitudes[0].exponent.has_value());
    EXPECT_GT(*lp->amplitudes[0].exponent, 3.0);
    EXPECT_LT(*lp->amplitudes[0].exponent, 3.02);
    EXPECT_GT(*lp->amplitudes[1].exponent, *lp->amplitudes[0].exponent);
  }
}

// The halves in series: 1/k = 1/k_interface + C with C = sum L/(E w t) (a bar), and the
// energy per cycle at a given peak force is the interface's (a linear spring dissipates
// nothing): W_series(delta_i + C Q) = W_interface(delta_i). The two tables differ by their
// verified bounds (~1e-9), and W = 8 Int Q - 4 x Q loses the digits of 8 x Q/W: 1e-7 of
// that covers both.
TEST(InterfacePatches, HalvesComplianceInSeries) {
  auto c = bolted_case();
  const joint::HalvesGeometry g{{5e-3, 8e-3}, {5e-3, 4e-3}, 10e-3};
  const double C = joint::halves_compliance({200e9, 200e9}, g);
  EXPECT_LT(rel(C, 5e-3 / (200e9 * 10e-3 * 5e-3) + 8e-3 / (200e9 * 10e-3 * 4e-3)), 1e-15);
  const auto flat = c.rough_flat();
  const double P = c.preloads[2];
  const auto patches = joint::case_patches(c, P);
  const auto alone = joint::predict_load(flat, P, patches, {}, {}, 0.0);
  std::vector<double> total;
  for (double a : kAmplitudes) total.push_back(a + C * alone.backbone->force(a));
  const auto interface = joint::predict_load(flat, P, patches, amplitudes(), {}, 0.0);
  const auto series = joint::predict_load(flat, P, patches, total, {}, 0.0, C);
  EXPECT_LT(rel(1.0 / series.stiffness, 1.0 / alone.stiffness + C), 1e-12);
  EXPECT_LT(rel(series.interface_stiffness, alone.stiffness), 1e-12);
  EXPECT_EQ(series.Q_max, alone.Q_max);
  EXPECT_LT(rel(series.gross_slip_amplitude, alone.gross_slip_amplitude + C * alone.Q_max), 1e-9);
  for (std::size_t i = 0; i < total.size(); ++i) {
    const auto &s = series.amplitudes[i], &a = interface.amplitudes[i];
    EXPECT_LT(rel(s.Q_peak, a.Q_peak), 1e-8) << i;
    EXPECT_LT(rel(s.energy, a.energy), 1e-7 * 8.0 * a.delta_max * a.Q_peak / a.energy) << i;
  }
  // Through a case file: [interface.halves].
  c.interface.halves = g;
  const auto lp = joint::predict_case_load(c, P);
  EXPECT_LT(rel(lp.stiffness, series.stiffness), 1e-12);
}

// --- case files and bad input ---

std::string case_text(const std::string& interface) {
  return R"(
[joint]
area = "170 mm^2"
[[joint.half]]
material  = { E = "200 GPa", nu = 0.24, G = "80.7 GPa", H = "5.8 GPa" }
roughness = { sigma = "1.763 um", eta = "3.34e-4 um^-2", R = "40.76 um" }
[[joint.half]]
material  = { E = "200 GPa", nu = 0.24, G = "80.7 GPa", H = "5.8 GPa" }
roughness = { sigma = "2.015 um", eta = "2.51e-4 um^-2", R = "44.77 um" }
)" + interface;
}

const char* kBolted = R"(
[load]
bolts = { count = 2, total_torque = "2.7 lbf*in", nut_factor = 0.2, diameter = "2.9 mm" }
[interface]
pressure = "bolted"
size = ["17 mm", "10 mm"]
patches = [17, 10]
[interface.bolts]
positions = [["4.25 mm", "5 mm"], ["12.75 mm", "5 mm"]]
head_diameter = "5.5 mm"
hole_diameter = "3.4 mm"
thickness = ["5 mm", "5 mm"]
)";

TEST(InterfaceCase, BoltedCaseFileEqualsTheBuiltInField) {
  const auto c = joint::parse_case(case_text(kBolted));
  ASSERT_EQ(c.preloads.size(), 1u);
  const auto ref = bolted_case();
  const auto a = joint::case_patches(c, c.preloads[0]);
  const auto b = joint::case_patches(ref, c.preloads[0]);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].force, b[i].force);
}

// `asperity vibration` with a [joint] and an [interface]: its rough_flat element is the
// summed backbone of predict (the same Q_max and stiffness).
TEST(InterfaceCase, VibrationUsesTheSummedBackbone) {
  const std::string text = case_text(kBolted) + R"(
[structure]
mass = [[1.0]]
stiffness = [[1e8]]
[[element]]
type = "rough_flat"
backbone = "joint"
T = [[1.0]]
[quasi_static_mode]
mode = 1
amplitude = { from = 1e-9, to = 1e-6 }
points = 3
)";
  const auto vc = vibration::parse_case_text(text, "<vib>", ".");
  ASSERT_TRUE(vc.joint.has_value());
  double Q_max = 0.0, k_t = 0.0;
  for (const auto& [k, v] : *vc.joint) {
    if (k == "Q_max_N") Q_max = std::get<double>(v.data);
    if (k == "stiffness_N_per_m") k_t = std::get<double>(v.data);
  }
  const auto jc = joint::parse_case(case_text(kBolted));
  const auto lp = joint::predict_case_load(jc, jc.preloads[0]);
  EXPECT_EQ(Q_max, lp.Q_max);
  EXPECT_EQ(k_t, lp.stiffness);
}

// validate's "bolt field" rows use the geometry of the shipped example (the same forces).
TEST(InterfaceCase, ValidateBoltFieldIsTheShippedExample) {
  const auto file = joint::read_case_file(std::string(ASPERITY_TEST_DATA_DIR) +
                                          "/../../examples/joints/steel420_bolt_field.toml");
  const auto built_in = joint::with_assumed_bolt_field(joint::chapter5_joint());
  ASSERT_EQ(file.preloads.size(), built_in.preloads.size());
  for (std::size_t i = 0; i < file.preloads.size(); ++i) {
    EXPECT_LT(rel(file.preloads[i], built_in.preloads[i]), 1e-12);
    const auto a = joint::case_patches(file, file.preloads[i]);
    const auto b = joint::case_patches(built_in, file.preloads[i]);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_LT(std::abs(a[k].force - b[k].force), 1e-12 * file.preloads[i]);
      EXPECT_LT(std::abs(a[k].area - b[k].area), 1e-12 * file.area);
    }
  }
}

struct TempDir {
  fs::path path;
  explicit TempDir(const char* name) : path(fs::temp_directory_path() / name) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const char* name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

std::string map_case(const std::string& file, const char* extra = "") {
  return case_text(std::string("[load]\npreload = \"526 N\"\n[interface]\npressure = \"map\"\n") +
                   "size = [\"17 mm\", \"10 mm\"]\npatches = [4, 2]\nmap = \"" + file + "\"\n" +
                   extra);
}

// A grid map: bilinear, rescaled to the preload; used as given it is its own load case.
TEST(InterfaceCase, MapScaledToPreloadOrAsGiven) {
  const TempDir d("asperity_interface_map");
  std::string csv = "x[mm],y[mm],p[MPa]\n";
  for (double x : {0.0, 8.5, 17.0})
    for (double y : {0.0, 10.0}) csv += fmt::format("{},{},{}\n", x, y, 2.0 + x / 17.0);
  const auto f = d.write("map.csv", csv);
  const auto c = joint::parse_case(map_case(f));
  double F = 0.0;
  const auto patches = joint::case_patches(c, 526.0);
  for (const auto& p : patches) F += p.force;
  EXPECT_LT(rel(F, 526.0), 1e-12);
  EXPECT_GT(patches.back().pressure(), patches.front().pressure());  // p grows with x
  // Bilinear interpolation is exact on a linear field, indexed (as read) or not.
  joint::PressureMap raw;
  raw.x = c.interface.map.x;
  raw.y = c.interface.map.y;
  raw.p = c.interface.map.p;
  for (const auto& [x, y] : {std::pair{3e-3, 7e-3}, {11.2e-3, 0.4e-3}, {17e-3, 10e-3}}) {
    const double exact = (2.0 + x / 17e-3) * 1e6;
    EXPECT_LT(rel(c.interface.map.at(x, y), exact), 1e-12);
    EXPECT_LT(rel(raw.at(x, y), exact), 1e-12);
  }
  // As given: the integral of p = 2 + x/17 MPa over 17 x 10 mm^2 is 2.5 MPa * 170 mm^2.
  const auto g = joint::parse_case(case_text(std::string("[interface]\npressure = \"map\"\n") +
                                             "size = [\"17 mm\", \"10 mm\"]\npatches = [4, 2]\n"
                                             "map = \"" +
                                             f + "\"\nscale_to_preload = false\n"));
  ASSERT_EQ(g.preloads.size(), 1u);
  EXPECT_LT(rel(g.preloads[0], 2.5e6 * 170e-6), 1e-12);  // midpoint rule is exact on a linear p
}

TEST(InterfaceCase, BadInputNamesTheProblem) {
  const TempDir d("asperity_interface_bad");
  // A map that does not cover the interface (x up to 12 mm of 17).
  const auto small = d.write("small.csv", "x[mm],y[mm],p[MPa]\n0,0,1\n12,0,1\n0,10,1\n12,10,1\n");
  EXPECT_NE(invalid_input_message([&] {
              (void)joint::parse_case(map_case(small));
            }).find("does not cover the interface"),
            std::string::npos);
  // Negative pressure.
  const auto neg = d.write("neg.csv", "x[mm],y[mm],p[MPa]\n0,0,1\n17,0,-1\n0,10,1\n17,10,1\n");
  const auto m = invalid_input_message([&] { (void)joint::parse_case(map_case(neg)); });
  EXPECT_NE(m.find("data row 2: p = -1e+06 Pa"), std::string::npos) << m;
  EXPECT_NE(m.find("must be >= 0"), std::string::npos) << m;
  // A scattered map with an empty patch.
  const auto sparse = d.write("sparse.csv", "x[mm],y[mm],p[MPa]\n1,1,1\n16,9,1\n2,3,1\n");
  EXPECT_NE(invalid_input_message([&] {
              (void)joint::parse_case(map_case(sparse));
            }).find("does not cover the interface: no point in patch"),
            std::string::npos);
  // A bolt outside the outline.
  std::string out = kBolted;
  out.replace(out.find("[\"12.75 mm\", \"5 mm\"]"), 20, "[\"16.5 mm\", \"5 mm\"]");
  const auto b = invalid_input_message([&] { (void)joint::parse_case(case_text(out)); });
  EXPECT_NE(b.find("interface.bolts.positions[2] = (16.5, 5) mm"), std::string::npos) << b;
  EXPECT_NE(b.find("must lie inside the outline"), std::string::npos) << b;
  // Patches too small for the rough flat's statistics: 170 x 100 patches of 0.01 mm^2 hold
  // about 2.9 asperities each (eta = 2.9e-4 um^-2), fewer than 100.
  std::string fine = kBolted;
  fine.replace(fine.find("patches = [17, 10]"), 18, "patches = [170, 100]");
  const auto fc = joint::parse_case(case_text(fine));
  const auto msg = invalid_input_message([&] { (void)joint::predict(fc); });
  EXPECT_NE(msg.find("holds fewer than 100 asperities"), std::string::npos) << msg;
  // Bolt count against positions, unknown pressure kind, outline not the area.
  std::string three = kBolted;
  three.replace(three.find("count = 2"), 9, "count = 3");
  EXPECT_NE(invalid_input_message([&] {
              (void)joint::parse_case(case_text(three));
            }).find("2 positions given for load.bolts.count = 3"),
            std::string::npos);
  std::string kind = kBolted;
  kind.replace(kind.find("\"bolted\""), 8, "\"cones\"");
  EXPECT_NE(invalid_input_message([&] {
              (void)joint::parse_case(case_text(kind));
            }).find("interface.pressure = \"cones\""),
            std::string::npos);
  std::string size = kBolted;
  size.replace(size.find("\"10 mm\"]"), 7, "\"12 mm\"");
  EXPECT_NE(invalid_input_message([&] {
              (void)joint::parse_case(case_text(size));
            }).find("the outline must be the nominal area"),
            std::string::npos);
}

// `asperity dynamics` with a [joint] and an [interface]: its friction law is the summed
// backbone of predict (the same Q_max and reversal stiffness, to the last bit: the same
// computation).
TEST(InterfaceCase, DynamicsUsesTheSummedBackbone) {
  const std::string text = case_text(kBolted) + R"(
[dynamics]
excitation = "impulse"
epsilon = 0.032
stiffness = "1e7 N/m"
amplitude = "12 um"
duration = 5
[dynamics.impulse]
amplitude = 1
)";
  const auto dc = dynamics::parse_case_text(text, "<dyn>", ".");
  double Q_max = 0.0, k_t = 0.0;
  for (const auto& [k, v] : dc.friction_summary) {
    if (k == "Q_max_N") Q_max = std::get<double>(v.data);
    if (k == "k_t_N_per_m") k_t = std::get<double>(v.data);
  }
  const auto jc = joint::parse_case(case_text(kBolted));
  const auto lp = joint::predict_case_load(jc, jc.preloads[0]);
  ASSERT_GT(lp.patches.size(), 100u);
  EXPECT_EQ(Q_max, lp.Q_max);
  EXPECT_EQ(k_t, lp.stiffness);
  const auto uniform = joint::predict_load(jc.rough_flat(), jc.preloads[0], {});
  EXPECT_NE(Q_max, uniform.Q_max);  // not the uniform flat's
}

}  // namespace

namespace asperity {
namespace {

// interface.tangential = "odfalk_vingsbo" (thesis Eq. 3.10): refused without its measured
// parameters, saying why; with them, each amplitude row is Mindlin's (Masing on the same
// backbone) at the elastic amplitude plus the parallelogram's energy.
TEST(InterfaceCase, OdfalkVingsboNeedsItsMeasuredParametersAndAddsTheParallelogram) {
  const std::string load = R"(
[load]
preload = "526 N"
[excitation]
amplitudes = ["0.1 um", "1 um", "8 um"]
)";
  const auto missing = invalid_input_message([&] {
    (void)joint::parse_case(case_text(load + "[interface]\ntangential = \"odfalk_vingsbo\"\n"));
  });
  EXPECT_NE(missing.find("interface.fretting_yield_point: missing"), std::string::npos) << missing;
  EXPECT_NE(missing.find("obtained experimentally"), std::string::npos) << missing;
  const auto stray = invalid_input_message([&] {
    (void)joint::parse_case(case_text(load + "[interface]\nhardening_coefficient = \"5 N/um\"\n"));
  });
  EXPECT_NE(stray.find("used only with tangential = \"odfalk_vingsbo\""), std::string::npos)
      << stray;

  const double Q_ty = 20.0, k_p = 50e6;  // [N], [N/m]
  const auto ov =
      joint::parse_case(case_text(
          load + "[interface]\ntangential = \"odfalk_vingsbo\"\nfretting_yield_point = \"20 N\"\n"
                 "hardening_coefficient = \"50 N/um\"\n"));
  ASSERT_TRUE(ov.interface.odfalk_vingsbo);
  EXPECT_EQ(ov.interface.odfalk_vingsbo->fretting_yield_point, Q_ty);
  EXPECT_NEAR(ov.interface.odfalk_vingsbo->hardening_coefficient, k_p, 1e-12 * k_p);
  const auto mindlin = joint::parse_case(case_text(load));
  const auto p = joint::predict(ov).loads.front();
  const double P = mindlin.preloads.front();
  // The stiffness at reversals stays Mindlin's (thesis section 3.3, Fig. 3.3).
  EXPECT_EQ(p.stiffness, joint::predict_case_load(mindlin, P).stiffness);
  ASSERT_EQ(p.amplitudes.size(), 3u);
  for (const auto& a : p.amplitudes) {
    SCOPED_TRACE(a.delta_max);
    ASSERT_GT(a.Q_peak, Q_ty);  // every row yields here
    const double x_e = a.delta_max - (a.Q_peak - Q_ty) / (2.0 * k_p);
    const auto m = joint::predict_case_load(mindlin, P, {x_e}).amplitudes.front();
    // The same table on both sides: 1e-9 covers the root's and the quadrature's rounding.
    EXPECT_NEAR(m.Q_peak, a.Q_peak, 1e-9 * a.Q_peak);
    const double W = m.energy + (a.Q_peak * a.Q_peak - Q_ty * Q_ty) / k_p;
    EXPECT_NEAR(a.energy, W, 1e-9 * W);
    EXPECT_EQ(a.regime, x_e >= p.gross_slip_amplitude ? "gross slip" : "partial slip");
  }
  EXPECT_EQ(p.amplitudes.back().regime, "gross slip");  // 8 um: 6.5 um elastic, beyond 3.4 um
  // Its steady loop closes at (delta_max, Q_peak) and is symmetric.
  const auto [x, Q] = joint::steady_loop(p, 1e-6, 200);
  EXPECT_NEAR(Q.front(), p.amplitudes[1].Q_peak, 1e-12 * Q.front());
  EXPECT_NEAR(Q[200], -Q.front(), 1e-12 * Q.front());
  EXPECT_NEAR(Q.back(), Q.front(), 1e-12 * Q.front());
}

}  // namespace
}  // namespace asperity
