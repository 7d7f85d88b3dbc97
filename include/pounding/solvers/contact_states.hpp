#pragma once
// The event-driven run's contact candidates as a state machine: which of them a root function
// watches and how, which are held closed, which carry a compliant law's force. The transitions
// are the named member functions; the run decides when each applies.
//
//   armed ──gap root, impulse law──▶ held (slow separation, pressed) or masked (bounced, grazed)
//   armed ──gap root beside the edge (its extension crossed)──▶ masked, no floor root
//   masked ──gap above its reopen level after a step──▶ armed
//   held ──tensile force, slid off the edge, separated by an impact, end of run──▶ masked
//   armed/masked ──gap root, compliant law, closing──▶ compliant ──force turns tensile──▶ released
//   released ──would push again──▶ compliant;   compliant/released ──gap opens──▶ masked
//
// Gaps in m, positive open; a masked pair's floor is the gap below which its root fires.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "pounding/contact/corners.hpp"
#include "pounding/contact/gap.hpp"

namespace pounding::solvers {

enum class ContactMode {
  armed,      // its gap is a root function: a closing is located where g = 0
  masked,     // just handled: ignored until its gap exceeds its reopen level, but a root at its floor
  held,       // sustained contact: a constraint g̈ = 0 whose force is a root function
  compliant,  // a compliant law's force acts (overlap δ = −g > 0)
  released,   // the law's force turned tensile while the slabs still overlap: they fly apart
};

class ContactStates {
 public:
  /// `count` candidates, all armed. overlap_allowance_m (> 0): how far below its gap at masking
  /// (or below zero, if it was open) a masked contact's floor root sits.
  ContactStates(std::size_t count, double overlap_allowance_m);

  std::size_t size() const { return modes_.size(); }
  ContactMode mode(std::size_t i) const { return modes_[i]; }
  bool is(std::size_t i, ContactMode mode) const { return modes_[i] == mode; }
  /// Armed or masked: no contact holds it or acts on it, its gap is watched by a root.
  bool open(std::size_t i) const { return modes_[i] == ContactMode::armed || modes_[i] == ContactMode::masked; }
  /// Held candidates, in the order they were held: the rows of the hold constraint.
  const std::vector<std::size_t>& held() const { return held_; }
  /// Compliant candidates whose force acts, in the order they began acting.
  const std::vector<std::size_t>& acting() const { return acting_; }
  /// Nothing held and no force acting: the motion is the buildings' own, linear one.
  bool free_motion() const { return held_.empty() && acting_.empty(); }

  /// The root function of candidate i's gap in the state where its gap is `gap_m`: the gap itself
  /// while armed, its height above the floor while masked with one, +1 (never crossing) otherwise.
  double gap_witness(std::size_t i, double gap_m) const;
  /// The gap (m) below which masked candidate i's root fires; −∞ when it has no floor root.
  double mask_floor_m(std::size_t i) const { return mask_floor_m_[i]; }
  bool has_floor(std::size_t i) const { return mask_floor_m_[i] > -kNoFloor; }

  /// Masks i until its gap exceeds reopen_m, with a floor root overlap_allowance_m below
  /// min(gap_m, 0) so that a re-closure cannot be stepped over. From held: leaves the hold.
  void mask(std::size_t i, double reopen_m, double gap_m);
  /// Masks i without a floor root: its vertex crossed the extension of the edge, beside it, and
  /// its gap goes on falling while it passes.
  void mask_beside_edge(std::size_t i, double reopen_m);
  /// Whether masked candidate i's vertex, now on its edge, has arrived in contact there (at the
  /// edge's line, or inside the other slab with this edge the nearest: EventContext::meets).
  using Arrived = std::function<bool(std::size_t i)>;
  /// After a step: masked candidates whose gap exceeds their reopen level are armed again, and
  /// one masked beside its edge whose vertex has now arrived on the edge gets its floor root.
  void rearm(const std::vector<contact::GapState>& gaps, const Arrived& arrived);
  /// The floor roots of `rearm` alone (at a restart: nothing has reopened within no time).
  void watch_arrivals(const std::vector<contact::GapState>& gaps, const Arrived& arrived);

  /// armed/masked → held. @return false if i was already held.
  bool hold(std::size_t i);
  /// held → masked at the touch band (reopen at reopen_m). @return false if i was not held.
  bool release_hold(std::size_t i, double reopen_m, double gap_m);

  /// armed/masked → compliant (a contact's onset), or released → compliant (pushing again).
  void start_acting(std::size_t i);
  /// compliant → released: the law's force turned tensile. (A contact that is over is masked.)
  void stop_acting(std::size_t i);

 private:
  static constexpr double kNoFloor = std::numeric_limits<double>::infinity();
  void leave_lists(std::size_t i);

  double overlap_allowance_m_;
  std::vector<ContactMode> modes_;
  std::vector<double> reopen_at_m_;   // gap beyond which a masked candidate is armed again
  std::vector<double> mask_floor_m_;  // gap below which a masked candidate's root fires
  std::vector<std::size_t> held_;
  std::vector<std::size_t> acting_;
};

/// Corners (docs/model.md §5a), recomputed at every check (a phase's start, a step's end) from
/// every candidate's gap there and the contact states:
///  - a contact in progress (held, or a compliant one from onset until its gap opens) covers its
///    point's other candidates on the struck slab, and the candidates of a corner of the struck
///    slab that lies at its point (within twice its depth plus the touch band): one contact
///    there, not two;
///  - a candidate is live (its gap a root function) when it is open, not covered, and either a
///    facing one or a corner one whose vertex projects onto its edge from in front of it (g above
///    minus the touch band). A dormant corner candidate is still examined at every step's end
///    (scan_missed_contacts).
class CornerCover {
 public:
  CornerCover(const std::vector<contact::Candidate>& candidates, contact::CornerLinks links, double touch_band_m);

  void update(const std::vector<contact::GapState>& gaps, const ContactStates& states);
  bool covered(std::size_t i) const { return covered_[i]; }
  bool live(std::size_t i) const { return live_[i]; }
  const contact::CornerLinks& links() const { return links_; }
  /// Corner candidates, and how many of them were ever live.
  long corner_count() const { return corner_count_; }
  long corner_armed() const { return static_cast<long>(std::count(ever_live_.begin(), ever_live_.end(), true)); }

 private:
  void cover_group(long group);

  const std::vector<contact::Candidate>& candidates_;
  contact::CornerLinks links_;
  double touch_band_m_;
  long corner_count_ = 0;
  std::vector<bool> covered_, live_, ever_live_;
};

/// The run's root functions ("witnesses"): three blocks, one entry per candidate (four when struck
/// columns are watched), then one entry per yielding column spring (YieldStates::witness), none
/// when every column stays elastic. A function
/// that does not apply to a candidate in its mode is held at +1, so it never crosses; the
/// integrators report falling crossings only, so each is written to fall at its event.
enum class Witness {
  gap,     // armed/masked: ContactStates::gap_witness. compliant/released: the overlap −g (falls where the gap opens)
  force,   // held: the hold's force (kN). compliant/released: the law's switch function
  edge,    // held or acting: distance of the contact point from the nearer end of its edge
           // (fraction of the edge) plus on_segment()'s tolerance: falls where it slides off
  column,  // a compliant slab-to-column contact whose column has a shear capacity V_c, until the
           // column fails: (V_c − its shear with the sway)/V_c (falls where it fails); only with
           // WitnessLayout's `struck_columns`
};

class WitnessLayout {
 public:
  /// `struck_columns`: the block of Witness::column is there (some struck column is watched).
  explicit WitnessLayout(std::size_t count, std::size_t springs = 0, bool struck_columns = false)
      : count_(count), springs_(springs), blocks_(struck_columns ? 4 : 3) {}
  int size() const { return static_cast<int>(blocks_ * count_ + springs_); }
  bool has_struck_columns() const { return blocks_ == 4; }
  /// Index of candidate i's `witness` in the root vector. @pre Witness::column only with has_struck_columns().
  Eigen::Index at(Witness witness, std::size_t i) const {
    return static_cast<Eigen::Index>(static_cast<std::size_t>(witness) * count_ + i);
  }
  /// Index of yielding spring j's witness.
  Eigen::Index at_spring(std::size_t j) const { return static_cast<Eigen::Index>(blocks_ * count_ + j); }
  /// The candidates whose witnesses an integrator flagged (roots_found(): non-zero = crossed);
  /// the springs' are YieldStates::switch_branches' to find.
  struct Crossed {
    std::vector<std::size_t> gap = {}, force = {}, edge = {}, column = {};
    bool contacts() const { return !gap.empty() || !force.empty() || !edge.empty() || !column.empty(); }
  };
  Crossed crossed(const std::vector<int>& flags) const;
  bool flagged(const std::vector<int>& flags, Witness witness, std::size_t i) const {
    return flags[static_cast<std::size_t>(at(witness, i))] != 0;
  }

 private:
  std::size_t count_;
  std::size_t springs_;
  std::size_t blocks_;
};

}  // namespace pounding::solvers
