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
  double thesis = 0.0;
  double ours = 0.0;
  double tolerance = 0.0;  ///< relative tolerance of the row (and its reason in `note`)
  /// "agrees", "differs (documented)" for known disagreements, "experiment" for
  /// model-versus-measurement rows (not a reproduction), or "FAIL".
  std::string verdict;
  std::string note;
  [[nodiscard]] double relative_difference() const;
};

/// The two-bolt steel 420 joint of chapter 5 (Tables 5.3-5.5; the same as
/// examples/joints/steel420_two_bolts.toml): preloads 234/331/526/721 N, BKE,
/// amplitudes 0.05-4 um.
[[nodiscard]] JointCase chapter5_joint();

/// Computes every row (well under a second).
[[nodiscard]] std::vector<ValidationRow> validation_rows();

/// Markdown report: a table per source with ours, the thesis's, the relative
/// difference and the verdict, and a summary count.
[[nodiscard]] std::string validation_markdown(const std::vector<ValidationRow>& rows);

}  // namespace asperity::joint
