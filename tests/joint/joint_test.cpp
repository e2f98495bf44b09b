// Joint layer (thesis ch. 5-6): Eq. 5.2 against Tables 5.2, 5.5 and 6.3; case files;
// predictions against the ch. 5 BKE friction coefficients and the rough-flat layer;
// fretting analysis on synthetic experiments with a known answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "asperity/core/error.hpp"
#include "asperity/core/units.hpp"
#include "asperity/hysteresis/backbones.hpp"
#include "asperity/hysteresis/masing.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/fretting.hpp"
#include "asperity/joint/output_dir.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"

namespace asperity::joint {
namespace {

const std::string kExamples = std::string(ASPERITY_TEST_DATA_DIR) + "/../../examples/joints/";

double rel(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}
double lbf_in(double v) {
  return core::parse_quantity(std::to_string(v) + " lbf*in", core::dim::energy, "T");
}

// ---------------------------------------------------------------- Eq. 5.2 tables
TEST(TorquePreload, Table52SingleBoltNo4UNF) {
  // Table 5.2: #4-48 UNF bolt, D = 2.845 mm, k = 0.2 (section 5.2); torques in lb-in,
  // preloads printed to 3 digits (99, 298, 993 N): 0.5 % covers the rounding.
  const double D = 2.845e-3;
  EXPECT_LT(rel(bolt_preload(lbf_in(0.5), 0.2, D), 99.0), 5e-3);
  EXPECT_LT(rel(bolt_preload(lbf_in(1.5), 0.2, D), 298.0), 5e-3);
  EXPECT_LT(rel(bolt_preload(lbf_in(5.0), 0.2, D), 993.0), 5e-3);
}

TEST(TorquePreload, Table55TotalTorqueOfTwoM3Bolts) {
  // Table 5.5: total torque on the two M3 bolts 1.2/1.7/2.7/3.7 lb-in -> 234/331/526/721 N
  // and p_mean = 1.4/2/3.2/4.4 MPa. D = 2.9 mm, k = 0.2. The printed p_mean follow from
  // A0 = 165 mm^2 (the chapter 6 joints), not the 170 mm^2 of the chapter 5 joint
  // (which gives 1.38/1.95/3.09/4.24): a slip in the thesis, see docs/joints.md.
  const double P[] = {234, 331, 526, 721}, T[] = {1.2, 1.7, 2.7, 3.7}, p[] = {1.4, 2.0, 3.2, 4.4};
  for (int i = 0; i < 4; ++i) {
    const Bolts b{.count = 2, .nut_factor = 0.2, .diameter = 2.9e-3, .torques = {}};
    const double F = b.preload(lbf_in(T[i]) / 2.0);
    EXPECT_LT(rel(F, P[i]), 2.5e-3) << T[i];            // 3 printed digits
    EXPECT_NEAR(F / 165e-6 / 1e6, p[i], 0.05) << T[i];  // 2 printed digits
  }
}

TEST(TorquePreload, Table63AndTheShippedCh6Examples) {
  // Table 6.3: total bolt torque 0.192/0.305/0.418 N m -> 331/526/721 N, p_mean 2/3.2/4.4 MPa
  // on A0 = 165 mm^2 (section 6.2).
  const double P[] = {331, 526, 721};
  for (const char* f : {"aluminium_smooth", "aluminium_rough", "steel_smooth", "steel_rough"}) {
    const auto c = read_case_file(kExamples + f + ".toml");
    ASSERT_EQ(c.preloads.size(), 3U) << f;
    for (int i = 0; i < 3; ++i) EXPECT_LT(rel(c.preloads[i], P[i]), 2.5e-3) << f << " " << i;
    EXPECT_NEAR(c.preloads[1] / c.area / 1e6, 3.2, 0.05);
  }
}

void expect_same_case(const JointCase& a, const JointCase& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_DOUBLE_EQ(a.area, b.area);
  EXPECT_EQ(a.model, b.model);
  for (int h = 0; h < 2; ++h) {
    const auto &ma = a.halves[h].material, &mb = b.halves[h].material;
    EXPECT_LT(rel(ma.E, mb.E), 1e-15);
    EXPECT_EQ(ma.nu, mb.nu);
    EXPECT_LT(rel(ma.G, mb.G), 1e-15);
    EXPECT_LT(rel(ma.H, mb.H), 1e-15);
    const auto &ra = a.halves[h].roughness.moments, &rb = b.halves[h].roughness.moments;
    EXPECT_LT(rel(ra.m0, rb.m0), 1e-12);
    EXPECT_LT(rel(ra.m2, rb.m2), 1e-12);
    EXPECT_LT(rel(ra.m4, rb.m4), 1e-12);
  }
  ASSERT_EQ(a.preloads.size(), b.preloads.size());
  for (std::size_t i = 0; i < a.preloads.size(); ++i)
    EXPECT_LT(rel(a.preloads[i], b.preloads[i]), 1e-12);
  ASSERT_EQ(a.amplitudes.size(), b.amplitudes.size());
  for (std::size_t i = 0; i < a.amplitudes.size(); ++i)
    EXPECT_LT(rel(a.amplitudes[i], b.amplitudes[i]), 1e-12);
  ASSERT_EQ(a.imposed.size(), b.imposed.size());
  for (std::size_t i = 0; i < a.imposed.size(); ++i)
    EXPECT_LT(rel(a.imposed[i], b.imposed[i]), 1e-12);
  EXPECT_DOUBLE_EQ(a.apparatus.compliance(), b.apparatus.compliance());
}

TEST(TorquePreload, ValidateUsesTheShippedExamples) {
  // asperity validate builds the thesis's joints in (it must run without the source tree);
  // they must equal the shipped example files, so neither drifts.
  expect_same_case(chapter5_joint(), read_case_file(kExamples + "steel420_two_bolts.toml"));
  const char* files[] = {"aluminium_smooth", "aluminium_rough", "steel_smooth", "steel_rough"};
  const auto ch6 = chapter6_joints();
  ASSERT_EQ(ch6.size(), 4U);
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(files[i]);
    expect_same_case(ch6[i], read_case_file(kExamples + files[i] + ".toml"));
  }
}

TEST(TorquePreload, RejectsNonPositiveInputs) {
  EXPECT_THROW((void)bolt_preload(-0.1, 0.2, 3e-3), InvalidInput);
  EXPECT_THROW((void)bolt_preload(0.1, 0.0, 3e-3), InvalidInput);
  EXPECT_THROW((void)bolt_preload(0.1, 0.2, 0.0), InvalidInput);
}

// ---------------------------------------------------------------- case files
const char* kCase = R"(
[joint]
name = "test"
area = "170 mm^2"
model = "bke"
[[joint.half]]
material  = { E = "200 GPa", nu = 0.24, G = "80.7 GPa", H = "5.8 GPa" }
roughness = { sigma = "1.763 um", eta = "3.34e-4 um^-2", R = "40.76 um" }
[[joint.half]]
material  = { E = "200 GPa", nu = 0.24, G = "80.7 GPa", H = "5.8 GPa" }
roughness = { sigma = "2.015 um", eta = "2.51e-4 um^-2", R = "44.77 um" }
[load]
preload = "526 N"
[excitation]
amplitudes = ["1 um", "0.25 um"]
)";

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_case(text, "case.toml");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(JointCase, ParsesQuantitiesWithUnits) {
  const auto c = parse_case(kCase, "case.toml");
  EXPECT_DOUBLE_EQ(c.area, 170e-6);
  ASSERT_EQ(c.preloads.size(), 1U);
  EXPECT_DOUBLE_EQ(c.preloads[0], 526.0);
  ASSERT_EQ(c.amplitudes.size(), 2U);
  EXPECT_DOUBLE_EQ(c.amplitudes[0], 0.25e-6);  // sorted
  EXPECT_NEAR(c.halves[0].material.E, 200e9, 1e-3);
  // Table 5.4: the halves combine to 2.677 um / 2.91e-4 um^-2 / 30.14 um (printed digits).
  const auto m = c.combined_roughness();
  EXPECT_LT(rel(m.sigma(), 2.677e-6), 5e-4);
  EXPECT_LT(rel(m.eta(), 2.91e8), 2.5e-3);
  EXPECT_LT(rel(m.R(), 30.14e-6), 5e-4);
}

TEST(JointCase, UnknownKeyNamesKeyAndLine) {
  const auto e = error_of(replaced(kCase, "model = \"bke\"", "modle = \"bke\""));
  EXPECT_NE(e.find("case.toml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("joint.modle"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
  const auto e2 = error_of(replaced(kCase, "nu = 0.24, G", "nu = 0.24, Gx = \"1 GPa\", G"));
  EXPECT_NE(e2.find("case.toml:7:"), std::string::npos) << e2;
  EXPECT_NE(e2.find("joint.half[1].material.Gx"), std::string::npos) << e2;
}

TEST(JointCase, WrongUnitsMissingHalvesAndBadLoads) {
  auto e = error_of(replaced(kCase, "\"170 mm^2\"", "\"3 N\""));
  EXPECT_NE(e.find("case.toml:4: joint.area"), std::string::npos) << e;
  EXPECT_NE(e.find("area"), std::string::npos) << e;
  e = error_of(replaced(kCase, "area = \"170 mm^2\"", "area = 170"));
  EXPECT_NE(e.find("joint.area"), std::string::npos) << e;
  // One half only.
  const auto first = std::string(kCase).find("[[joint.half]]");
  const auto second = std::string(kCase).find("[[joint.half]]", first + 1);
  const auto load = std::string(kCase).find("[load]");
  std::string one = std::string(kCase).erase(second, load - second);
  e = error_of(one);
  EXPECT_NE(e.find("joint.half"), std::string::npos) << e;
  EXPECT_NE(e.find("two"), std::string::npos) << e;
  e = error_of(replaced(
      kCase, "preload = \"526 N\"",
      "bolts = { count = 2, torque = \"-0.1 N*m\", nut_factor = 0.2, diameter = \"2.9 mm\" }"));
  // The value as typed, no SI conversion and no stray colon.
  EXPECT_NE(e.find("case.toml:13: load.bolts.torque = \"-0.1 N*m\": must be > 0"),
            std::string::npos)
      << e;
  e = error_of(replaced(kCase, "preload = \"526 N\"", "preload = \"526 N\"\npreloads = [\"1 N\"]"));
  EXPECT_NE(e.find("exactly one"), std::string::npos) << e;
  e = error_of(replaced(kCase, "[load]\npreload = \"526 N\"\n", ""));
  EXPECT_NE(e.find("load"), std::string::npos) << e;
  e = error_of(replaced(kCase, "model = \"bke\"", "model = \"xyz\""));
  EXPECT_NE(e.find("joint.model"), std::string::npos) << e;
  e = error_of(replaced(kCase, "[excitation]", "[excitation"));
  EXPECT_NE(e.find("case.toml:14: TOML syntax error"), std::string::npos) << e;
  e = error_of(replaced(kCase, "\"0.25 um\"", "\"-0.25 um\""));
  EXPECT_NE(e.find("case.toml:15: excitation.amplitudes[2] = \"-0.25 um\": must be > 0"),
            std::string::npos)
      << e;
}

TEST(JointCase, MessagesNameTheKeyAndEchoTheValue) {
  // Dimensionless values are bare numbers: a string is an error naming the key.
  auto e = error_of(replaced(kCase,
                             "nu = 0.24, G = \"80.7 GPa\", H = \"5.8 GPa\" }\nroughness = "
                             "{ sigma = \"1.763 um\"",
                             "nu = \"0.24\", G = \"80.7 GPa\", H = \"5.8 GPa\" }\nroughness = { "
                             "sigma = \"1.763 um\""));
  EXPECT_NE(e.find("case.toml:7: joint.half[1].material.nu = \"0.24\": a dimensionless value is "
                   "a bare number"),
            std::string::npos)
      << e;
  // A unit on a dimensionless value: the advice drops the unit (not "write nu = 0.24 GPa").
  e = error_of(replaced(kCase, "nu = 0.24, G", "nu = \"0.24 GPa\", G"));
  EXPECT_NE(e.find("joint.half[1].material.nu = \"0.24 GPa\": nu is dimensionless and takes "
                   "no unit: write nu = 0.24 (no quotes, no \"GPa\")"),
            std::string::npos)
      << e;
  e = error_of(replaced(kCase, "nu = 0.24, G", "nu = \"abc\", G"));
  EXPECT_NE(e.find("nu is dimensionless: write a bare number"), std::string::npos) << e;
  // Grammar of the half count.
  const std::string k(kCase);
  const auto second = k.find("[[joint.half]]", k.find("[[joint.half]]") + 1);
  e = error_of(k.substr(0, second) + k.substr(k.find("[load]")));
  EXPECT_NE(e.find("found 1 [[joint.half]] table; a joint has two"), std::string::npos) << e;
  const auto half = k.substr(second, k.find("[load]") - second);
  e = error_of(k.substr(0, k.find("[load]")) + half + k.substr(k.find("[load]")));
  EXPECT_NE(e.find("found 3 [[joint.half]] tables"), std::string::npos) << e;
  // [excitation] must say something.
  e = error_of(replaced(kCase, "amplitudes = [\"1 um\", \"0.25 um\"]", ""));
  EXPECT_NE(e.find("case.toml:14: excitation: give amplitudes"), std::string::npos) << e;
  // The apparatus only with imposed amplitudes; its stiffness needs units of N/m.
  e = error_of(std::string(kCase) + "apparatus = { pzt_stiffness = \"38 N/um\" }\n");
  EXPECT_NE(e.find("excitation.apparatus: is used only with imposed"), std::string::npos) << e;
  e = error_of(std::string(kCase) +
               "imposed = [\"6.75 um\"]\napparatus = { pzt_stiffness = \"38 N\" }\n");
  EXPECT_NE(e.find("case.toml:17: excitation.apparatus.pzt_stiffness"), std::string::npos) << e;
}

TEST(JointCase, ErrorsFoundLaterNameTheFileLineAndKey) {
  // A preload beyond the model's range is found by predict, after parsing.
  auto c = parse_case(replaced(kCase, "preload = \"526 N\"", "preloads = [\"526 N\", \"5e6 N\"]"),
                      "case.toml");
  try {
    (void)predict(c);
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("case.toml:13: load.preloads[2] = \"5e6 N\": preload = 5e+06 N is beyond", 0),
              0U)
        << m;
  }
  // beta = sigma R eta of the combination too small for Eq. 4.2: names the halves' roughness.
  c = parse_case(replaced(replaced(kCase, "R = \"40.76 um\"", "R = \"4 um\""), "R = \"44.77 um\"",
                          "R = \"4 um\""),
                 "case.toml");
  try {
    (void)predict(c);
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("case.toml:6: joint.half[1-2].roughness (combined", 0), 0U) << m;
    EXPECT_NE(m.find("beta"), std::string::npos) << m;
  }
}

TEST(JointCase, ImposedAmplitudesThroughTheApparatus) {
  const auto c = parse_case(std::string(kCase) +
                                "imposed = [\"6.75 um\", \"2 um\"]\n"
                                "apparatus = { pzt_stiffness = \"40 N/um\" }\n",
                            "case.toml");
  ASSERT_EQ(c.imposed.size(), 2U);
  EXPECT_DOUBLE_EQ(c.imposed[0], 2e-6);  // sorted
  EXPECT_DOUBLE_EQ(c.apparatus.pzt_stiffness, 40e6);
  EXPECT_DOUBLE_EQ(c.apparatus.load_cell_stiffness, 1462e6);  // default (section 5.2)
  const auto p = predict(c);
  const auto& l = p.loads.front();
  ASSERT_EQ(l.amplitudes.size(), 4U);  // two given, two imposed, sorted by delta_max
  for (std::size_t i = 1; i < l.amplitudes.size(); ++i)
    EXPECT_LE(l.amplitudes[i - 1].delta_max, l.amplitudes[i].delta_max);
  const double comp = 1.0 / 40e6 + 1.0 / 1462e6;
  std::size_t given = 0;
  for (const auto& a : l.amplitudes) {
    if (!a.imposed) {  // given directly: no PZT amplitude (not a 0 that reads as one)
      ++given;
      continue;
    }
    // Fig. 5.7: the springs in series, delta + c Q_l(delta) = imposed (root to 50 bits).
    EXPECT_LT(rel(a.delta_max + comp * a.Q_peak, *a.imposed), 1e-12);
  }
  EXPECT_EQ(given, 2U);
}

TEST(JointCase, TorqueSweepAndPerBoltTorque) {
  const auto c =
      parse_case(replaced(kCase, "preload = \"526 N\"",
                          "bolts = { count = 2, torques = [\"0.1525 N*m\", \"0.209 N*m\"], "
                          "diameter = \"2.9 mm\" }"),
                 "case.toml");
  ASSERT_EQ(c.preloads.size(), 2U);
  EXPECT_LT(rel(c.preloads[0], 526.0), 1e-3);  // 2 x 0.1525/(0.2 x 2.9 mm)
  EXPECT_LT(rel(c.preloads[1], 720.7), 1e-3);
}

TEST(JointCase, ProfilesGiveTable54) {
  // examples/joints/steel420_profiles.toml reads the scans of examples/roughness, made to
  // reproduce Table 5.4 (docs/roughness.md): combined 2.677 um / 2.91e-4 um^-2 / 30.14 um.
  const auto c = read_case_file(kExamples + "steel420_profiles.toml");
  const auto m = c.combined_roughness();
  EXPECT_LT(rel(m.sigma(), 2.677e-6), 1e-3);
  EXPECT_LT(rel(m.eta(), 2.91e8), 3e-3);
  EXPECT_LT(rel(m.R(), 30.14e-6), 1e-3);
  EXPECT_EQ(c.halves[0].roughness.directions.size(), 2U);
  EXPECT_LT(rel(c.preloads[0], 526.0), 1e-3);
}

TEST(JointCase, ProfileSettingsAreThoseOfTheRoughnessCommand) {
  // [profiles] takes the settings of `asperity roughness` (--end, --truncation, --dx too),
  // and its errors suggest those keys, not the command's flags.
  namespace fs = std::filesystem;
  const auto c = parse_case(std::string(kCase) +
                                "[profiles]\nend = \"regression\"\ntruncation = 2\ndx = "
                                "\"0.5 um\"\nlevel = \"mean\"\nrule = \"arithmetic\"\n",
                            "case.toml");
  EXPECT_EQ(c.profile_settings.filter.end, surface::EndEffects::regression);
  EXPECT_DOUBLE_EQ(c.profile_settings.filter.truncation, 2.0);
  ASSERT_TRUE(c.profile_settings.dx.has_value());
  EXPECT_DOUBLE_EQ(*c.profile_settings.dx, 0.5e-6);
  EXPECT_EQ(c.profile_settings.level, surface::Levelling::mean);
  EXPECT_EQ(c.profile_settings.rule, surface::IsotropicRule::arithmetic);
  auto e = error_of(std::string(kCase) + "[profiles]\ntruncation = 5\n");
  EXPECT_NE(e.find("truncation"), std::string::npos) << e;
  e = error_of(std::string(kCase) + "[profiles]\ndx = \"-1 um\"\n");
  EXPECT_NE(e.find("profiles.dx = \"-1 um\": must be > 0"), std::string::npos) << e;
  // A scan shorter than the default filter (lc = 0.8 mm discards 0.8 mm at each end):
  // 1.2 mm of the shipped 4 mm scan.
  const auto dir = fs::temp_directory_path() / "asperity_joint_short_scan";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    std::ifstream in(kExamples + "../roughness/pzt_max.csv");
    std::ofstream out(dir / "short.csv");
    std::string line;
    for (int i = 0; i < 1200 && std::getline(in, line); ++i) out << line << "\n";
  }
  const std::string scans = "profiles = [\"short.csv\"]";
  const auto text = replaced(kCase,
                             "roughness = { sigma = \"1.763 um\", eta = \"3.34e-4 um^-2\", R = "
                             "\"40.76 um\" }",
                             scans);
  try {
    (void)parse_case(text, "case.toml", dir.string());
    FAIL() << "a scan shorter than the filter was accepted";
  } catch (const InvalidInput& ex) {
    const std::string m = ex.what();
    EXPECT_NE(m.find("end = \"regression\" in [profiles]"), std::string::npos) << m;
    EXPECT_EQ(m.find("--"), std::string::npos) << m;  // no command-line flag
  }
  const auto ok =
      parse_case(text + "[profiles]\nend = \"regression\"\n", "case.toml", dir.string());
  EXPECT_GT(ok.halves[0].roughness.moments.sigma(), 0.0);
  EXPECT_EQ(ok.halves[0].roughness.profiles.size(), 1U);
  fs::remove_all(dir);
}

TEST(JointCase, ProcessingPerHalf) {
  // Issue 22: the two halves are often measured differently. A half's `processing` table
  // overrides the keys of [profiles] it names, for that half only. Reference: the same
  // scans with the setting given case-wide (the same function on the same settings: equal).
  std::ifstream in(kExamples + "steel420_profiles.toml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string half2 = "profiles = [\"../roughness/lc_max.csv\", \"../roughness/lc_min.csv\"]";
  ASSERT_NE(text.find(half2), std::string::npos);
  const auto base = parse_case(text, "case.toml", kExamples);
  const auto per_half = parse_case(
      replaced(text, half2, half2 + "\nprocessing = { lc = \"0.25 mm\" }"), "case.toml", kExamples);
  const auto all =
      parse_case(replaced(text, "lc = \"0.8 mm\"", "lc = \"0.25 mm\""), "case.toml", kExamples);
  EXPECT_EQ(per_half.halves[0].roughness.moments.m0, base.halves[0].roughness.moments.m0);
  EXPECT_EQ(per_half.halves[0].roughness.moments.m2, base.halves[0].roughness.moments.m2);
  EXPECT_EQ(per_half.halves[1].roughness.moments.m0, all.halves[1].roughness.moments.m0);
  EXPECT_EQ(per_half.halves[1].roughness.moments.m4, all.halves[1].roughness.moments.m4);
  // A shorter long-wave cut-off removes waviness: sigma falls.
  EXPECT_LT(per_half.halves[1].roughness.moments.sigma(), base.halves[1].roughness.moments.sigma());
  EXPECT_DOUBLE_EQ(per_half.halves[1].profile_settings.filter.lc, 0.25e-3);
  EXPECT_EQ(per_half.halves[1].profile_settings.filter.ls,
            base.profile_settings.filter.ls);  // from [profiles]
  EXPECT_DOUBLE_EQ(per_half.halves[0].profile_settings.filter.lc, 0.8e-3);
  // Refused: on a half given as parameters, and an unknown key, naming the half.
  auto e =
      error_of(replaced(kCase, "roughness = { sigma = \"1.763 um\"",
                        "processing = { lc = \"0.25 mm\" }\nroughness = { sigma = \"1.763 um\""));
  EXPECT_NE(e.find("joint.half[1].processing: is used only with profiles"), std::string::npos) << e;
  try {
    (void)parse_case(replaced(text, half2, half2 + "\nprocessing = { lcc = \"0.25 mm\" }"),
                     "case.toml", kExamples);
    FAIL() << "an unknown key was accepted";
  } catch (const InvalidInput& ex) {
    EXPECT_NE(std::string(ex.what()).find("joint.half[2].processing"), std::string::npos)
        << ex.what();
  }
}

// ---------------------------------------------------------------- predictions
TEST(JointPredict, Chapter5BkeFrictionCoefficientsWithinFivePercent) {
  // Section 5.3: BKE mu = 0.354, 0.334, 0.335, 0.347 at 234, 331, 526, 721 N.
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto p = predict(c);
  const double mu[] = {0.354, 0.334, 0.335, 0.347};
  ASSERT_EQ(p.loads.size(), 4U);
  for (int i = 0; i < 4; ++i) EXPECT_LT(rel(p.loads[i].mu, mu[i]), 0.05) << p.loads[i].preload;
  // psi of Table 5.4 (4.725) within 0.5 %.
  EXPECT_LT(rel(p.psi, 4.725), 5e-3);
}

TEST(JointPredict, EnergyEqualsTheRoughFlatLayerToRoundOff) {
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto flat = c.rough_flat();
  const auto p = predict(c);
  const auto& s = *flat.scales();
  for (const auto& l : p.loads) {
    const auto bb = flat.backbone(l.d_star);
    for (const auto& a : l.amplitudes) {
      const double x = a.delta_max / s.sigma;
      const double layer = hysteresis::energy_per_cycle(*bb, x) * s.force * s.sigma;
      EXPECT_LT(rel(a.energy, layer), 1e-13);
      // and the direct sum over asperities (Eq. 4.14) to the table's verified error
      EXPECT_LT(rel(a.energy, flat.energy_star(x, l.d_star) * s.force * s.sigma), 1e-7);
      EXPECT_LT(rel(a.Q_peak, flat.loading_force_star(x, l.d_star) * s.force), 1e-8);
    }
    EXPECT_LT(rel(l.stiffness, flat.stiffness_star(l.d_star) * s.force / s.sigma), 1e-14);
  }
}

TEST(JointPredict, SteadyLoopClosesThroughTheReversalPoints) {
  const auto c = parse_case(kCase, "case.toml");
  const auto p = predict(c);
  const auto& l = p.loads.front();
  const auto [x, Q] = steady_loop(*l.backbone, 1e-6, 50);
  EXPECT_DOUBLE_EQ(x.front(), 1e-6);
  EXPECT_NEAR(Q.front(), l.amplitudes.back().Q_peak, 1e-9);
  EXPECT_NEAR(Q[50], -l.amplitudes.back().Q_peak, 1e-9);
  EXPECT_NEAR(Q.back(), Q.front(), 1e-9);
}

TEST(JointOutput, StagedDirectoryLeavesNothingOnError) {
  const auto base = std::filesystem::temp_directory_path() / "asperity_joint_staged_test";
  std::filesystem::remove_all(base);
  std::filesystem::create_directories(base);
  const auto target = (base / "out").string();
  {
    StagedDirectory d(target);
    std::ofstream(d.file("a.txt")) << "x";
  }  // no commit: an error happened
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_TRUE(std::filesystem::is_empty(base));
  {  // missing parents are created, and removed again when nothing is committed
    StagedDirectory d((base / "a" / "b" / "out").string());
    EXPECT_TRUE(std::filesystem::is_directory(base / "a" / "b"));
  }
  EXPECT_TRUE(std::filesystem::is_empty(base));
  {
    StagedDirectory d(target);
    std::ofstream(d.file("a.txt")) << "y";
    d.commit();
  }
  EXPECT_TRUE(std::filesystem::exists(base / "out" / "a.txt"));
  EXPECT_TRUE(std::filesystem::exists(base / "out" / kOutputMarker));
  {  // an earlier asperity output (it has the marker) is replaced as a whole
    StagedDirectory d(target);
    std::ofstream(d.file("b.txt")) << "z";
    d.commit();
  }
  EXPECT_FALSE(std::filesystem::exists(base / "out" / "a.txt"));
  EXPECT_TRUE(std::filesystem::exists(base / "out" / "b.txt"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(base),
                          std::filesystem::directory_iterator{}),
            1);  // no temporary or old siblings left
  std::filesystem::remove_all(base);
}

TEST(JointOutput, StagedDirectoryNeverTouchesForeignFiles) {
  const auto base = std::filesystem::temp_directory_path() / "asperity_joint_foreign_test";
  std::filesystem::remove_all(base);
  std::filesystem::create_directories(base / "precious");
  std::ofstream(base / "precious" / "thesis.tex") << "years of work";
  try {
    StagedDirectory d((base / "precious").string());
    FAIL() << "a foreign directory was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("did not write"), std::string::npos) << e.what();
  }
  // Filled while the output was being staged: refused at commit, nothing lost.
  std::filesystem::create_directories(base / "late");
  {
    StagedDirectory d((base / "late").string());
    std::ofstream(d.file("a.txt")) << "x";
    std::ofstream(base / "late" / "notes.txt") << "mine";
    EXPECT_THROW(d.commit(), InvalidInput);
  }
  EXPECT_TRUE(std::filesystem::exists(base / "precious" / "thesis.tex"));
  EXPECT_TRUE(std::filesystem::exists(base / "late" / "notes.txt"));
  EXPECT_FALSE(std::filesystem::exists(base / "late" / "a.txt"));
  // An empty directory is taken; a file is refused.
  std::filesystem::create_directories(base / "empty");
  {
    StagedDirectory d((base / "empty").string());
    d.commit();
  }
  EXPECT_TRUE(std::filesystem::exists(base / "empty" / kOutputMarker));
  std::ofstream(base / "file") << "x";
  EXPECT_THROW(StagedDirectory((base / "file").string()), InvalidInput);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(base),
                          std::filesystem::directory_iterator{}),
            4);  // precious, late, empty, file: no temporary siblings left
  std::filesystem::remove_all(base);
}

TEST(JointOutput, OutputDirectoryNeverIsOrHoldsAnInput) {
  namespace fs = std::filesystem;
  const auto base = fs::temp_directory_path() / "asperity_joint_inputs_test";
  fs::remove_all(base);
  fs::create_directories(base / "out" / "sub");
  std::ofstream(base / "case.toml") << "x";
  std::ofstream(base / "out" / "sub" / "data.csv") << "x";
  const auto b = base.string();
  const auto message = [](const std::string& dir, const std::vector<NamedInput>& in) {
    try {
      require_output_apart_from_inputs(dir, in);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // Equal (also through "." and ".."), and holding an input at any depth: refused,
  // naming the input.
  EXPECT_NE(
      message(b + "/case.toml", {{"the case file", b + "/case.toml"}}).find("names the case file"),
      std::string::npos);
  EXPECT_NE(message(b + "/out/../case.toml", {{"the case file", b + "/./case.toml"}})
                .find("names the case file"),
            std::string::npos);
  EXPECT_NE(message(b + "/out/", {{"the data file", b + "/out/sub/data.csv"}})
                .find("holds the data file"),
            std::string::npos);
  EXPECT_NE(message(b, {{"the data file", b + "/out/sub/data.csv"}}).find("holds"),
            std::string::npos);
  // Through a symbolic link to the output directory.
  fs::create_directory_symlink(base / "out", base / "link");
  EXPECT_NE(message(b + "/out", {{"the data file", b + "/link/sub/data.csv"}}).find("holds"),
            std::string::npos);
  // Siblings and a common text prefix ("out" and "out2/...") are not inside.
  EXPECT_EQ(message(b + "/out2", {{"the data file", b + "/out/sub/data.csv"}}), "");
  EXPECT_EQ(message(b + "/ou", {{"the data file", b + "/out/sub/data.csv"}}), "");
  EXPECT_EQ(message(b + "/out/sub/new", {{"the case file", b + "/case.toml"}}), "");
  fs::remove_all(base);
}

TEST(JointPredict, RegimeFromTheBackbone) {
  // Gross slip from the backbone table's end on (every asperity slips there: Q_l = Q_max
  // to < 1e-12); below it partial slip, Q_peak < Q_max.
  auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto p = predict(c);
  for (const auto& l : p.loads) {
    EXPECT_GT(l.gross_slip_amplitude, 0.0);
    for (const auto& a : l.amplitudes) {
      if (a.delta_max >= l.gross_slip_amplitude) {
        EXPECT_EQ(a.regime, "gross slip");
        EXPECT_NEAR(a.Q_ratio, 1.0, 1e-9);
      } else {
        EXPECT_EQ(a.regime, "partial slip");
        EXPECT_LT(a.Q_ratio, 1.0);
      }
    }
    EXPECT_EQ(l.amplitudes.front().regime, "partial slip");  // 0.05 um
    EXPECT_EQ(l.amplitudes.back().regime, "gross slip");     // 4 um
  }
}

TEST(JointPredict, ImposedAmplitudeMatchesTheSyntheticApparatus) {
  // The closed form delta + c Q_l(delta) = imposed (used by predict and validate's Table
  // 5.6) against the time-stepped synthetic experiment (Eq. 5.3, Fig. 5.7) at 20 kHz: the
  // joint's steady half peak-to-peak motion. The sampled extreme lies within
  // (pi f/rate)^2/2 = 1.2e-8 of the peak; 1e-5 covers the solver's tolerance.
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const Apparatus app{};
  for (double P : {234.0, 721.0}) {
    const auto lp = predict_load(c.rough_flat(), P, {}, {6.75e-6}, app.compliance());
    SyntheticOptions o;
    o.excitation.amplitude = 6.75e-6;
    o.excitation.cycles = 3;
    o.sample_rate = 20000.0;
    o.noise_delta = o.noise_Q = 0.0;
    const auto d = synthetic_experiment(lp.backbone, o);
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < d.t.size(); ++i) {
      if (d.t[i] >= 2.0 && d.t[i] < 3.0) {
        lo = std::min(lo, d.delta[i]);
        hi = std::max(hi, d.delta[i]);
      }
    }
    EXPECT_LT(rel(0.5 * (hi - lo), lp.amplitudes.front().delta_max), 1e-5) << P;
  }
}

// ---------------------------------------------------------------- analysis
struct Truth {
  double delta_amp, Q_amp, energy, stiffness;
};

// The answer for a synthetic run: the noise-free joint displacement amplitude of a
// steady cycle and the Masing values there.
Truth truth_of(const hysteresis::Backbone& bb, SyntheticOptions o) {
  o.noise_delta = 0.0;
  o.noise_Q = 0.0;
  const auto clean =
      synthetic_experiment(std::shared_ptr<const hysteresis::Backbone>(&bb, [](auto*) {}), o);
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < clean.t.size(); ++i) {
    if (clean.t[i] >= 2.0 && clean.t[i] < 3.0) {
      lo = std::min(lo, clean.delta[i]);
      hi = std::max(hi, clean.delta[i]);
    }
  }
  const double a = 0.5 * (hi - lo);
  return {a, bb.force(a), hysteresis::energy_per_cycle(bb, a), bb.initial_stiffness()};
}

class AnalyzeSynthetic : public ::testing::TestWithParam<std::tuple<double, int, bool>> {};

// The mean stiffness is 1/mean(1/k_i) over the cycles (fretting.hpp): with every cycle
// resolved it lies between the per-cycle values.
void expect_mean_consistent(const FrettingAnalysis& a) {
  double sumC = 0.0, lo = 1e300, hi = -1e300;
  bool all = true;
  for (const auto& c : a.cycles) {
    sumC += 1.0 / c.stiffness;
    lo = std::min(lo, c.stiffness);
    hi = std::max(hi, c.stiffness);
    all &= c.stiffness_resolved;
  }
  EXPECT_LT(rel(a.mean.stiffness, static_cast<double>(a.cycles.size()) / sumC), 1e-12);
  if (all) {
    EXPECT_GE(a.mean.stiffness, lo);
    EXPECT_LE(a.mean.stiffness, hi);
  }
}

TEST_P(AnalyzeSynthetic, RecoversEnergyStiffnessAndMu) {
  // Table 5.6's experiment: the PZT tip moves 6.75 um (half peak-to-peak, Eq. 5.3, 1 Hz,
  // 10 cycles); the apparatus of Fig. 5.7 (38 N/um PZT side, 1462 N/um load cell side);
  // noise 0.1 um on delta and 1 N on Q (section 5.2); 1 kHz sampling (section 5.3), the
  // DEFAULT analysis. The issue's tolerances: energy 2 %, mu 1 %, stiffness 5 %.
  // Stiffness at 1 kHz: 5 % is not reached run by run by any estimator we tried (docs/
  // joints.md); with Delta the default's error over 80 seeds is 4-8 % rms (largest at
  // 234 N, the smallest force swing), at most 12.8 %. Here: 15 % and within 3 reported
  // standard errors. Without Delta (delta(Q) alone) it scatters by 13-46 % rms: then a
  // warning is required and the standard error must still cover the error.
  const auto [P, seed, imposed] = GetParam();
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto lp = predict_load(c.rough_flat(), P, {});
  SyntheticOptions o;
  o.excitation.amplitude = 6.75e-6;
  o.seed = static_cast<std::uint64_t>(seed);
  auto data = synthetic_experiment(lp.backbone, o);
  if (!imposed) data.Delta.clear();
  const auto truth = truth_of(*lp.backbone, o);
  const auto a = analyze_fretting(data, P);
  EXPECT_EQ(a.cycles.size(), 9U);  // 10 harmonic periods: 9 maximum-to-maximum cycles
  EXPECT_LT(rel(a.mean.energy, truth.energy), 0.02) << a.mean.energy << " " << truth.energy;
  EXPECT_LT(rel(a.loop_energy, truth.energy), 0.02);
  EXPECT_TRUE(a.energy_resolved);
  EXPECT_LT(rel(a.mu, truth.Q_amp / P), 0.01) << a.mu << " " << truth.Q_amp / P;
  EXPECT_LT(rel(a.mean.delta_max, truth.delta_amp), 0.03);
  // The noise estimates (second differences) recover the synthetic noise: 5 % (the
  // signal's own second difference at 1 kHz is below 1e-3 of the noise).
  EXPECT_LT(rel(a.noise_delta, o.noise_delta), 0.05);
  EXPECT_LT(rel(a.noise_Q, o.noise_Q), 0.05);
  const double err = std::abs(a.mean.stiffness - truth.stiffness);
  EXPECT_LT(err, 3.0 * a.stiffness_standard_error)
      << a.mean.stiffness << " +- " << a.stiffness_standard_error << " vs " << truth.stiffness;
  if (imposed) {
    EXPECT_LT(err / truth.stiffness, 0.15) << a.mean.stiffness << " " << truth.stiffness;
  } else {
    EXPECT_TRUE(std::any_of(a.warnings.begin(), a.warnings.end(), [](const std::string& w) {
      return w.find("standard error") != std::string::npos;
    }));
  }
  expect_mean_consistent(a);
}

TEST(AnalyzeSyntheticDefault, StiffnessAt1kHzOverSeeds) {
  // The default path (Delta recorded, window 0.35, quadratic) on the thesis's 1 kHz
  // experiment at the four preloads of Table 5.5, seeds 1-6. Measured (docs/joints.md):
  // rms error 7.8/5.9/4.4/4.0 % at 234/331/526/721 N, mean -0.5..+1.7 %, all within
  // 12.8 %, 22 of 24 within 2 standard errors. The issue's 5 % holds on average at 526
  // and 721 N, not run by run: stated tolerances rms 7 %, mean 3 %, coverage 80 %.
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto flat = c.rough_flat();
  double ss = 0.0, sum = 0.0;
  int n = 0, covered = 0;
  for (double P : {234.0, 331.0, 526.0, 721.0}) {
    const auto lp = predict_load(flat, P, {});
    for (int seed = 1; seed <= 6; ++seed) {
      SyntheticOptions o;
      o.excitation.amplitude = 6.75e-6;
      o.seed = static_cast<std::uint64_t>(seed);
      const auto a = analyze_fretting(synthetic_experiment(lp.backbone, o), P);
      const double k0 = lp.backbone->initial_stiffness();
      const double e = (a.mean.stiffness - k0) / k0;
      ss += e * e;
      sum += e;
      ++n;
      covered += std::abs(e) * k0 < 2.0 * a.stiffness_standard_error;
    }
  }
  EXPECT_LT(std::sqrt(ss / n), 0.07);
  EXPECT_LT(std::abs(sum / n), 0.03);
  EXPECT_GE(covered, static_cast<int>(0.8 * n));
}

class AnalyzeSyntheticDense : public AnalyzeSynthetic {};

TEST_P(AnalyzeSyntheticDense, RecoversStiffnessFromDeltaAlone) {
  // Without the imposed displacement the stiffness comes from delta(Q). The stiffness at
  // reversal of this joint (430-1200 N/um) makes the displacement over the fit window
  // only 0.1-0.2 um, comparable with the 0.1 um noise: at 1 kHz and 10 cycles the fit
  // scatters by 13-46 %. With 40 kHz (the LNS has 250 kHz bandwidth, section 5.2) and 40
  // cycles, a cubic over window 0.5 is within 5 %.
  const auto [P, seed, imposed] = GetParam();
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto lp = predict_load(c.rough_flat(), P, {});
  SyntheticOptions o;
  o.excitation.amplitude = 6.75e-6;
  o.excitation.cycles = 40;
  o.sample_rate = 40000.0;
  o.seed = static_cast<std::uint64_t>(seed) + 100;
  auto data = synthetic_experiment(lp.backbone, o);
  if (!imposed) data.Delta.clear();  // with Delta: it splits the cycles, not the stiffness
  const auto a = analyze_fretting(
      data, P, {.stiffness_window = 0.5, .stiffness_degree = 3, .stiffness_from_imposed = false});
  EXPECT_FALSE(a.stiffness_from_imposed);
  const double k0 = lp.backbone->initial_stiffness();
  EXPECT_LT(rel(a.mean.stiffness, k0), 0.05) << a.mean.stiffness << " " << k0;
  EXPECT_LT(rel(a.mean.stiffness, lp.stiffness), 0.05);
  EXPECT_LT(std::abs(a.mean.stiffness - k0), 3.0 * a.stiffness_standard_error);
  expect_mean_consistent(a);
}

class AnalyzeSyntheticImposed : public ::testing::TestWithParam<std::tuple<double, int>> {};

TEST_P(AnalyzeSyntheticImposed, RecoversStiffnessAndApparatusCompliance) {
  // Where the issue's 5 % is achieved with the thesis's 10 cycles: Table 5.6's experiment
  // as in AnalyzeSynthetic (noise 0.1 um and 1 N) with the imposed Delta, sampled at
  // 20 kHz and fitted by a cubic over window 0.5: noise-free bias -1 % (below), scatter
  // about 1.5 %, 24 seeds within 4.3 %.
  const auto [P, seed] = GetParam();
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto lp = predict_load(c.rough_flat(), P, {});
  SyntheticOptions o;
  o.excitation.amplitude = 6.75e-6;
  o.sample_rate = 20000.0;
  o.seed = static_cast<std::uint64_t>(seed) + 200;
  const AnalysisOptions dense{.stiffness_window = 0.5, .stiffness_degree = 3};
  const auto a = analyze_fretting(synthetic_experiment(lp.backbone, o), P, dense);
  ASSERT_TRUE(a.stiffness_from_imposed);
  const double k0 = lp.backbone->initial_stiffness();
  EXPECT_LT(rel(a.mean.stiffness, k0), 0.05) << a.mean.stiffness << " " << k0;
  EXPECT_LT(std::abs(a.mean.stiffness - k0), 3.0 * a.stiffness_standard_error);
  EXPECT_TRUE(a.warnings.empty()) << a.warnings.front();
  // Fig. 5.7: the springs in series; the fit's standard error is about 0.03 %, so 0.5 %
  // is about 15 standard errors. The residual is the displacement noise (0.1 um) plus
  // c times the force noise (0.027 um) in quadrature.
  const double c_app = 1.0 / o.pzt_stiffness + 1.0 / o.load_cell_stiffness;
  EXPECT_LT(rel(a.apparatus_compliance, c_app), 5e-3) << a.apparatus_compliance;
  EXPECT_LT(rel(a.apparatus_residual_rms, std::hypot(o.noise_delta, c_app * o.noise_Q)), 0.05);
  // Noise-free: the bias of the method alone.
  o.noise_delta = 0.0;
  o.noise_Q = 0.0;
  const auto clean = analyze_fretting(synthetic_experiment(lp.backbone, o), P, dense);
  EXPECT_LT(rel(clean.mean.stiffness, k0), 0.02) << clean.mean.stiffness << " " << k0;
  EXPECT_LT(clean.apparatus_residual_rms, 1e-3 * o.excitation.amplitude);
}

INSTANTIATE_TEST_SUITE_P(AnalyzeTable56, AnalyzeSyntheticImposed,
                         ::testing::Values(std::make_tuple(234.0, 1), std::make_tuple(331.0, 2),
                                           std::make_tuple(526.0, 3), std::make_tuple(721.0, 4)));
INSTANTIATE_TEST_SUITE_P(AnalyzeTable56, AnalyzeSyntheticDense,
                         ::testing::Values(std::make_tuple(234.0, 1, false),
                                           std::make_tuple(526.0, 3, true),
                                           std::make_tuple(721.0, 5, false)));
INSTANTIATE_TEST_SUITE_P(
    AnalyzeTable56, AnalyzeSynthetic,
    ::testing::Values(std::make_tuple(234.0, 1, false), std::make_tuple(331.0, 2, false),
                      std::make_tuple(526.0, 3, true), std::make_tuple(526.0, 4, false),
                      std::make_tuple(721.0, 5, false), std::make_tuple(234.0, 6, true),
                      std::make_tuple(721.0, 7, true)));

TEST(AnalyzeFretting, EnergyNoiseFloorOfThinLoops) {
  // 526 N, PZT amplitude 0.5 um: the joint moves about 0.02 um and dissipates ~0.008 uJ
  // per cycle, far below what the sensors resolve (noise 0.1 um, 1 N at 1 kHz). The signed
  // per-cycle energy keeps the mean unbiased (|area| per cycle was 17x too high); the run
  // is flagged, and over 12 seeds the mean's scatter matches the predicted noise floor
  // (ratio of rms deviation to rms floor within 0.7-1.4: 12 samples give +-20 % on an rms).
  const auto c = read_case_file(kExamples + "steel420_two_bolts.toml");
  const auto lp = predict_load(c.rough_flat(), 526.0, {});
  SyntheticOptions o;
  o.excitation.amplitude = 0.5e-6;
  const auto truth = truth_of(*lp.backbone, o);
  double dev2 = 0.0, floor2 = 0.0;
  for (int seed = 1; seed <= 12; ++seed) {
    o.seed = static_cast<std::uint64_t>(seed);
    const auto a = analyze_fretting(synthetic_experiment(lp.backbone, o), 526.0);
    EXPECT_FALSE(a.energy_resolved) << a.mean.energy << " floor " << a.energy_noise_floor;
    EXPECT_TRUE(std::any_of(a.warnings.begin(), a.warnings.end(), [](const std::string& w) {
      return w.find("noise floor") != std::string::npos;
    }));
    dev2 += (a.mean.energy - truth.energy) * (a.mean.energy - truth.energy);
    floor2 += a.energy_noise_floor * a.energy_noise_floor;
  }
  const double ratio = std::sqrt(dev2 / floor2);
  EXPECT_GT(ratio, 0.7);
  EXPECT_LT(ratio, 1.4);
}

TEST(AnalyzeFretting, NoiseFreeJenkinsLoopIsExact) {
  // A Jenkins element (k = 100 N/um, F = 50 N) driven directly: energy 4 F (d - F/k),
  // sliding displacement d - F/k, partial slip F/k (Fig. 6.1).
  auto bb = std::make_shared<hysteresis::JenkinsBackbone>(100e6, 50.0);
  SyntheticOptions o;
  o.excitation.amplitude = 2e-6;
  o.pzt_stiffness = 1e15;  // rigid apparatus
  o.load_cell_stiffness = 1e15;
  o.noise_delta = 0.0;
  o.noise_Q = 0.0;
  o.sample_rate = 20000.0;
  const auto a = analyze_fretting(synthetic_experiment(bb, o), 100.0);
  const double d = 2e-6, F = 50.0, k = 100e6;
  // The moving average over 1/50 cycle rounds the loop's corners: 0.13 % less area.
  EXPECT_LT(rel(a.mean.energy, 4 * F * (d - F / k)), 2e-3);
  EXPECT_LT(rel(a.loop_energy, 4 * F * (d - F / k)), 2e-3);  // the averaged loop, smoothed too
  EXPECT_LT(rel(a.mean.sliding, d - F / k), 2e-3);
  EXPECT_LT(rel(a.mean.partial_slip, F / k), 2e-3 * d / (F / k));
  EXPECT_LT(rel(a.mean.stiffness, k), 1e-6);
  EXPECT_LT(rel(a.mu, 0.5), 1e-3);
}

TEST(AnalyzeFretting, PowerLawExponent) {
  EXPECT_NEAR(power_law_exponent({1, 2, 4}, {3, 24, 192}), 3.0, 1e-12);
  EXPECT_THROW((void)power_law_exponent({1}, {1}), InvalidInput);
  // The interval: log e = log 3 + 3 log q + (+-0.1): residuals +0.1, -0.2, +0.1 over
  // log q = 0, ln 2, ln 4 (centred: -ln 2, 0, ln 2): slope unchanged, s^2 = 0.06/1,
  // Sxx = 2 ln^2 2, t(0.975, 1) = 12.706.
  const auto f =
      fit_power_law({1, 2, 4}, {3 * std::exp(0.1), 24 * std::exp(-0.2), 192 * std::exp(0.1)});
  EXPECT_NEAR(f.exponent, 3.0, 1e-12);
  const double se = std::sqrt(0.06 / (2.0 * std::log(2.0) * std::log(2.0)));
  EXPECT_NEAR(f.standard_error, se, 1e-12);
  EXPECT_NEAR(f.ci_high - f.exponent, 12.7062047361747 * se, 1e-9);
  EXPECT_TRUE(std::isnan(fit_power_law({1, 2}, {1, 8}).standard_error));
}

TEST(AnalyzeFretting, BadDataIsRejected) {
  FrettingData d;
  d.source = "x.csv";
  for (int i = 0; i < 100; ++i) {
    d.t.push_back(i * 0.01);
    d.delta.push_back(std::sin(i * 0.01) * 1e-6);
    d.Q.push_back(std::sin(i * 0.01));
  }
  try {  // less than one cycle
    (void)analyze_fretting(d, 100.0);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("fewer than one complete"), std::string::npos) << e.what();
  }
  auto g = d;
  g.t[50] = g.t[49];
  try {
    g.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv: sample 51: time t = 0.49 s does not increase"),
              std::string::npos)
        << e.what();
  }
  auto h = d;
  for (std::size_t i = 60; i < h.t.size(); ++i) h.t[i] += 1.0;
  try {
    h.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    // Times with 6 significant digits, not 0.0099999999999998.
    EXPECT_NE(std::string(e.what()).find("x.csv: sample 61: a gap in time (0.59 s to 1.6 s, a "
                                         "step of 1.01 s where the median step is 0.01 s)"),
              std::string::npos)
        << e.what();
  }
}

TEST(AnalyzeFretting, SyntheticExperimentLimits) {
  // Fewer than kMinSamplesPerPeriod samples per period, or more than kMaxSyntheticSamples
  // in all: InvalidInput naming the fields, before anything is allocated (a 1e15-sample
  // request returns at once instead of exhausting the memory).
  const auto backbone = std::make_shared<hysteresis::JenkinsBackbone>(1e6, 1.0);
  SyntheticOptions o;
  o.excitation = {.amplitude = 1e-6, .frequency = 1.0, .cycles = 10};
  const auto message = [&](double rate, int cycles) {
    o.sample_rate = rate;
    o.excitation.cycles = cycles;
    try {
      (void)synthetic_experiment(backbone, o);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(1.0, 10).find("sample_rate = 1 Hz gives 1 samples per period"),
            std::string::npos);
  EXPECT_NE(message(49.0, 10).find("at least 50"), std::string::npos);
  EXPECT_EQ(message(kMinSamplesPerPeriod, 10), "");  // the bound itself is allowed
  EXPECT_NE(message(1e9, 1000000).find("exceed the limit of 1e+07"), std::string::npos);
  // Just above: (cycles + 1)/f x rate + 1 = 10 s x 1 MHz + 1 = 1e7 + 1 samples.
  EXPECT_NE(message(1e6, 9).find("exceed the limit"), std::string::npos);
  EXPECT_EQ(message(1e4, 2), "");
}

TEST(AnalyzeFretting, Eq53Excitation) {
  // Eq. 5.3: A t up to t = 0.5 s, 0.5 A (1 + sin 2 pi f t) after: continuous, between 0 and A.
  const Eq53Excitation e{.amplitude = 1e-6, .frequency = 1.0, .cycles = 10};
  EXPECT_DOUBLE_EQ(e(0.0), 0.0);
  EXPECT_NEAR(e(0.5), 1e-6, 1e-18);
  EXPECT_NEAR(e(0.75), 0.0, 1e-18);
  EXPECT_NEAR(e(1.25), 2e-6, 1e-18);
  EXPECT_NEAR(e(10.5), 1e-6, 1e-15);
  EXPECT_NEAR(e(11.0), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(e.duration(), 11.0);
}

}  // namespace
}  // namespace asperity::joint

namespace asperity::joint {
namespace {

TEST(ValidateReport, EveryReproductionAgreesOrIsDocumented) {
  const auto rows = validation_rows();
  // The rows documented to differ from the thesis (docs/seed_notes.md: Table 4.1 does not
  // follow from the printed equations). Every other reproduction must agree, and these
  // must still differ (else the docs are out of date).
  const std::set<std::string> documented = {
      "Table 4.1: mu KE psi = 0.5", "Table 4.1: mu BKE psi = 0.5", "Table 4.1: mu CEB psi = 1",
      "Table 4.1: mu KE psi = 1",   "Table 4.1: mu BKE psi = 1",   "Table 4.1: mu CEB psi = 2",
      "Table 4.1: mu KE psi = 2"};
  std::size_t experiments = 0, regression = 0;
  for (const auto& r : rows) {
    const std::string id = r.source + ": " + r.quantity;
    if (r.verdict.find("model vs experiment") != std::string::npos) {
      ++experiments;
      EXPECT_EQ(r.kind(), "model vs experiment") << id;
      continue;
    }
    regression += r.source == "Table 4.1 (regression)";
    EXPECT_EQ(r.verdict, documented.count(id) ? "differs (documented)" : "agrees")
        << id << ": ours " << r.ours << ", reference " << r.thesis;
  }
  EXPECT_EQ(regression, 12U);  // every Table 4.1 entry against the independent quadrature
  // Table 5.6 (8) and Table 6.4 (12); per model variant of issue 11 (uniform, bolt field,
  // each with and without the halves): ch. 5 stiffness (16), Table 5.6 delta_max (16),
  // Fig. 6.11 stiffness (48), and the exponent of Fig. 6.12-6.14 (uniform and bolt field:
  // 24; every one of these runs is in partial slip at 2.25 um).
  EXPECT_EQ(experiments, 124U);
  for (const char* s : {"Ch. 5 stiffness (section 5.2: 10-300 N/um)", "Table 5.6 by variant",
                        "Fig. 6.11 stiffness (dry; steel 200-275, Al 30-65 N/um)",
                        "Fig. 6.12-6.14 energy-force exponent (2-3)"}) {
    EXPECT_EQ(std::count_if(rows.begin(), rows.end(),
                            [&](const ValidationRow& r) { return r.source == s; }),
              std::string(s).starts_with("Fig. 6.11")   ? 48
              : std::string(s).starts_with("Fig. 6.12") ? 24
                                                        : 16)
        << s;
  }
  // Every table of issue 5 is covered.
  for (const char* s : {"Table 3.2", "Table 3.4", "Table 4.1", "Table 4.1 (regression)", "Fig. 4.4",
                        "Table 5.2", "Table 5.4", "Table 5.5", "Table 5.6", "Table 6.2",
                        "Table 6.3", "Table 6.4", "Ch. 5 mu (BKE)"}) {
    EXPECT_TRUE(std::any_of(rows.begin(), rows.end(), [&](const ValidationRow& r) {
      return r.source == s;
    })) << s;
  }
  const auto md = validation_markdown(rows);
  EXPECT_NE(md.find("| mu at 526 N | 0.335 |"), std::string::npos);
  // The summary counts the three kinds apart (regressions are not agreements with the thesis).
  EXPECT_NE(md.find("12 regression (our own reference) rows (12 agrees)"), std::string::npos);
  EXPECT_NE(md.find("124 model-versus-experiment rows"), std::string::npos);
}

}  // namespace
}  // namespace asperity::joint
