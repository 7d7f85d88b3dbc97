// SecondOrderLinearSolver's solves of the Newton system (I − γJ) x = b, J = [[0, I], [A21, A22]],
// against an independent dense LU of the whole 2n × 2n matrix, on both of its paths: the dense
// Jacobian and the sparse rows [A21, A22] (OdeFunctions::acceleration_jacobian). The system is a
// chain of masses (A21, A22 tridiagonal, like a building's storeys) with one long-range coupling
// (like a held contact between the two buildings), so neither path can lean on a band; the dense
// path's diagonal case is a set of uncoupled oscillators (modal free flight). Then when J is
// evaluated: once per linear phase whatever γ does, at every refactorisation otherwise.

#include <boost/test/unit_test.hpp>

#include <Eigen/LU>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pounding/solvers/second_order_solver.hpp"

using namespace pounding::solvers;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr int kDof = 12;

/// J's lower half: springs k_i and dampers c_i between neighbours, unit masses, and (when
/// `long_range`) a spring between the first and the last mass.
MatrixXd acceleration_rows(bool long_range = true) {
  MatrixXd stiffness = MatrixXd::Zero(kDof, kDof), damping = MatrixXd::Zero(kDof, kDof);
  auto link = [](MatrixXd& m, int i, int j, double value) {
    m(i, i) += value;
    m(j, j) += value;
    m(i, j) -= value;
    m(j, i) -= value;
  };
  for (int i = 0; i + 1 < kDof; ++i) {
    link(stiffness, i, i + 1, 100.0 + 10.0 * i);
    link(damping, i, i + 1, 0.5 + 0.1 * i);
  }
  stiffness(0, 0) += 50.0;  // the ground
  if (long_range) link(stiffness, 0, kDof - 1, 30.0);
  MatrixXd rows(kDof, 2 * kDof);
  rows << -stiffness, -damping;
  return rows;
}

/// J's lower half for uncoupled oscillators, −ω² and −2ζω on the diagonals (modal coordinates).
MatrixXd modal_rows() {
  const VectorXd omega = VectorXd::LinSpaced(kDof, 2.0, 90.0);
  MatrixXd rows = MatrixXd::Zero(kDof, 2 * kDof);
  rows.leftCols(kDof).diagonal() = -omega.array().square();
  rows.rightCols(kDof).diagonal() = -2.0 * 0.05 * omega;
  return rows;
}

class Chain final : public OdeFunctions {
 public:
  explicit Chain(bool sparse, MatrixXd rows = acceleration_rows()) : sparse_(sparse), rows_(std::move(rows)) {}
  /// A new phase: with or without the long-range spring (a different sparsity pattern).
  void set_long_range(bool long_range) { rows_ = acceleration_rows(long_range); }
  /// New values of J: a new phase, or the state-dependent J of a nonlinear one.
  void set_rows(MatrixXd rows) { rows_ = std::move(rows); }
  void set_linear(bool linear) { linear_ = linear; }
  /// How many times J was handed out (as the dense matrix or as the sparse rows).
  int evaluations() const { return evaluations_; }
  int state_size() const override { return 2 * kDof; }
  bool is_linear() const override { return linear_; }
  int root_count() const override { return 1; }
  void rhs(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    const VectorXd accelerations = rows_ * y;
    y_dot << y.tail(kDof), accelerations;
  }
  void jacobian(double, const Eigen::Ref<const VectorXd>&, Eigen::Ref<MatrixXd> jac) override {
    ++evaluations_;
    jac = full();
  }
  void roots(double, const Eigen::Ref<const VectorXd>&, Eigen::Ref<VectorXd> g) override { g.setOnes(); }
  bool acceleration_jacobian(double, const Eigen::Ref<const VectorXd>&, Eigen::SparseMatrix<double>& rows) override {
    if (!sparse_) return false;
    ++evaluations_;
    rows = rows_.sparseView();
    return true;
  }
  MatrixXd full() const {
    MatrixXd j = MatrixXd::Zero(2 * kDof, 2 * kDof);
    j.topRightCorner(kDof, kDof).setIdentity();
    j.bottomRows(kDof) = rows_;
    return j;
  }

 private:
  bool sparse_;
  MatrixXd rows_;
  bool linear_ = false;
  int evaluations_ = 0;
};

/// The solver on `chain` through its SUNDIALS interface, at the γ set in `gamma`.
struct Newton {
  explicit Newton(Chain& chain)
      : context(pounding::solvers::sundials::make_context()),
        state(pounding::solvers::sundials::make_vector(2 * kDof, context.get())),
        x(pounding::solvers::sundials::make_vector(2 * kDof, context.get())),
        solver(
            chain,
            [this] {
              return NewtonData{0.0, state.get(), gamma};
            },
            context.get(), error) {
    N_VConst(0.0, state.get());
  }
  /// x solving (I − γJ) x = b, x aliasing b as CVODE does.
  VectorXd solve(const VectorXd& b) {
    Eigen::Map<VectorXd>(N_VGetArrayPointer(x.get()), 2 * kDof) = b;
    BOOST_TEST_REQUIRE(SUNLinSolSolve(solver.get(), nullptr, x.get(), x.get(), 0.0) == SUNLS_SUCCESS, error);
    return Eigen::Map<VectorXd>(N_VGetArrayPointer(x.get()), 2 * kDof);
  }

  pounding::solvers::sundials::Context context;
  pounding::solvers::sundials::Vector state, x;
  std::string error;
  double gamma = 0.0;
  SecondOrderLinearSolver solver;
};

/// The solution of (I − γJ) x = b by a dense LU of the whole 2n × 2n matrix.
VectorXd expected_solution(const Chain& chain, double gamma, const VectorXd& b) {
  return (MatrixXd::Identity(2 * kDof, 2 * kDof) - gamma * chain.full()).partialPivLu().solve(b);
}

/// x solving (I − γJ) x = b through the solver's SUNDIALS interface, x aliasing b as CVODE does.
VectorXd solve(Chain& chain, double gamma, const VectorXd& b) {
  pounding::solvers::sundials::Context context = pounding::solvers::sundials::make_context();
  pounding::solvers::sundials::Vector state = pounding::solvers::sundials::make_vector(2 * kDof, context.get());
  pounding::solvers::sundials::Vector x = pounding::solvers::sundials::make_vector(2 * kDof, context.get());
  N_VConst(0.0, state.get());
  std::string error;
  SecondOrderLinearSolver solver(
      chain,
      [&] {
        return NewtonData{0.0, state.get(), gamma};
      },
      context.get(), error);
  Eigen::Map<VectorXd>(N_VGetArrayPointer(x.get()), 2 * kDof) = b;
  const int flag = SUNLinSolSolve(solver.get(), nullptr, x.get(), x.get(), 0.0);
  BOOST_TEST_REQUIRE(flag == SUNLS_SUCCESS, error);
  BOOST_TEST(solver.factorizations() == 1);
  return Eigen::Map<VectorXd>(N_VGetArrayPointer(x.get()), 2 * kDof);
}

}  // namespace

BOOST_AUTO_TEST_CASE(BothPathsSolveTheNewtonSystemToRoundOff) {
  const VectorXd b = VectorXd::LinSpaced(2 * kDof, -1.0, 2.0).array().sin();
  for (double gamma : {1e-4, 1e-2, 0.3}) {
    Chain dense(false), sparse(true);
    const MatrixXd newton = MatrixXd::Identity(2 * kDof, 2 * kDof) - gamma * dense.full();
    const VectorXd expected = newton.partialPivLu().solve(b);
    // Round-off of two LU solves of a matrix whose condition number is below 1e4 here.
    const double allowed = 1e-12 * expected.norm();
    BOOST_TEST((solve(dense, gamma, b) - expected).norm() <= allowed, "dense, gamma " << gamma);
    BOOST_TEST((solve(sparse, gamma, b) - expected).norm() <= allowed, "sparse, gamma " << gamma);
    BOOST_TEST((newton * solve(sparse, gamma, b) - b).norm() <= allowed * newton.norm(), "residual, gamma " << gamma);
  }
}

BOOST_AUTO_TEST_CASE(RefactorsCorrectlyWhenThePatternChangesAndChangesBack) {
  // The sparse path orders a pattern once and reuses the ordering while it stays the same: each
  // phase's solve must still be that phase's, through a change of pattern and back.
  pounding::solvers::sundials::Context context = pounding::solvers::sundials::make_context();
  pounding::solvers::sundials::Vector state = pounding::solvers::sundials::make_vector(2 * kDof, context.get());
  pounding::solvers::sundials::Vector x = pounding::solvers::sundials::make_vector(2 * kDof, context.get());
  N_VConst(0.0, state.get());
  Chain chain(true);
  const double gamma = 0.05;
  std::string error;
  SecondOrderLinearSolver solver(
      chain,
      [&] {
        return NewtonData{0.0, state.get(), gamma};
      },
      context.get(), error);
  const VectorXd b = VectorXd::LinSpaced(2 * kDof, 0.5, 3.0).array().cos();
  for (bool long_range : {true, false, false, true}) {
    chain.set_long_range(long_range);
    solver.invalidate();
    const VectorXd expected = (MatrixXd::Identity(2 * kDof, 2 * kDof) - gamma * chain.full()).partialPivLu().solve(b);
    Eigen::Map<VectorXd>(N_VGetArrayPointer(x.get()), 2 * kDof) = b;
    BOOST_TEST_REQUIRE(SUNLinSolSolve(solver.get(), nullptr, x.get(), x.get(), 0.0) == SUNLS_SUCCESS, error);
    const VectorXd actual = Eigen::Map<VectorXd>(N_VGetArrayPointer(x.get()), 2 * kDof);
    BOOST_TEST((actual - expected).norm() <= 1e-12 * expected.norm(), "long-range spring " << long_range);
  }
  BOOST_TEST(solver.factorizations() == 4);
}

BOOST_AUTO_TEST_CASE(ALinearPhaseEvaluatesItsJacobianOnceWhateverGammaDoes) {
  // Each γ is more than 20 % from the last, so every solve refactors; each must solve its own γ's
  // system from the one J evaluated at the phase's first factorisation, on all three paths.
  const VectorXd b = VectorXd::LinSpaced(2 * kDof, -2.0, 1.0).array().sin();
  const std::vector<double> gammas = {1e-3, 3e-2, 1e-4, 0.2, 1e-2};
  for (auto [sparse, rows, path] :
       {std::tuple{true, acceleration_rows(), "sparse"}, std::tuple{false, acceleration_rows(), "dense"},
        std::tuple{false, modal_rows(), "dense diagonal"}}) {
    Chain chain(sparse, rows);
    chain.set_linear(true);
    Newton newton(chain);
    for (double gamma : gammas) {
      newton.gamma = gamma;
      const VectorXd expected = expected_solution(chain, gamma, b);
      // Round-off of two LU solves of a matrix whose condition number is below 1e4 here.
      BOOST_TEST((newton.solve(b) - expected).norm() <= 1e-12 * expected.norm(), path << ", gamma " << gamma);
    }
    BOOST_TEST(newton.solver.factorizations() == static_cast<long>(gammas.size()), path);
    BOOST_TEST(chain.evaluations() == 1, path);
    BOOST_TEST(newton.solver.jacobian_evaluations() == 1, path);
  }
}

BOOST_AUTO_TEST_CASE(ANewLinearPhaseEvaluatesItsOwnJacobian) {
  // invalidate() (the integrator's restart) starts a phase: its J, not the last phase's, even
  // when both are linear and the sparsity pattern is the same.
  const VectorXd b = VectorXd::LinSpaced(2 * kDof, 0.5, 3.0).array().cos();
  for (bool sparse : {true, false}) {
    Chain chain(sparse, acceleration_rows());
    chain.set_linear(true);
    Newton newton(chain);
    newton.gamma = 0.05;
    newton.solve(b);
    chain.set_rows(2.0 * acceleration_rows());
    newton.solver.invalidate();
    const VectorXd expected = expected_solution(chain, newton.gamma, b);
    BOOST_TEST((newton.solve(b) - expected).norm() <= 1e-12 * expected.norm(), "sparse " << sparse);
    BOOST_TEST(chain.evaluations() == 2, "sparse " << sparse);
  }
}

BOOST_AUTO_TEST_CASE(ANonlinearPhaseEvaluatesItsJacobianAtEveryRefactorisation) {
  // A held or compliant contact's J depends on the state: within one phase (no invalidate) each
  // refactorisation for a new γ must see J as it is now.
  const VectorXd b = VectorXd::LinSpaced(2 * kDof, -1.0, 2.5).array().sin();
  for (bool sparse : {true, false}) {
    Chain chain(sparse, acceleration_rows());
    Newton newton(chain);
    const std::vector<double> gammas = {1e-2, 1e-3, 5e-2};
    for (std::size_t k = 0; k < gammas.size(); ++k) {
      chain.set_rows((1.0 + 0.5 * static_cast<double>(k)) * acceleration_rows());  // the state moved
      newton.gamma = gammas[k];
      const VectorXd expected = expected_solution(chain, newton.gamma, b);
      BOOST_TEST((newton.solve(b) - expected).norm() <= 1e-12 * expected.norm(), "sparse " << sparse << ", step " << k);
    }
    BOOST_TEST(chain.evaluations() == static_cast<int>(gammas.size()), "sparse " << sparse);
    BOOST_TEST(newton.solver.jacobian_evaluations() == newton.solver.factorizations(), "sparse " << sparse);
  }
}
