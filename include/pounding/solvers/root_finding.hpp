#pragma once
// Scalar root bracketing shared by the solution paths.

#include <functional>

namespace pounding::solvers {

/// Illinois (modified regula falsi) on [a, b] with f(a), f(b) of opposite signs (or f(b) = 0),
/// to round-off, or until the bracket is narrower than `width` (> 0). Returns the end of the
/// final bracket on b's side, so a root of a falling gap comes back with g ≤ 0.
double find_root(const std::function<double(double)>& f, double a, double b, double fa, double fb, double width = 0.0);

}  // namespace pounding::solvers
