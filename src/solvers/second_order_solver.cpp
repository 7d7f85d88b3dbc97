#include "pounding/solvers/second_order_solver.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

namespace pounding::solvers {
namespace {

Eigen::Map<Eigen::VectorXd> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

constexpr double kGammaTolerance = 0.2;

bool is_diagonal(const Eigen::Ref<const Eigen::MatrixXd>& block) {
  for (Eigen::Index col = 0; col < block.cols(); ++col) {
    for (Eigen::Index row = 0; row < block.rows(); ++row) {
      if (row != col && block(row, col) != 0.0) return false;
    }
  }
  return true;
}

SecondOrderLinearSolver* self(SUNLinearSolver solver) { return static_cast<SecondOrderLinearSolver*>(solver->content); }

}  // namespace

SecondOrderLinearSolver::SecondOrderLinearSolver(OdeFunctions& functions, std::function<NewtonData()> newton_data,
                                                 SUNContext context, std::string& error_sink)
    : functions_(functions),
      newton_data_(std::move(newton_data)),
      n_((functions.state_size() - functions.extra_state_count()) / 2),
      m_(functions.extra_state_count()),
      error_sink_(error_sink) {
  SUNLinearSolver solver = SUNLinSolNewEmpty(context);
  if (!solver) throw std::runtime_error("SUNDIALS: could not create a linear solver");
  solver->content = this;
  solver->ops->gettype = type;
  solver->ops->setup = setup;
  solver->ops->solve = solve;
  solver->ops->free = release;
  handle_.reset(solver);
}

SUNLinearSolver_Type SecondOrderLinearSolver::type(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }

// CVODE and ARKODE (6.4) do not call setup for matrix-embedded solvers, so solve() keeps the
// factorisation current itself; setup is kept for integrators that do call it.
int SecondOrderLinearSolver::setup(SUNLinearSolver solver, SUNMatrix) {
  self(solver)->stale_ = true;
  return SUNLS_SUCCESS;
}

void SecondOrderLinearSolver::factor(const NewtonData& data) {
  // A linear phase's J is constant: evaluating it (and, dense, scanning it for the diagonal
  // case) once per phase leaves a change of γ only the γ-dependent work.
  const bool new_jacobian = !jacobian_current_ || !functions_.is_linear();
  if (new_jacobian) evaluate_jacobian(data);
  if (sparse_) {
    factor_sparse(data.gamma, new_jacobian);
  } else {
    factor_dense(data.gamma);
  }
  gamma_ = data.gamma;
  factored_t_s_ = data.t_s;
  stale_ = false;
  ++factorizations_;
}

void SecondOrderLinearSolver::evaluate_jacobian(const NewtonData& data) {
  sparse_ = functions_.acceleration_jacobian(data.t_s, view(data.prediction), sparse_rows_);
  if (m_ > 0) {
    if (!sparse_) throw std::logic_error("extra states need the sparse acceleration rows");
    functions_.extra_state_jacobian(data.t_s, view(data.prediction), accel_by_w_, w_rate_by_velocity_, w_rate_by_w_);
  }
  if (!sparse_) {
    jacobian_.resize(2 * n_, 2 * n_);
    functions_.jacobian(data.t_s, view(data.prediction), jacobian_);
    const auto a21 = jacobian_.bottomLeftCorner(n_, n_), a22 = jacobian_.bottomRightCorner(n_, n_);
    diagonal_ = is_diagonal(a21) && is_diagonal(a22);
    if (diagonal_) {
      a21_diagonal_ = a21.diagonal();
      a22_diagonal_ = a22.diagonal();
    }
  }
  jacobian_current_ = true;
  ++jacobian_evaluations_;
}

void SecondOrderLinearSolver::factor_sparse(double g, bool new_rows) {
  Eigen::SparseMatrix<double> identity(n_, n_);
  identity.setIdentity();
  Eigen::SparseMatrix<double> reduced = identity - g * sparse_rows_.rightCols(n_) - (g * g) * sparse_rows_.leftCols(n_);
  if (m_ > 0) {
    w_factor_ = (1.0 - g * w_rate_by_w_.array()).inverse().matrix();
    reduced -= (g * g) * (accel_by_w_ * w_factor_.asDiagonal() * w_rate_by_velocity_);
  }
  // The pattern changes with the contact phase only, and ordering it costs half as much as the
  // numeric factorisation: order again only when the pattern is not the one ordered (rows kept
  // from the last factorisation keep its pattern, which was ordered then).
  if (new_rows) {
    const auto outer = std::span(reduced.outerIndexPtr(), static_cast<std::size_t>(n_ + 1));
    const auto inner = std::span(reduced.innerIndexPtr(), static_cast<std::size_t>(reduced.nonZeros()));
    if (!std::ranges::equal(outer, ordered_outer_) || !std::ranges::equal(inner, ordered_inner_)) {
      sparse_reduced_.analyzePattern(reduced);
      ordered_outer_.assign(outer.begin(), outer.end());
      ordered_inner_.assign(inner.begin(), inner.end());
    }
  }
  sparse_reduced_.factorize(reduced);
  if (sparse_reduced_.info() != Eigen::Success) {
    throw std::runtime_error("sparse LU of the Newton matrix failed: " + sparse_reduced_.lastErrorMessage());
  }
}

void SecondOrderLinearSolver::factor_dense(double g) {
  if (diagonal_) {
    reduced_diagonal_ = 1.0 - g * a22_diagonal_.array() - g * g * a21_diagonal_.array();
  } else {
    const auto a21 = jacobian_.bottomLeftCorner(n_, n_), a22 = jacobian_.bottomRightCorner(n_, n_);
    Eigen::MatrixXd reduced = -g * a22 - g * g * a21;
    reduced.diagonal().array() += 1.0;
    reduced_.compute(reduced);
  }
}

int SecondOrderLinearSolver::solve(SUNLinearSolver solver, SUNMatrix, N_Vector x, N_Vector b, double) {
  SecondOrderLinearSolver* me = self(solver);
  try {
    const NewtonData data = me->newton_data_();
    // Refactor when the contact phase changed or γ moved by more than 20 % from the factored
    // value (the policy of CVODE's own matrix-based path): a modestly stale Newton matrix still
    // converges quickly, a badly stale one does not.
    // Extra states (Bouc–Wen's z) change J sharply where a drift rate turns: J is evaluated anew
    // at every new step attempt (t), which costs little next to the steps it saves.
    const bool new_step = me->m_ > 0 && data.t_s != me->factored_t_s_;
    if (me->stale_ || new_step || std::abs(data.gamma - me->gamma_) > kGammaTolerance * std::abs(me->gamma_)) {
      me->factor(data);
    }
    const Eigen::Index n = me->n_;
    const auto rhs = view(b);
    auto out = view(x);
    const double g = me->gamma_;  // solve the system that was factored, consistently
    if (me->sparse_) {
      const Eigen::Index m = me->m_;
      Eigen::VectorXd right = rhs.segment(n, n) + g * (me->sparse_rows_.leftCols(n) * rhs.head(n));
      Eigen::VectorXd w_part;  // D⁻¹ b₃
      if (m > 0) {
        w_part = me->w_factor_.cwiseProduct(rhs.tail(m));
        right += g * (me->accel_by_w_ * w_part);
      }
      const Eigen::VectorXd x2 = me->sparse_reduced_.solve(right);
      // x may alias b: b₁ and b₃ are read before x₁ and x₃ are written.
      if (m > 0) out.tail(m) = w_part + g * me->w_factor_.cwiseProduct(me->w_rate_by_velocity_ * x2);
      out.head(n) = rhs.head(n) + g * x2;
      out.segment(n, n) = x2;
      return SUNLS_SUCCESS;
    }
    if (me->diagonal_) {
      // x may alias b: x₂ first from b, then x₁ from b₁ and x₂.
      out.tail(n) =
          (rhs.tail(n).array() + g * me->a21_diagonal_.array() * rhs.head(n).array()) / me->reduced_diagonal_.array();
      out.head(n) = rhs.head(n) + g * out.tail(n);
      return SUNLS_SUCCESS;
    }
    const Eigen::VectorXd x2 =
        me->reduced_.solve(rhs.tail(n) + g * (me->jacobian_.bottomLeftCorner(n, n) * rhs.head(n)));
    out.head(n) = rhs.head(n) + g * x2;
    out.tail(n) = x2;
    return SUNLS_SUCCESS;
  } catch (const std::exception& error) {
    me->error_sink_ = std::string("linear solve: ") + error.what();
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int SecondOrderLinearSolver::release(SUNLinearSolver solver) {
  solver->content = nullptr;  // owned by the C++ object, not by SUNDIALS
  SUNLinSolFreeEmpty(solver);
  return SUNLS_SUCCESS;
}

}  // namespace pounding::solvers
