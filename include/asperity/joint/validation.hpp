#pragma once
// Reproduction of the thesis's numbers (asperity validate): every table and statement
// the library can recompute, with the thesis's value, ours, the relative difference and
// a verdict. Used by the CLI, the test suite and docs/validation.md.
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

/// Computes every row (about a second).
[[nodiscard]] std::vector<ValidationRow> validation_rows();

/// Markdown report: a table per source with ours, the thesis's, the relative
/// difference and the verdict, and a summary count.
[[nodiscard]] std::string validation_markdown(const std::vector<ValidationRow>& rows);

}  // namespace asperity::joint
