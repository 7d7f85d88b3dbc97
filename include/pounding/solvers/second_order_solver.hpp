#pragma once
// A SUNDIALS linear solver for the Newton systems (I − γJ) x = b of a second-order system written
// in first-order form. With J = [[0, I], [A21, A22]] (n×n blocks) the 2n system reduces exactly to
//   (I − γA22 − γ²A21) x₂ = b₂ + γ A21 b₁,   x₁ = b₁ + γ x₂,
// so one n×n LU replaces a 2n×2n one (8× fewer flops to factor, 4× fewer to solve). When A21 and
// A22 are diagonal (the free motion in modal coordinates) the reduced matrix is too, and a solve
// is O(n) divisions instead of an LU. When OdeFunctions gives [A21, A22] sparse (the physical
// form: K and C couple only a storey's two floors, a held contact adds a few rows), the reduced
// matrix is factored by a sparse LU, O(n) for a building's block-tridiagonal structure instead of
// the dense LU's O(n³). It is "matrix-embedded": it evaluates the Jacobian through OdeFunctions
// itself and refactors when the contact phase changes or γ drifts by more than 20 %. While the
// phase is linear (OdeFunctions::is_linear: J constant) J is evaluated once per phase, so a
// refactorisation for a new γ redoes only the γ-dependent work (O(n) in modal free flight, where
// evaluating and scanning the dense J is O(n²)); a nonlinear phase (a hold, a compliant contact)
// evaluates J at every refactorisation.
//   Extra first-order states w (OdeFunctions::extra_state_count: Bouc–Wen's z), with
// J = [[0, I, 0], [A21, A22, B], [0, C, diag d]], are eliminated too (sparse path only): with
// D = I − γ diag d,
//   (I − γA22 − γ²A21 − γ² B D⁻¹ C) x₂ = b₂ + γ A21 b₁ + γ B D⁻¹ b₃,  x₃ = D⁻¹ (b₃ + γ C x₂),
// where B D⁻¹ C couples only the floors a column joins, so the reduced matrix keeps K's pattern.

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <functional>
#include <vector>

#include "pounding/solvers/integrator.hpp"
#include "pounding/solvers/sundials_handles.hpp"

namespace pounding::solvers {

/// What the integrator is solving for when it asks for a linear solve.
struct NewtonData {
  double t_s = 0.0;
  N_Vector prediction = nullptr;  // the state the Jacobian is evaluated at
  double gamma = 0.0;
};

class SecondOrderLinearSolver {
 public:
  /// `functions`, whatever `newton_data` reads and `error_sink` must outlive the solver; a failed
  /// solve writes its reason to `error_sink` (the integrator's failure message).
  /// @pre functions.jacobian() returns [[0, I], [A21, A22]].
  SecondOrderLinearSolver(OdeFunctions& functions, std::function<NewtonData()> newton_data, SUNContext context,
                          std::string& error_sink);

  SUNLinearSolver get() const { return handle_.get(); }
  long factorizations() const { return factorizations_; }
  /// How many times J was evaluated (at most factorizations(): once per linear phase).
  long jacobian_evaluations() const { return jacobian_evaluations_; }
  /// The Jacobian changed (new contact phase): evaluate it and refactor at the next solve.
  void invalidate() {
    stale_ = true;
    jacobian_current_ = false;
  }

 private:
  static SUNLinearSolver_Type type(SUNLinearSolver);
  static int setup(SUNLinearSolver solver, SUNMatrix);
  static int solve(SUNLinearSolver solver, SUNMatrix, N_Vector x, N_Vector b, double tolerance);
  static int release(SUNLinearSolver solver);
  void factor(const NewtonData& data);
  /// Evaluates J at the Newton prediction into sparse_rows_ or jacobian_ (and, dense, whether its
  /// lower blocks are diagonal).
  void evaluate_jacobian(const NewtonData& data);

  OdeFunctions& functions_;
  std::function<NewtonData()> newton_data_;
  sundials::LinearSolver handle_;
  Eigen::Index n_ = 0;  // second-order DOF count: the state has 2n entries, then m_ extra ones
  Eigen::Index m_ = 0;
  /// Factors I − γA22 − γ²A21 from the sparse rows [A21, A22] in sparse_rows_; orders its pattern
  /// again only when `new_rows` (just evaluated) and the pattern is not the one ordered.
  void factor_sparse(double gamma, bool new_rows);
  /// Factors it from the dense jacobian_.
  void factor_dense(double gamma);

  Eigen::MatrixXd jacobian_;                                     // dense path: the whole 2n × 2n Jacobian
  Eigen::PartialPivLU<Eigen::MatrixXd> reduced_;                 // dense path, when not diagonal
  bool sparse_ = false;                                          // the last evaluation of J gave sparse rows
  Eigen::SparseMatrix<double> sparse_rows_;                      // [A21, A22], n × 2n
  Eigen::SparseMatrix<double> accel_by_w_, w_rate_by_velocity_;  // B (n × m) and C (m × n)
  Eigen::VectorXd w_rate_by_w_, w_factor_;                       // d, and D⁻¹ = 1/(1 − γ d) as factored
  Eigen::SparseLU<Eigen::SparseMatrix<double>> sparse_reduced_;
  std::vector<int> ordered_outer_, ordered_inner_;  // the pattern sparse_reduced_ was ordered for
  bool diagonal_ = false;                           // A21 and A22 diagonal: reduced_diagonal_ holds the matrix
  Eigen::VectorXd reduced_diagonal_;                // 1 − γ diag A22 − γ² diag A21
  Eigen::VectorXd a21_diagonal_, a22_diagonal_;
  bool jacobian_current_ = false;  // J is this phase's (kept while the phase is linear)
  double gamma_ = 0.0;
  double factored_t_s_ = 0.0;  // the Newton prediction's time at the last factorisation
  bool stale_ = true;
  long factorizations_ = 0, jacobian_evaluations_ = 0;
  std::string& error_sink_;
};

}  // namespace pounding::solvers
