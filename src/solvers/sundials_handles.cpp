#include "pounding/solvers/sundials_handles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace pounding::solvers::sundials {
namespace {

template <typename Pointer>
Pointer require(Pointer pointer, const char* what) {
  if (!pointer) throw std::runtime_error(std::string("SUNDIALS: could not create ") + what);
  return pointer;
}

// The serial vector's element-wise kernels, compiled here. Debian's SUNDIALS 6.4.1 libraries are
// built without optimisation (-O0: every element goes through the stack), and on the paper
// scene these kernels were most of the time spent inside CVode and ERKStepEvolve. Each kernel
// computes every element with the same operations in the same order as nvector_serial.c, so
// results are bit for bit those of the library's: its special cases of N_VLinearSum (x + y,
// a(x + y), a(x − y), ax + y, …) all round like the three cases kept here, since multiplying by
// ±1 and negating are exact. The fused and vector-array operations stay unset: SUNDIALS then
// composes them from these, as before.
using Index = sunindextype;
double* data(N_Vector v) { return NV_DATA_S(v); }
Index length(N_Vector v) { return NV_LENGTH_S(v); }

void linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  const Index n = length(x);
  if (a == b) {
    for (Index i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (Index i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (Index i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}
void constant(double c, N_Vector z) { std::fill_n(data(z), length(z), c); }
void product(N_Vector x, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = xd[i] * yd[i];
}
void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = xd[i] / yd[i];
}
void scale(double c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = c * xd[i];
}
void absolute(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = std::abs(xd[i]);
}
void inverse(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = 1.0 / xd[i];
}
void add_constant(N_Vector x, double b, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = xd[i] + b;
}
double dot(N_Vector x, N_Vector y) {
  const double *xd = data(x), *yd = data(y);
  double sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}
double max_norm(N_Vector x) {
  const double* xd = data(x);
  double largest = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) largest = std::max(largest, std::abs(xd[i]));
  return largest;
}
double weighted_square_sum(N_Vector x, N_Vector w) {
  const double *xd = data(x), *wd = data(w);
  double sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) {
    const double p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}
double weighted_square_sum_masked(N_Vector x, N_Vector w, N_Vector id) {
  const double *xd = data(x), *wd = data(w), *idd = data(id);
  double sum = 0.0;
  for (Index i = 0, n = length(x); i < n; ++i) {
    if (!(idd[i] > 0.0)) continue;
    const double p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}
double root_mean(double sum, N_Vector x) {
  const double mean = sum / static_cast<double>(length(x));
  return mean <= 0.0 ? 0.0 : std::sqrt(mean);
}
double wrms_norm(N_Vector x, N_Vector w) { return root_mean(weighted_square_sum(x, w), x); }
double wrms_norm_masked(N_Vector x, N_Vector w, N_Vector id) {
  return root_mean(weighted_square_sum_masked(x, w, id), x);
}
double minimum(N_Vector x) {
  const double* xd = data(x);
  double smallest = xd[0];
  for (Index i = 1, n = length(x); i < n; ++i) smallest = std::min(smallest, xd[i]);
  return smallest;
}
void compare(double c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for (Index i = 0, n = length(x); i < n; ++i) zd[i] = std::abs(xd[i]) >= c ? 1.0 : 0.0;
}
booleantype inverse_test(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  booleantype no_zero = SUNTRUE;
  for (Index i = 0, n = length(x); i < n; ++i) {
    if (xd[i] == 0.0) {
      no_zero = SUNFALSE;
    } else {
      zd[i] = 1.0 / xd[i];
    }
  }
  return no_zero;
}

void use_compiled_operations(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvprod = product;
  ops->nvdiv = quotient;
  ops->nvscale = scale;
  ops->nvabs = absolute;
  ops->nvinv = inverse;
  ops->nvaddconst = add_constant;
  ops->nvdotprod = ops->nvdotprodlocal = dot;
  ops->nvmaxnorm = ops->nvmaxnormlocal = max_norm;
  ops->nvwrmsnorm = wrms_norm;
  ops->nvwrmsnormmask = wrms_norm_masked;
  ops->nvwsqrsumlocal = weighted_square_sum;
  ops->nvwsqrsummasklocal = weighted_square_sum_masked;
  ops->nvmin = ops->nvminlocal = minimum;
  ops->nvcompare = compare;
  ops->nvinvtest = ops->nvinvtestlocal = inverse_test;
}

}  // namespace

Context make_context() {
  SUNContext context = nullptr;
  if (SUNContext_Create(nullptr, &context) != 0 || !context) {
    throw std::runtime_error("SUNDIALS: could not create a context");
  }
  return Context(context);
}

Vector make_vector(long length, SUNContext context) {
  Vector vector(require(N_VNew_Serial(length, context), "a serial vector"));
  use_compiled_operations(vector.get());  // clones (the integrators' work vectors) copy the table
  return vector;
}

Matrix make_dense_matrix(long n, SUNContext context) {
  return Matrix(require(SUNDenseMatrix(n, n, context), "a dense matrix"));
}

LinearSolver make_dense_solver(N_Vector template_vector, SUNMatrix matrix, SUNContext context) {
  return LinearSolver(require(SUNLinSol_Dense(template_vector, matrix, context), "a dense linear solver"));
}

std::string take_flag_name(char* name) {
  std::string copy = name ? name : "unknown flag";
  std::free(name);
  return copy;
}

void check(int flag, const char* call, char* (*flag_name)(long)) {
  if (flag >= 0) return;
  throw std::runtime_error(std::string(call) + " failed: " + take_flag_name(flag_name(flag)));
}

}  // namespace pounding::solvers::sundials
