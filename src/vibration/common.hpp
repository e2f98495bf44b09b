#pragma once
// Pieces shared by several files of the vibration layer (internal; a unity build puts
// these files in one translation unit, so each is defined once).
#include <cstddef>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Core>

#include "asperity/core/error.hpp"
#include "asperity/vibration/harmonic_balance.hpp"

namespace asperity::vibration::detail {

/// -1, 0 or +1.
[[nodiscard]] inline int sign_of(double x) {
  return (x > 0.0) - (x < 0.0);
}

/// Smallest prominence of a reported fold, relative to the frequency (or lambda) range. On
/// the hardening-contact case of issue 23 the Z's of sample-located contact stay below 1e-2
/// of the range in frequency; its folds are 0.06 to 0.2 of the range.
inline constexpr double kFoldProminence = 1e-2;

/// InvalidInput naming the first output DOF outside 0 .. dofs - 1 (its position 1-based).
inline void require_outputs(const HarmonicBalance& hb, const std::vector<Eigen::Index>& outputs) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k] < 0 || outputs[k] >= hb.dofs()) {
      throw InvalidInput(fmt::format("output_dofs[{}] = {}: DOFs are numbered 0 .. {}", k + 1,
                                     outputs[k], hb.dofs() - 1));
    }
  }
}

}  // namespace asperity::vibration::detail
