// The energy-force power law energy = c Q_max^n over fretting runs (Fig. 6.12-6.14):
// least squares in log-log with a Student-t interval of the exponent.
#include "asperity/joint/fretting.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include <boost/math/distributions/students_t.hpp>

#include "asperity/core/error.hpp"

namespace asperity::joint {

PowerLawFit fit_power_law(const std::vector<double>& Q_max, const std::vector<double>& energy) {
  if (Q_max.size() != energy.size() || Q_max.size() < 2) {
    throw InvalidInput("power law: give at least two runs (energy and Q_max each)");
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(Q_max.size());
  for (std::size_t i = 0; i < Q_max.size(); ++i) {
    if (!(Q_max[i] > 0.0) || !(energy[i] > 0.0))
      throw InvalidInput(
          fmt::format("power law: run {}: Q_max = {:.4g} N and energy = {:.4g} J "
                      "must be > 0",
                      i + 1, Q_max[i], energy[i]));
    const double x = std::log(Q_max[i]), y = std::log(energy[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double den = n * sxx - sx * sx;
  if (!(std::abs(den) > 1e-12 * n * sxx))
    throw InvalidInput("power law: the runs have the same Q_max");
  PowerLawFit f;
  f.runs = Q_max.size();
  f.exponent = (n * sxy - sx * sy) / den;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f.standard_error = f.ci_low = f.ci_high = nan;
  if (Q_max.size() >= 3) {
    const double a = (sy - f.exponent * sx) / n;
    double rss = 0.0;
    for (std::size_t i = 0; i < Q_max.size(); ++i) {
      const double e = std::log(energy[i]) - a - f.exponent * std::log(Q_max[i]);
      rss += e * e;
    }
    const double sxx_c = sxx - sx * sx / n;
    f.standard_error = std::sqrt(rss / (n - 2.0) / sxx_c);
    const boost::math::students_t dist(n - 2.0);
    const double tq = boost::math::quantile(boost::math::complement(dist, 0.025));
    f.ci_low = f.exponent - tq * f.standard_error;
    f.ci_high = f.exponent + tq * f.standard_error;
  }
  return f;
}

double power_law_exponent(const std::vector<double>& Q_max, const std::vector<double>& energy) {
  return fit_power_law(Q_max, energy).exponent;
}

}  // namespace asperity::joint
