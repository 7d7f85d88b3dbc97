#include "pounding/solvers/root_finding.hpp"

#include <algorithm>
#include <cmath>

namespace pounding::solvers {

double find_root(const std::function<double(double)>& f, double a, double b, double fa, double fb, double width) {
  int side = 0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    if (b - a <= std::max(width, 4e-16 * std::max(1.0, std::abs(b)))) break;
    double c = (a * fb - b * fa) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc == 0.0) return c;
    if ((fc < 0.0) == (fb < 0.0)) {
      b = c;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c;
      fa = fc;
      if (side == +1) fb *= 0.5;
      side = +1;
    }
  }
  return b;
}

}  // namespace pounding::solvers
