#pragma once
// RAII owners for the SUNDIALS objects (6.x API) and a flag-checking helper.

#include <memory>
#include <nvector/nvector_serial.h>
#include <string>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace pounding::solvers::sundials {

struct ContextDeleter {
  void operator()(SUNContext context) const { SUNContext_Free(&context); }
};
struct VectorDeleter {
  void operator()(N_Vector vector) const { N_VDestroy(vector); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix matrix) const { SUNMatDestroy(matrix); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver solver) const { SUNLinSolFree(solver); }
};

/// Frees a package's integrator memory with that package's function (CVodeFree, ERKStepFree, ...).
struct IntegratorMemoryDeleter {
  void (*free)(void**) = nullptr;
  void operator()(void* memory) const { free(&memory); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
/// Owned from creation on, so a set-up call that throws after CVodeCreate/…StepCreate frees it.
using IntegratorMemory = std::unique_ptr<void, IntegratorMemoryDeleter>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;

/// @throws std::runtime_error if creation fails.
Context make_context();
/// A serial vector whose element-wise operations (and those of its clones) are compiled with this
/// library rather than taken from the SUNDIALS build: same results, several times faster.
Vector make_vector(long length, SUNContext context);
/// A dense n×n matrix and the dense direct solver for it.
Matrix make_dense_matrix(long n, SUNContext context);
LinearSolver make_dense_solver(N_Vector template_vector, SUNMatrix matrix, SUNContext context);

/// @throws std::runtime_error "<call> failed: <flag name>" when flag < 0. `flag_name` maps the
/// module's flag to its name (e.g. CVodeGetReturnFlagName, which allocates; it is freed here).
void check(int flag, const char* call, char* (*flag_name)(long));

/// Copies a flag name returned by a SUNDIALS *GetReturnFlagName function and frees it.
std::string take_flag_name(char* name);

}  // namespace pounding::solvers::sundials
