#pragma once
// The event-driven run's largest step (s), re-evaluated after every step and event. Three rules:
//  - the automatic bound (EventOptions::max_step_s = 0): a 1/steps_per_period of the shortest
//    damped period among the modes that move some gap (GapModeBound), so no gap rate changes sign
//    twice inside a step unseen; or the fixed max_step_s;
//  - in free flight with clearance steps on: as far as every watched gap provably stays above the
//    touch band (GapClearance), up to the next record sample; nothing inside such a step needs
//    examining (open_until_s);
//  - a masked pair in flight back towards its floor: a quarter of the predicted time until it
//    gets there, (g − floor) + ġτ + ½g̈τ² = 0, so the interpolant that locates the re-closure
//    spans a short stretch of a smooth flight.

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/contact_states.hpp"
#include "pounding/solvers/gap_clearance.hpp"
#include "pounding/solvers/gap_mode_bound.hpp"

namespace pounding::solvers {

struct EventOptions;

class EventStepBound {
 public:
  /// g̈ of candidate i (m/s²) in the state last passed to max_step_s, with its contact forces.
  using GapAcceleration = std::function<double(std::size_t i)>;

  /// @throws as GapModeBound for invalid options (validated by EventOptions::validate()).
  EventStepBound(const dynamics::CoupledSystem& system, const EventOptions& options);

  /// Turns on clearance steps (EventOptions::clearance_steps). @return the shortest damped period
  /// (s) of the buildings: such steps span whole record intervals. @throws std::runtime_error if a
  /// building's damping is not classical.
  double enable_clearance();

  /// The bound from (t, y), whose gaps are `gaps`; `gap_acceleration` is asked only for masked
  /// pairs in flight; `cover` says which corner candidates are armed. Sets open_until_s().
  double max_step_s(double t, const Eigen::VectorXd& y, const std::vector<contact::GapState>& gaps,
                    const ContactStates& states, const CornerCover& cover, const GapAcceleration& gap_acceleration);

  /// The time (s) up to which the last max_step_s proved every watched gap open (−∞: none).
  double open_until_s() const { return open_until_s_; }

 private:
  double clear_step_s(double t, const Eigen::VectorXd& y, const ContactStates& states, const CornerCover& cover);

  const dynamics::CoupledSystem& system_;
  const EventOptions& options_;
  std::optional<GapModeBound> mode_bound_;  // when max_step_s is automatic
  std::optional<GapClearance> clearance_;   // when clearance steps apply
  std::vector<bool> watched_;               // scratch: the candidates clearance_ watches
  double open_until_s_ = -std::numeric_limits<double>::infinity();
};

}  // namespace pounding::solvers
