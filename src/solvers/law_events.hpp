#pragma once
// The event-driven run's two contact-law policies (internal to src/solvers). The loop (the
// Simulator, driving the event-driven system of event_driven.cpp) finds the events and owns the
// integrator; a policy decides what an event does to the contacts and the velocities:
//   ImpulseEvents (impulse_events.cpp): velocity jumps solved per level as one complementarity
//     problem, slow separations held closed by a constraint force, holds released on a tensile
//     force or a slide off the edge;
//   CompliantEvents (compliant_events.cpp): a force while the slabs overlap (kelvin, hertzdamp,
//     jankowski), integrated with the motion; contacts begin, release and end at roots.

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/contact_states.hpp"
#include "pounding/solvers/event_options.hpp"
#include "pounding/solvers/recorder.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

/// What a policy works on: the run's system, options, contact states, recorder and result.
struct EventContext {
  const dynamics::CoupledSystem& system;
  const EventOptions& options;
  ContactStates& states;
  const CornerCover& cover;  // covered and live candidates, and the corner links
  Recorder& recorder;
  RunResult& result;
  /// The yielding springs' branches for the system's functions (null: every column elastic).
  const dynamics::SpringStates* springs;
  /// The run's ẏ at (t, y), with the present holds and contact forces.
  std::function<void(double, const dynamics::VectorXd&, Eigen::Ref<dynamics::VectorXd>)> derivative;
  /// Whether yielding spring j's column has failed in shear (YieldStates::failed_in_shear).
  std::function<bool(std::size_t j)> spring_failed;
  /// Spring j's column, failed in shear at (t, y) under a slab's push, loses its stiffness
  /// (YieldStates::lose_stiffness).
  std::function<void(std::size_t j, double t, const dynamics::VectorXd& y)> lose_stiffness;

  /// Masks candidate i until its gap exceeds reopen_m, with a root at its floor.
  void mask(std::size_t i, double reopen_m, const dynamics::VectorXd& y) const {
    states.mask(i, reopen_m, system.gap(y, i).gap_m);
  }
  /// The vertex of candidate i crossed the extension of its edge, not the edge: no contact.
  void passed_beside_edge(std::size_t i) const {
    states.mask_beside_edge(i, options.reopen_gap_m);
    ++result.statistics.off_segment_crossings;
  }
  /// Whether candidate i, whose root fired (or whose closing a scan found) in state y with gap
  /// state s, is a contact there (docs/model.md §5a, "inside means inside"): its vertex over its
  /// edge, and either at the edge's line (within the touch band: a crossing) or, found deeper,
  /// inside the other slab with this edge the nearest. A vertex behind the line of a side edge
  /// but on the other slab's facade (a floor root or a scan that found it there) touches nothing.
  bool meets(std::size_t i, const dynamics::VectorXd& y, const contact::GapState& s) const {
    if (!s.on_segment()) return false;
    if (s.gap_m >= -options.contact_tolerance_m) return !slides_along_face(i, y, s);
    return inside_across_edge(s.gap_m, system.depth_inside_m(y, i, s));
  }
  /// Whether candidate i's vertex, at its edge's line near an end, lies on the line of the struck
  /// slab's edge round that end, without closing on it, where that edge and an edge of the vertex's
  /// own slab face each other: the vertex slides along the face where the slabs meet, on the
  /// struck slab's outline, and enters it across neither edge.
  bool slides_along_face(std::size_t i, const dynamics::VectorXd& y, const contact::GapState& s) const;
  /// Notes candidate i's overlap in state y (its gap state s) if its vertex lies inside the other
  /// slab: behind its edge's line is inside only within the slab's outline (not for a corner
  /// beside the slab's end), and there no deeper than the vertex's distance to the nearest edge.
  void note_overlap(double t, const dynamics::VectorXd& y, std::size_t i, const contact::GapState& s) const {
    if (!(s.gap_m < -result.statistics.max_interpenetration_m)) return;
    const double overlap_m =
        noted_overlap_m(s.gap_m, options.contact_tolerance_m, [&] { return system.depth_inside_m(y, i, s); });
    if (!std::isnan(overlap_m)) result.statistics.note_overlap(overlap_m, t, i);
  }
  /// The candidate that carries on contact i (held, or a compliant one still overlapping), whose
  /// point has just slid off the end of its edge, in state y (docs/model.md §5a): the twin at
  /// that end if its corner lies on its own edge and in contact there, else the next edge round
  /// that end if the point lies on it and in contact; none if the contact ends. "In contact":
  /// overlapping (g < 0) for a compliant law, within the touch band for a hold. "On its edge":
  /// within twice the contact's depth plus the touch band of it, the distance the slabs' relative
  /// rotation can put between a corner and the point passing it.
  std::optional<std::size_t> successor(std::size_t i, const dynamics::VectorXd& y, bool compliant) const;
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
  /// EventContext::meets, for the loop's checks after a step.
  bool meets(std::size_t i, const dynamics::VectorXd& y, const contact::GapState& s) const {
    return context_.meets(i, y, s);
  }
  /// EventContext::note_overlap, for the loop's checks after a step.
  void note_overlap(double t, const dynamics::VectorXd& y, std::size_t i, const contact::GapState& s) const {
    context_.note_overlap(t, y, i, s);
  }

 protected:
  // What both laws work on, by the names their functions use.
  EventContext context_;
  const dynamics::CoupledSystem& system_;
  const EventOptions& options_;
  ContactStates& states_;
  Recorder& recorder_;
  RunResult& result_;
};

/// Whether some compliant slab-to-column candidate's column has a shear capacity along the plan
/// axis nearer its edge's normal, so that its shear with the sway is watched (Witness::column).
bool watches_struck_columns(const dynamics::CoupledSystem& system, const EventOptions& options);

std::unique_ptr<LawEvents> make_impulse_events(const EventContext& context);
std::unique_ptr<LawEvents> make_compliant_events(const EventContext& context);

}  // namespace pounding::solvers
