#define BOOST_TEST_MODULE second_order_solver
// SecondOrderLinearSolver's solves of the Newton system (I − γJ) x = b, J = [[0, I], [A21, A22]],
// against an independent dense LU of the whole 2n × 2n matrix, on both of its paths: the dense
// Jacobian and the sparse rows [A21, A22] (OdeFunctions::acceleration_jacobian). The system is a
// chain of masses (A21, A22 tridiagonal, like a building's storeys) with one long-range coupling
// (like a held contact between the two buildings), so neither path can lean on a band.

#include <boost/test/unit_test.hpp>

#include <Eigen/LU>
#include <string>

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

class Chain final : public OdeFunctions {
 public:
  explicit Chain(bool sparse) : sparse_(sparse), rows_(acceleration_rows()) {}
  /// A new phase: with or without the long-range spring (a different sparsity pattern).
  void set_long_range(bool long_range) { rows_ = acceleration_rows(long_range); }
  int state_size() const override { return 2 * kDof; }
  int root_count() const override { return 1; }
  void rhs(double, const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) override {
    const VectorXd accelerations = rows_ * y;
    y_dot << y.tail(kDof), accelerations;
  }
  void jacobian(double, const Eigen::Ref<const VectorXd>&, Eigen::Ref<MatrixXd> jac) override { jac = full(); }
  void roots(double, const Eigen::Ref<const VectorXd>&, Eigen::Ref<VectorXd> g) override { g.setOnes(); }
  bool acceleration_jacobian(double, const Eigen::Ref<const VectorXd>&, Eigen::SparseMatrix<double>& rows) override {
    if (sparse_) rows = rows_.sparseView();
    return sparse_;
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
};

/// x solving (I − γJ) x = b through the solver's SUNDIALS interface, x aliasing b as CVODE does.
VectorXd solve(Chain& chain, double gamma, const VectorXd& b) {
  pounding::solvers::sundials::Context context = pounding::solvers::sundials::make_context();
  pounding::solvers::sundials::Vector state = pounding::solvers::sundials::make_vector(2 * kDof, context.get());
  pounding::solvers::sundials::Vector x = pounding::solvers::sundials::make_vector(2 * kDof, context.get());
  N_VConst(0.0, state.get());
  std::string error;
  SecondOrderLinearSolver solver(chain, [&] { return NewtonData{0.0, state.get(), gamma}; }, context.get(), error);
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
  SecondOrderLinearSolver solver(chain, [&] { return NewtonData{0.0, state.get(), gamma}; }, context.get(), error);
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
