// Quantities with units (core/units.hpp): SI prefixes, powers, compound units, US
// customary units and the errors for malformed text or a wrong dimension.
//
// Reference values are exact unit definitions: SI prefixes (BIPM SI Brochure, 9th ed.,
// Table 7), the international inch 0.0254 m and pound-force 4.4482216152605 N (NIST
// SP 811, App. B.8). Every product of a decimal number and such factors is computed
// by the parser with at most a few roundings, so a relative tolerance of 4 ulp
// (1e-15) is both tight and safe.
#include <gtest/gtest.h>

#include "../support.hpp"

#include <string>

#include "asperity/core/error.hpp"
#include "asperity/core/units.hpp"

namespace asperity::core {
namespace {

using asperity::testing::invalid_input_message;

constexpr double kTol = 1e-15;            // a few ulp: the parser multiplies exact factors
constexpr double kInch = 0.0254;          // m, exact (NIST SP 811)
constexpr double kLbf = 4.4482216152605;  // N, exact (NIST SP 811)

void expect_quantity(const std::string& text, double value, Dimension d) {
  const Quantity q = parse_quantity(text, "test");
  EXPECT_NEAR(q.value, value, kTol * std::abs(value)) << text;
  EXPECT_EQ(q.dimension, d) << text << " -> " << dimension_name(q.dimension);
}

TEST(Units, SiPrefixesOnPressureLengthForce) {
  expect_quantity("207 GPa", 207e9, dim::pressure);
  expect_quantity("207GPa", 207e9, dim::pressure);
  expect_quantity("6.83 GPa", 6.83e9, dim::pressure);
  expect_quantity("300 MPa", 300e6, dim::pressure);
  expect_quantity("2.5mm", 2.5e-3, dim::length);
  expect_quantity("1.5 um", 1.5e-6, dim::length);
  expect_quantity("12.67 nm", 12.67e-9, dim::length);
  expect_quantity("3 pm", 3e-12, dim::length);
  expect_quantity("4 cm", 4e-2, dim::length);
  expect_quantity("35N", 35.0, dim::force);
  expect_quantity("1.1 uN", 1.1e-6, dim::force);
  expect_quantity("2 kN", 2e3, dim::force);
  expect_quantity("3 kg", 3.0, dim::mass);     // k + g: the SI base unit of mass
  expect_quantity("250 ms", 0.25, dim::time);  // milli-second, not metre-second
  expect_quantity("40 kHz", 4e4, dim::frequency);
  expect_quantity("1e-3 m", 1e-3, dim::length);
  expect_quantity("+2 m", 2.0, dim::length);
  expect_quantity("-2 m", -2.0, dim::length);  // the sign is the caller's business
}

TEST(Units, MicroSignAndGreekMu) {
  expect_quantity("1.5 \xC2\xB5m", 1.5e-6, dim::length);  // U+00B5 MICRO SIGN
  expect_quantity("1.5 \xCE\xBCm", 1.5e-6, dim::length);  // U+03BC GREEK SMALL LETTER MU
  expect_quantity("1.1 \xC2\xB5N", 1.1e-6, dim::force);
}

TEST(Units, PowersOfUnits) {
  // Table 5.4 writes eta in um^-2: 2.91e-4 um^-2 = 2.91e-4 * 1e12 m^-2.
  expect_quantity("2.91e-4 um^-2", 2.91e8, dim::inverse_area);
  expect_quantity("170 mm^2", 170e-6, dim::area);
  expect_quantity("1 m^3", 1.0, Dimension{3, 0, 0});
  expect_quantity("9.81 m/s^2", 9.81, Dimension{1, 0, -2});
  expect_quantity("16.17 N/um", 16.17e6, dim::stiffness);
  expect_quantity("1 N/m^2", 1.0, dim::pressure);
}

TEST(Units, CompoundProducts) {
  // Bolt torque of chapter 5: N*m, N.m, N m and N·m (U+00B7) all mean newton metre.
  expect_quantity("0.1525 N*m", 0.1525, dim::energy);
  expect_quantity("0.1525 N.m", 0.1525, dim::energy);
  expect_quantity("0.1525 N m", 0.1525, dim::energy);
  expect_quantity("0.1525 N\xC2\xB7m", 0.1525, dim::energy);
  expect_quantity("3 J", 3.0, dim::energy);
  expect_quantity("2 kg*m/s^2", 2.0, dim::force);
}

TEST(Units, UsCustomaryUnits) {
  expect_quantity("1 in", kInch, dim::length);
  expect_quantity("2 ft", 24 * kInch, dim::length);
  expect_quantity("1 lbf", kLbf, dim::force);
  expect_quantity("10 lbf*in", 10 * kLbf * kInch, dim::energy);
  expect_quantity("1 psi", kLbf / (kInch * kInch), dim::pressure);
  // 1 psi = 6894.757293168361 Pa (NIST SP 811 B.8: 6.894 757 E+03).
  EXPECT_NEAR(parse_quantity("1 psi", dim::pressure, "p"), 6894.757293168361, 1e-9);
  expect_quantity("30 ksi", 30e3 * kLbf / (kInch * kInch), dim::pressure);
  expect_quantity("2 h", 7200.0, dim::time);
  expect_quantity("3 min", 180.0, dim::time);
}

TEST(Units, DimensionCheckedOverload) {
  EXPECT_DOUBLE_EQ(parse_quantity("207 GPa", dim::pressure, "--E1"), 207e9);
  EXPECT_DOUBLE_EQ(parse_quantity("0.3", dim::dimensionless, "--nu1"), 0.3);
  // Bare numbers are accepted only where the quantity is dimensionless.
  const auto bare =
      invalid_input_message([] { (void)parse_quantity("207", dim::pressure, "--E1"); });
  EXPECT_NE(bare.find("--E1"), std::string::npos) << bare;
  EXPECT_NE(bare.find("pressure"), std::string::npos) << bare;
  // A quantity of another dimension is rejected and both dimensions are named.
  const auto mismatch =
      invalid_input_message([] { (void)parse_quantity("2.5 mm", dim::force, "--P"); });
  EXPECT_NE(mismatch.find("--P"), std::string::npos) << mismatch;
  EXPECT_NE(mismatch.find("length"), std::string::npos) << mismatch;
  EXPECT_NE(mismatch.find("force"), std::string::npos) << mismatch;
  // And a unit where a pure number is expected.
  const auto with_unit =
      invalid_input_message([] { (void)parse_quantity("0.3 N", dim::dimensionless, "--nu1"); });
  EXPECT_NE(with_unit.find("--nu1"), std::string::npos) << with_unit;
}

TEST(Units, MalformedTextIsRejectedNamingTheField) {
  for (const std::string text :
       {"207 GPaa", "abc", "", "   ", "GPa", "207 G Pa", "1.5 um^", "1.5 um^x", "1 N*", "1 /m",
        "1 N**m", "1 m^0", "1 m^7", "5 $", "1 Pa#", "nan", "inf", "1e999 m", "207 gpa"}) {
    const auto msg = invalid_input_message([&] { (void)parse_quantity(text, "--E1"); });
    EXPECT_FALSE(msg.empty()) << "accepted \"" << text << "\"";
    EXPECT_NE(msg.find("--E1"), std::string::npos) << msg;
  }
  // The message says what is wrong with the text.
  EXPECT_NE(invalid_input_message([] { (void)parse_quantity("207 GPaa", "--E1"); }).find("GPaa"),
            std::string::npos);
  EXPECT_NE(invalid_input_message([] { (void)parse_quantity("abc", "--E1"); }).find("abc"),
            std::string::npos);
}

TEST(Units, OverflowAndUnderflowAreNamedAsSuch) {
  // A number outside the double range is well formed: the message must say overflow
  // or underflow, not "does not start with a number".
  const auto big = invalid_input_message([] { (void)parse_quantity("1e400", "--P"); });
  EXPECT_NE(big.find("--P"), std::string::npos) << big;
  EXPECT_NE(big.find("overflows"), std::string::npos) << big;
  EXPECT_EQ(big.find("does not start with a number"), std::string::npos) << big;
  const auto tiny = invalid_input_message([] { (void)parse_quantity("1e-400 N", "--P"); });
  EXPECT_NE(tiny.find("underflows"), std::string::npos) << tiny;
  const auto neg = invalid_input_message([] { (void)parse_quantity("-1e400 N", "--P"); });
  EXPECT_NE(neg.find("overflows"), std::string::npos) << neg;
  // In range as a number, out of range once in SI units.
  const auto si = invalid_input_message([] { (void)parse_quantity("1e300 TPa", "--E1"); });
  EXPECT_NE(si.find("overflows"), std::string::npos) << si;
  const auto si_tiny = invalid_input_message([] { (void)parse_quantity("1e-315 pm", "--R1"); });
  EXPECT_NE(si_tiny.find("underflows"), std::string::npos) << si_tiny;
}

TEST(Units, NonPrefixableUnitsRejectPrefixes) {
  // "kpsi" and "min" as milli-inch must not be invented; "min" is minutes.
  EXPECT_THROW((void)parse_quantity("1 kpsi", "x"), InvalidInput);
  EXPECT_THROW((void)parse_quantity("1 klbf", "x"), InvalidInput);
  expect_quantity("1 min", 60.0, dim::time);
}

TEST(Units, DimensionNames) {
  EXPECT_NE(dimension_name(dim::pressure).find("pressure"), std::string::npos);
  EXPECT_EQ(dimension_name(dim::dimensionless), "dimensionless");
  EXPECT_EQ(dimension_name(Dimension{3, 0, 0}), "m^3");
  EXPECT_EQ(dimension_name(Dimension{1, 2, -3}), "m kg^2 s^-3");
}

}  // namespace
}  // namespace asperity::core
