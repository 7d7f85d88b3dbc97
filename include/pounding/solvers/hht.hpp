#pragma once
// The published reference scheme (docs/model.md §8): HHT-α time stepping with fixed Δt, contacts
// checked at step ends, and the step repeated with Δt/2, Δt/4, … when a slab overlaps another,
// until the end state is in contact within a tolerance; then the impact law, and on with Δt.
// Also the variants users compare against: impacts at the end of the overlapping step (no
// halving), and the contact instant found on the step's cubic Hermite interpolant.

#include <Eigen/Cholesky>
#include <array>
#include <functional>
#include <map>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/run_budget.hpp"
#include "pounding/solvers/run_result.hpp"
#include "pounding/solvers/run_sink.hpp"

namespace pounding::solvers {

/// HHT-α for M q̈ + C q̇ + K q = f(t), M diagonal, α ∈ [−1/3, 0]:
///   M a₁ + (1+α)(C v₁ + K d₁) − α(C v₀ + K d₀) = (1+α) f(t₁) − α f(t₀)
/// with the Newmark updates d₁ = d₀ + h v₀ + h²((½ − β) a₀ + β a₁), v₁ = v₀ + h((1 − γ) a₀ + γ a₁),
/// β = (1 − α)²/4, γ = (1 − 2α)/2. The effective matrix M + (1+α)γh C + (1+α)βh² K is factorised
/// once per step size and reused.
class HhtStepper {
 public:
  struct State {
    double t_s = 0.0;
    Eigen::VectorXd d, v, a;  // displacements, velocities, accelerations
  };
  using Force = std::function<void(double, Eigen::Ref<Eigen::VectorXd>)>;

  /// @pre mass > 0, damping and stiffness symmetric, stiffness positive definite, α ∈ [−1/3, 0].
  HhtStepper(Eigen::VectorXd mass_diagonal, Eigen::MatrixXd damping, Eigen::MatrixXd stiffness, Force force,
             double alpha);

  /// The state (t, d, v) with the acceleration that satisfies the equation of motion.
  State at(double t, Eigen::VectorXd d, Eigen::VectorXd v) const;
  /// One step of size h from `from`.
  State step(const State& from, double h);
  /// The energy (kJ) the update from `from` to `to` removes: D = Δdᵀ⟨f⟩ − Δdᵀ C⟨v⟩ − Δ(½vᵀMv + ½dᵀKd),
  /// ⟨x⟩ the mean of both ends, in the closed form of the scheme (hht.cpp). 0 for α = 0 (energy
  /// conserving), > 0 on average for α < 0. @pre `to` is a step from `from` (or from() itself).
  double algorithmic_dissipation(const State& from, const State& to) const;
  long factorizations() const { return factorizations_; }

 private:
  const Eigen::LLT<Eigen::MatrixXd>& effective(double h);
  /// r = M a − (f − C v − K d): how far the scheme's acceleration is from the equation of motion.
  Eigen::VectorXd defect(const State& s) const;

  Eigen::VectorXd mass_;
  Eigen::MatrixXd damping_, stiffness_;
  Force force_;
  double alpha_, beta_, gamma_;
  std::map<double, Eigen::LLT<Eigen::MatrixXd>> factors_;  // by step size
  long factorizations_ = 0;
};

enum class HhtEventLocation {
  halving,      // the published scheme: repeat the step with half the size until in contact
  end_of_step,  // naive: the impact is applied at the end of the step in which overlap appears
  interpolate,  // the contact instant from the step's cubic Hermite interpolant, step redone to it
};

struct HhtOptions {
  double dt_s = 0.05;
  double alpha = -0.05;
  double contact_tolerance_m = 1e-4;  // |g| within which a candidate counts as in contact
  int max_halvings = 30;
  HhtEventLocation location = HhtEventLocation::halving;
  double restitution = 0.5;
  Eigen::VectorXd initial_state;    // (q, q̇) at the record's start; empty: at rest
  OutputSelection outputs;          // what the run records besides impacts and energy; default: all
  std::vector<int> history_floors;  // levels (1-based) to write; empty: every level
  std::vector<std::array<int, 2>> history_other_floors;  // as EventOptions'

  double history_interval_s = 0.01;
  /// Receives the history rows and impacts as they come (the history then holds no rows); null:
  /// the whole history is kept in the result. Must outlive the run.
  RunSink* sink = nullptr;
  long max_steps = 10'000'000;  // trial steps (halvings included) before step_limit
  RunBudget budget;             // wall time; a run also stops when interrupted
  /// @pre dt_s, contact_tolerance_m > 0, alpha ∈ [−1/3, 0], max_halvings ∈ 0..60, restitution ∈
  ///   [0, 1] (user input is checked by analysis::SolverSettings::validate() and the scene).
  /// @throws InputError naming the field for history_interval_s, max_steps, budget.
  void validate() const;
};

/// Runs the coupled system with HHT-α over the whole ground motion. Sustained contact
/// is not modelled (the published scheme has none): a pressed pair keeps taking small impacts.
/// A contact that approaches by less than a millionth of the tolerance per step is no impact.
/// Every time a pair sinks deeper than the contact tolerance at an accepted step end (halving
/// did not resolve it) is counted in `unresolved_contacts`, and the run ends with status
/// `unresolved_overlap` naming the deepest overlap; `energy.algorithmic_dissipation_kJ` sums D.
RunResult run_hht(const dynamics::CoupledSystem& system, const HhtOptions& options, const std::string& method);

}  // namespace pounding::solvers
