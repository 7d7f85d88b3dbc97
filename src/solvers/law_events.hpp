#pragma once
// The event-driven run's two contact-law policies (internal to src/solvers). The loop
// (event_driven.cpp) finds the events and owns the integrator; a policy decides what an event
// does to the contacts and the velocities:
//   ImpulseEvents (impulse_events.cpp): velocity jumps solved per level as one complementarity
//     problem, slow separations held closed by a constraint force, holds released on a tensile
//     force or a slide off the edge;
//   CompliantEvents (compliant_events.cpp): a force while the slabs overlap (kelvin, hertzdamp,
//     jankowski), integrated with the motion; contacts begin, release and end at roots.

#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/contact_states.hpp"
#include "pounding/solvers/event_driven.hpp"
#include "pounding/solvers/recorder.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// What a policy works on: the run's system, options, contact states, recorder and result.
struct EventContext {
  const dynamics::CoupledSystem& system;
  const EventOptions& options;
  ContactStates& states;
  Recorder& recorder;
  RunResult& result;
  /// The yielding springs' branches for the system's functions (null: every column elastic).
  const dynamics::SpringStates* springs;
  /// The run's ẏ at (t, y), with the present holds and contact forces.
  std::function<void(double, const dynamics::VectorXd&, Eigen::Ref<dynamics::VectorXd>)> derivative;

  /// Masks candidate i until its gap exceeds reopen_m, with a root at its floor.
  void mask(std::size_t i, double reopen_m, const dynamics::VectorXd& y) const {
    states.mask(i, reopen_m, system.gap(y, i).gap_m);
  }
  /// The vertex of candidate i crossed the extension of its edge, not the edge: no contact.
  void passed_beside_edge(std::size_t i) const {
    states.mask_beside_edge(i, options.reopen_gap_m);
    ++result.statistics.off_segment_crossings;
  }
};

/// The edge witness of a contact in state s: how far its point is from the nearer end of its edge
/// (fraction of the edge), shifted by on_segment()'s tolerance so that a contact at a corner does
/// not start at a root.
inline double edge_witness(const contact::GapState& s) {
  return std::min(s.segment_param, 1.0 - s.segment_param) + contact::kOnSegmentTolerance;
}

/// Interpolates the state at a time inside the last step.
using StateInterpolant = std::function<void(double t_s, dynamics::VectorXd& y)>;

class LawEvents {
 public:
  explicit LawEvents(const EventContext& context)
      : context_(context),
        system_(context.system),
        options_(context.options),
        states_(context.states),
        recorder_(context.recorder),
        result_(context.result) {}
  virtual ~LawEvents() = default;
  /// Adds the acting contacts' forces to ẏ (the holds are the system's constraint).
  virtual void add_forces(const Eigen::Ref<const dynamics::VectorXd>& y,
                          Eigen::Ref<dynamics::VectorXd> y_dot) const = 0;
  /// Adds their slopes to the acceleration rows of the Jacobian.
  virtual void add_force_jacobian(const Eigen::Ref<const dynamics::VectorXd>& y,
                                  Eigen::SparseMatrix<double>& rows) const = 0;
  /// Writes the force and edge witnesses (and a compliant contact's gap witness) into g.
  virtual void write_witnesses(double t, const Eigen::Ref<const dynamics::VectorXd>& y, const WitnessLayout& layout,
                               Eigen::Ref<dynamics::VectorXd> g) const = 0;
  /// The contacts carrying a force at (t, y), for the recorder.
  virtual std::vector<ContactForce> contact_forces(double t, const dynamics::VectorXd& y) const = 0;
  /// The power (kW) of the hold constraints' forces at (t, y), for the energy audit.
  virtual double constraint_power(double t, const dynamics::VectorXd& y) const = 0;
  /// The event at t: the witnesses that crossed (at the start: the contacts already closed;
  /// after a missed contact: its gap). May change y's velocities.
  virtual void on_event(double t, dynamics::VectorXd& y, const WitnessLayout::Crossed& crossed) = 0;
  /// Integrals over the step [t_a, t_b] that ends in y_b (compliant contacts' impulse and work).
  virtual void integrate(double t_a, double t_b, const dynamics::VectorXd& y_b, const StateInterpolant& at) = 0;
  /// Bookkeeping after a step that ends at (t, y) without an event, or after an event.
  virtual void after_step(double t, const dynamics::VectorXd& y) = 0;
  /// Closes what is still open at the end of the run (t, y).
  virtual void finish(double t, const dynamics::VectorXd& y) = 0;

 protected:
  // What both laws work on, by the names their functions use.
  EventContext context_;
  const dynamics::CoupledSystem& system_;
  const EventOptions& options_;
  ContactStates& states_;
  Recorder& recorder_;
  RunResult& result_;
};

std::unique_ptr<LawEvents> make_impulse_events(const EventContext& context);
std::unique_ptr<LawEvents> make_compliant_events(const EventContext& context);

}  // namespace pounding::solvers
