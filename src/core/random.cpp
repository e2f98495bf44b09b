#include "asperity/core/random.hpp"

#include <cmath>

namespace asperity::core {

double StandardNormal::operator()() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  for (;;) {
    const double v1 = 2.0 * uniform() - 1.0;
    const double v2 = 2.0 * uniform() - 1.0;
    const double s = v1 * v1 + v2 * v2;
    if (s >= 1.0 || s == 0.0) continue;
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v2 * f;
    has_spare_ = true;
    return v1 * f;
  }
}

}  // namespace asperity::core
