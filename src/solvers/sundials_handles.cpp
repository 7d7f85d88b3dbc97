#include "pounding/solvers/sundials_handles.hpp"

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

}  // namespace

Context make_context() {
  SUNContext context = nullptr;
  if (SUNContext_Create(nullptr, &context) != 0 || !context) {
    throw std::runtime_error("SUNDIALS: could not create a context");
  }
  return Context(context);
}

Vector make_vector(long length, SUNContext context) {
  return Vector(require(N_VNew_Serial(length, context), "a serial vector"));
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
