#pragma once
// Internal to the dynamics case file (asperity/dynamics/case.hpp): read by case_parse.cpp,
// run by case_run.cpp; what both use.
#include "asperity/dynamics/case.hpp"

namespace asperity::dynamics::detail {

/// The time scale sqrt(m/k) of tau = sqrt(k/m) t (dynamics/system.hpp); needs the scales
/// mass and stiffness.
double time_scale(const CaseScales& s);

}  // namespace asperity::dynamics::detail
