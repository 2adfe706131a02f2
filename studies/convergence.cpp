#include <cmath>
#include <limits>

#include "studies/study.hpp"

namespace nsb {

namespace {
bool usable(double e) { return e > 0.0 && std::isfinite(e); }
}  // namespace

double observed_order(double h1, double e1, double h2, double e2) {
  if (!usable(e1) || !usable(e2) || h1 == h2) return std::numeric_limits<double>::quiet_NaN();
  return std::log(e1 / e2) / std::log(h1 / h2);
}

double fitted_order(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < h.size() && i < e.size(); ++i) {
    if (!usable(e[i]) || !(h[i] > 0.0)) continue;
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  const double det = n * sxx - sx * sx;
  if (n < 2 || det == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / det;
}

}  // namespace nsb
