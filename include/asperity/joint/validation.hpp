#pragma once
// Reproduction of the thesis's numbers (asperity validate): every table and statement
// the library can recompute, with the thesis's value, ours, the relative difference and
// a verdict. Used by the CLI, the test suite and docs/validation.md.
#include <optional>
#include <string>
#include <vector>

#include "asperity/joint/case.hpp"

namespace asperity::joint {

struct ValidationRow {
  std::string source;    ///< "Table 3.2", "Fig. 4.4", ...
  std::string quantity;  ///< what is compared
  double thesis =
      0.0;  ///< the reference: the thesis's value (or measurement, or our independent quadrature)
  double ours = 0.0;
  double tolerance = 0.0;  ///< relative tolerance of the row (and its reason in `note`)
  /// "agrees", "differs (documented)" for a disagreement documented for this row, or
  /// "FAIL"; model-versus-measurement rows (not reproductions; `thesis` holds the
  /// measurement) read "agrees (model vs experiment)" within 10 % or "differs (model vs
  /// experiment)", and never fail.
  std::string verdict;
  std::string note;
  /// A measured range (lo, hi) instead of one value (both 0 when none): `thesis` then
  /// holds the nearer bound (the relative difference is 0 inside the range) and the
  /// verdict reads "agrees (model vs experiment)" only inside it.
  double range_low = 0.0, range_high = 0.0;
  /// "reproduction", "regression" (our own reference) or "model vs experiment".
  [[nodiscard]] std::string kind() const;
  [[nodiscard]] double relative_difference() const;
};

/// The two-bolt steel 420 joint of chapter 5 (Tables 5.3-5.5; the same as
/// examples/joints/steel420_two_bolts.toml): preloads 234/331/526/721 N, BKE,
/// amplitudes 0.05-4 um.
[[nodiscard]] JointCase chapter5_joint();

/// The four joints of chapter 6 (Tables 6.1-6.3; the same as examples/joints/
/// {aluminium,steel}_{smooth,rough}.toml, tested): smooth Al, rough Al, smooth steel,
/// rough steel; BKE, A0 = 165 mm^2, total torques 0.192/0.305/0.418 N m.
[[nodiscard]] std::vector<JointCase> chapter6_joints();

/// The joint's interface under the two bolts' pressure cones, with the geometry assumed for
/// the thesis's lap joints (not printed there): outline Lx x 10 mm with Lx = A0/10 mm,
/// bolts on the centre line at the quarter points, M3 socket head d_w = 5.5 mm (ISO 4762),
/// hole 3.4 mm (ISO 273 medium), both halves 5 mm thick, 1 mm patches.
[[nodiscard]] JointCase with_assumed_bolt_field(JointCase c);

/// The halves between the measurement points and the interface, assumed for the thesis's
/// joints (not printed there): 5 mm free length and 5 mm thickness each, 10 mm wide.
[[nodiscard]] HalvesGeometry assumed_halves();

/// One model variant of one joint at one preload (issue 11): the numbers the variant
/// rows hold against the measurements, for plots.
struct VariantPoint {
  std::string joint;       ///< "ch. 5", "smooth Al", "rough Al", "smooth St", "rough St"
  std::string variant;     ///< "uniform", "bolt field", "uniform + halves", "bolt field + halves"
  double preload = 0.0;    ///< [N]
  double stiffness = 0.0;  ///< between the measurement points [N/m]
  double stiffness_low = 0.0, stiffness_high = 0.0;  ///< measured range [N/m]
  std::optional<double> exponent;  ///< at the smallest imposed amplitude (ch. 6), partial slip
};

/// Computes every row (a few seconds); `points` (if given) receives the variant points.
[[nodiscard]] std::vector<ValidationRow> validation_rows(
    std::vector<VariantPoint>* points = nullptr);

/// A model-versus-measurement row made elsewhere (the finite-element rows of `asperity
/// validate --fem`): `measured` the measurement, verdict "agrees (model vs experiment)"
/// within 10 %, else "differs (model vs experiment)"; never a failure.
[[nodiscard]] ValidationRow experiment_row(std::string source, std::string quantity,
                                           double measured, double ours, std::string note);
/// The same against a measured range [lo, hi] (agrees only inside it).
[[nodiscard]] ValidationRow experiment_range_row(std::string source, std::string quantity,
                                                 double lo, double hi, double ours,
                                                 std::string note);

/// Markdown report: a table per source with ours, the thesis's, the relative
/// difference and the verdict, and a summary count.
[[nodiscard]] std::string validation_markdown(const std::vector<ValidationRow>& rows);

}  // namespace asperity::joint
