#pragma once
// The yielding column springs' branches during an event-driven run (dynamics/yielding_springs.hpp),
// their transitions at the roots of their witnesses, and what the outputs need of them: each
// spring's peak drift, first yield, yield count, dissipated (hysteretic) energy and final drift
// and slip. Transitions:
//   elastic  → yielding ±  where |d − s| reaches d_y with the drift moving outwards;
//   yielding → elastic     where the drift rate turns (ḋ = 0), keeping the slip s = d ∓ d_y.
// A yielding phase dissipates (1 − α) k d_y |Δs| (the plastic part's constant force times its
// slip), added when it ends. A smooth (Bouc–Wen) spring has no branches: its one event is its
// first yield (|d| reaching d_y outwards), and its dissipation is integrated with the energy
// audit (EnergyBalance) and handed to finish(). A spring whose column has a shear capacity V_c
// (YieldingSpring::shear_capacity_kN) and whose YieldStates locates shear failures adds the root
// of (V_c − |F|)/k to its witness, until |F| first reaches V_c: that instant is its shear failure,
// where a spring that loses its stiffness (YieldingSpring::loses_stiffness) goes to the failed
// branch for good. A degrading (IMK) spring's law (dynamics::ImkPeakOriented) lives here: at each
// root of its witness it takes the branch changes the motion makes (ImkPeakOriented::advance) and
// hands its new line to the state; it dissipates its work less ½F²/K_u, all of it once failed
// (the law's failure sends it to the failed branch for good, at SpringResult::degrading_failure_t_s).

#include <Eigen/Core>
#include <cmath>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "pounding/dynamics/yielding_springs.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// A run's end called for by its yielding columns: its status and what the detail names (the
/// building, storey, column and direction, and the instant).
struct YieldingStop {
  RunStatus status = RunStatus::collapse;  // collapse, or event_limit (a spring chattering)
  std::string detail;
};

class YieldStates {
 public:
  /// @pre `springs` outlives this. `max_switches_per_s`: a spring switching more often than this
  /// within one simulated second is chattering (chattering()). `locate_shear_failures`: the
  /// witnesses also mark where a column's force first reaches its shear capacity.
  YieldStates(const dynamics::YieldingSprings& springs, double max_switches_per_s, bool locate_shear_failures = false);

  bool empty() const { return springs_.empty(); }
  std::size_t size() const { return springs_.size(); }
  /// The states for the system's functions: nullptr when nothing yields (the elastic path).
  const dynamics::SpringStates* states() const { return springs_.empty() ? nullptr : &states_; }
  /// A spring on a yielding branch, or failed: its force then moves with q.
  bool any_yielding() const { return yielding_ > 0 || failed_ > 0; }
  /// Spring j's witness in y: its branch's (YieldingSprings::witness; a smooth spring's is
  /// d_y − |d| until it first yields, then 1), or, while its shear failure is watched for and
  /// nearer, (V_c − |F|)/k (m).
  double witness(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const;

  /// At an event at (t, y), ẏ = y_dot (on the present branches): switches every spring whose
  /// witness is at or below zero (the flagged ones and any that crossed with them by rounding)
  /// if its motion goes on past the switch: outwards from the yield drift (a drift rate, or at
  /// zero rate an acceleration, pointing out), back from a yielding branch (the drift rate
  /// turned, unless at zero rate the acceleration reloads it). A smooth spring
  /// moving outwards at its first yield counts too (it is the integrator's to restart). Notes,
  /// first, the shear failure of every watched spring whose force has reached its capacity.
  /// @return the number switched.
  int switch_branches(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& y_dot);
  /// Whether spring j's column has failed in shear (its sway shear reached its capacity) or lost
  /// its stiffness.
  bool failed_in_shear(std::size_t j) const {
    return !std::isnan(results_[j].shear_failure_t_s) || states_[j].branch == dynamics::SpringBranch::failed;
  }
  /// Spring j's column, failed in shear at (t, y) by its sway or under a slab's push with it
  /// (docs/model.md §6b), loses its stiffness: its shear_failure_t_s and the failed branch (a
  /// restart follows: the event's). @pre springs()[j].loses_stiffness, !failed_in_shear(j).
  void lose_stiffness(std::size_t j, double t, const Eigen::VectorXd& y);
  /// The first spring that switched more than max_switches_per_s times within one simulated
  /// second (a drift rate held at round-off on the yield drift), if any.
  std::optional<std::size_t> chattering() const { return chattering_; }
  /// Tracks the peak drifts at a state the run passed through (step ends, events). @return the
  /// index of a spring whose drift passed kCollapseDriftRatio of its storey height, if one did.
  std::optional<std::size_t> observe(const Eigen::VectorXd& y);
  /// Why a run must end for its columns at (t, y), if it must: a drift past kCollapseDriftRatio
  /// of its storey (collapse; observe() tracks the peaks), else a spring chattering (event_limit).
  /// `building_names`: by the springs' building index.
  std::optional<YieldingStop> stop(double t, const Eigen::VectorXd& y, const std::vector<std::string>& building_names);
  /// The per-spring results at the run's end (ending the yielding phases in progress), and the
  /// energy they dissipated (kJ). `smooth_dissipated_kJ`: per spring, what the audit integrated
  /// for the smooth ones (EnergyBalance::smooth_dissipated_kJ).
  std::vector<SpringResult> finish(const Eigen::VectorXd& y, const std::vector<double>& smooth_dissipated_kJ,
                                   double& hysteretic_kJ);

 private:
  /// Degrading spring j's branch changes at (t, y) with drift rate `rate_mps` and drift
  /// acceleration `accel_mps2`. @return whether its branch changed.
  bool advance_degrading(std::size_t j, double t, const Eigen::VectorXd& y, double rate_mps, double accel_mps2);
  /// Spring j's state from its law's present line (or the failed branch): keeps yielding_ counting
  /// the springs whose force moves with q other than at k.
  void take_line(std::size_t j);
  /// Ends a yielding phase of spring j at slip `slip_m`: adds its dissipation.
  void end_yielding(std::size_t j, double slip_m);
  double branch_witness(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const;
  /// Spring j's column loses its stiffness at y: a yielding phase in progress ends, and the energy
  /// the spring holds, ½ α k d² + ½ (1 − α) k (d − s)², counts as dissipated (hysteretic).
  void fail(std::size_t j, const Eigen::VectorXd& y);
  /// Spring j has a shear capacity its force has not reached yet, and failures are located.
  bool watches_capacity(std::size_t j) const;
  double capacity_witness(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const;

  const dynamics::YieldingSprings& springs_;
  dynamics::SpringStates states_;
  std::vector<SpringResult> results_;
  /// Records a switch of spring j at t for the chattering check.
  void count_switch(std::size_t j, double t);

  std::vector<std::optional<dynamics::ImkPeakOriented>> laws_;  // degrading springs' laws (empty: none)
  std::vector<double> phase_start_slip_m_;                      // the slip where the current yielding phase began
  int yielding_ = 0;                                            // springs on a yielding branch
  int failed_ = 0;                                              // springs whose column failed and lost its stiffness
  double max_switches_per_s_;
  bool locate_shear_failures_;
  std::vector<std::deque<double>> recent_switches_s_;  // per spring, its switches within the last second
  std::optional<std::size_t> chattering_;
};

}  // namespace pounding::solvers
