#pragma once
// Internal: the tolerances the rough flat's files share (rough_flat.cpp,
// rough_flat_unloading.cpp, rough_flat_backbone.cpp, patched_flat.cpp).

namespace asperity::surface::detail {

/// Heights beyond exp(-kTailExponent) of the density at max(d*, 0) are left out of the
/// statistical sums, loading and unloading.
inline constexpr double kTailExponent = 60.0;
/// Relative tolerance of every statistical-sum quadrature.
inline constexpr double kQuadratureTol = 1e-13;
/// A tabulated virgin curve (the flat's, each patch's) ends where Q_max - Q_l <
/// kSaturation * Q_max.
inline constexpr double kSaturation = 1e-12;

}  // namespace asperity::surface::detail
