// The compliant laws' events (law_events.hpp): contacts that begin, release and end at roots,
// their force integrated with the motion.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "law_events.hpp"
#include "pounding/contact/column_contact.hpp"
#include "pounding/contact/compliant_law.hpp"
#include "pounding/solvers/floor_impacts.hpp"
#include "pounding/solvers/root_finding.hpp"

namespace pounding::solvers {

namespace {

using dynamics::VectorXd;

/// A compliant contact in progress: its law, its record and the integrals over it.
struct OpenContact {
  contact::CompliantContact law;
  ImpactRecord record;
  double work_kJ = 0.0;  // ∫F ġ dt: the contact's work on the slabs (−energy lost)
};

/// A step inside a compliant contact is integrated (Simpson) on this many pieces of its interpolant.
constexpr int kIntervals = 16;

/// The plan axis (0: x, 1: y) nearer a slab-to-column contact's normal, the force's direction:
/// the one whose capacity and sway shear its column's demands are measured along.
int capacity_axis(const contact::Candidate& c) {
  return std::abs(c.normal_rest.x()) >= std::abs(c.normal_rest.y()) ? 0 : 1;
}

/// The column a slab-to-column candidate strikes, watched against its shear capacity.
struct StruckColumn {
  int building = 0;  // 0-based
  int storey = 1;
  std::size_t column = 0;
  int axis = 0;
  double capacity_kN = 0.0;
  std::optional<std::size_t> spring;  // its yielding spring along the axis
};

/// Per candidate: its struck column when it is a slab-to-column candidate whose column has a
/// capacity along capacity_axis().
std::vector<std::optional<StruckColumn>> struck_columns(const dynamics::CoupledSystem& system) {
  std::vector<std::optional<StruckColumn>> struck(system.candidates().size());
  for (std::size_t i = 0; i < struck.size(); ++i) {
    const contact::Candidate& c = system.candidates()[i];
    // A column point needs its column (a scene's always has one; a test's may stand for it alone).
    if (!c.column || c.column_index >= system.building(c.striking_building).definition.columns.size()) continue;
    const int axis = capacity_axis(c), storey = c.lower_floor + 1;
    const double capacity_kN =
        model::column_shear_capacity_kN(system.building(c.striking_building), storey, c.column_index, axis);
    if (capacity_kN <= 0.0) continue;
    struck[i] = StruckColumn{.building = c.striking_building,
                             .storey = storey,
                             .column = c.column_index,
                             .axis = axis,
                             .capacity_kN = capacity_kN,
                             .spring = system.springs().index_of(c.striking_building, storey, c.column_index, axis)};
  }
  return struck;
}

/// A struck column's shear with its sway under a push F (kN) and the sway shear V_s in it.
struct ColumnShear {
  double total_kN = 0.0;
  double sway_kN = 0.0;
};

class CompliantEvents final : public LawEvents {
 public:
  explicit CompliantEvents(const EventContext& context)
      : LawEvents(context), open_(system_.candidates().size()), struck_(struck_columns(system_)) {
    result_.struck_columns_watched =
        std::any_of(struck_.begin(), struck_.end(), [](const auto& column) { return column.has_value(); });
  }

  void add_forces(const Eigen::Ref<const VectorXd>& y, Eigen::Ref<VectorXd> y_dot) const override {
    for (std::size_t i : states_.acting()) system_.add_contact_force(y, i, force_kN(i, y), y_dot);
  }
  void add_force_jacobian(const Eigen::Ref<const VectorXd>& y, Eigen::SparseMatrix<double>& rows) const override {
    for (std::size_t i : states_.acting()) {
      const contact::GapState s = system_.gap(y, i);
      const contact::ForceSlopes slopes = open_[i]->law.slopes(-s.gap_m, -s.gap_rate_mps);
      system_.add_contact_force_jacobian(y, i, slopes.per_overlap_kN_per_m, slopes.per_rate_kNs_per_m, rows);
    }
  }
  // From onset until its gap opens: the overlap −g (it falls through zero where the gap opens)
  // and the law's switch function; while the force acts, the edge root.
  void write_witnesses(double, const Eigen::Ref<const VectorXd>& y, const WitnessLayout& layout,
                       Eigen::Ref<VectorXd> g) const override {
    for (std::size_t i = 0; i < open_.size(); ++i) {
      if (!open_[i]) continue;
      const contact::GapState s = system_.gap(y, i);
      g[layout.at(Witness::gap, i)] = -s.gap_m;
      g[layout.at(Witness::force, i)] = open_[i]->law.switch_value(-s.gap_m, -s.gap_rate_mps);
    }
    for (std::size_t i : states_.acting()) {
      g[layout.at(Witness::edge, i)] = edge_witness(system_.gap(y, i));
      if (watches(i)) g[layout.at(Witness::column, i)] = column_witness(i, y);
    }
  }
  std::vector<ContactForce> contact_forces(double, const VectorXd& y) const override {
    std::vector<ContactForce> forces;
    for (std::size_t i : states_.acting()) forces.push_back({i, force_kN(i, y)});
    return forces;
  }
  double constraint_power(double, const VectorXd&) const override { return 0.0; }
  void on_event(double t, VectorXd& y, const WitnessLayout::Crossed& crossed) override;
  void integrate(double t_a, double t_b, const VectorXd& y_b, const StateInterpolant& at) override;
  void after_step(double, const VectorXd&) override {}
  void finish(double t, const VectorXd& y) override;

 private:
  /// The law's force of compliant contact i (kN) at δ = −g.
  double force_kN(std::size_t i, const Eigen::Ref<const VectorXd>& y) const {
    const contact::GapState s = system_.gap(y, i);
    return open_[i]->law.force_kN(-s.gap_m, -s.gap_rate_mps);
  }
  /// The rate of compliant contact i's switch function in state y (its unit per s).
  double switch_rate(double t, const VectorXd& y, std::size_t i) const {
    VectorXd y_dot(system_.state_size());
    context_.derivative(t, y, y_dot);
    const contact::GapState s = system_.gap(y, i);
    return open_[i]->law.switch_rate(-s.gap_m, -s.gap_rate_mps, -system_.gap_acceleration(y, y_dot, i));
  }
  void begin_contact(std::size_t i, double t, const VectorXd& y);
  /// Contact i's point slid off its edge's end at (t, y): candidate j carries it on, with its law
  /// and record (one contact: docs/model.md §5a). Round the corner the force may already pull
  /// (the next edge's normal has turned it): the contact is then released there at once, as at a
  /// force root, for the element cannot pull.
  void hand_over(std::size_t i, std::size_t j, double t, const VectorXd& y) {
    open_[j] = std::move(open_[i]);
    open_[i].reset();
    context_.mask(i, options_.reopen_gap_m, y);
    states_.start_acting(j);
    ++result_.statistics.corner_handovers;
    contact::CompliantContact& law = open_[j]->law;
    if (law.law() != contact::ContactLaw::jankowski && force_kN(j, y) < 0.0) {
      law.toggle();
      release(j, t, y);
      return;
    }
    fail_column_if_over(j, t, y);
  }
  /// Compliant contact i's force turned tensile at (t, y): released, the slabs flying apart while
  /// they still overlap, until the gap opens.
  void release(std::size_t i, double t, const VectorXd& y) {
    states_.stop_acting(i);
    open_[i]->record.separation_velocity_mps = system_.gap(y, i).gap_rate_mps;
    open_[i]->record.duration_s = t - open_[i]->record.t_s;
  }
  void end_contact(std::size_t i, double t, const VectorXd& y);
  /// dF/dt (kN/s) of acting contact i at (t, y), from the law's slopes and the gap's acceleration.
  double force_rate_kN_per_s(std::size_t i, double t, const VectorXd& y) const;
  /// Acting contact i's largest force in the step from t_a whose sample k (of kIntervals, h apart) is
  /// its largest: the root of its rate on the step's interpolant, where that changes sign beside k.
  void locate_peak_force(std::size_t i, double t_a, double h, int k, const StateInterpolant& at);
  /// Slab-to-column contact i pushing with `force_kN` at (t, y): its column's shear with the
  /// sway (docs/model.md §6b).
  ColumnShear column_shear(std::size_t i, const Eigen::Ref<const VectorXd>& y, double force_kN) const;
  /// The same, kept in contact i's record where it is the largest so far.
  void note_column_shear(std::size_t i, double t, const VectorXd& y, double force_kN);
  /// Whether contact i's struck column is watched against its capacity: it has one and has not
  /// failed yet (by a push or, for a yielding column, its sway).
  bool watches(std::size_t i) const {
    if (!struck_[i] || failed_.count(column_of(i)) > 0) return false;
    return !struck_[i]->spring || !context_.spring_failed(*struck_[i]->spring);
  }
  /// (V_c − its shear with the sway)/V_c for watched contact i in state y: falls where it fails.
  double column_witness(std::size_t i, const Eigen::Ref<const VectorXd>& y) const {
    return 1.0 - column_shear(i, y, std::max(0.0, force_kN(i, y))).total_kN / struck_[i]->capacity_kN;
  }
  /// Contact i's struck column has reached its capacity at (t, y): a failure, and, where its
  /// building's columns lose their stiffness, its spring's failed branch.
  void fail_column(std::size_t i, double t, const VectorXd& y);
  /// Where contact i starts to push (onset, a push again before the gap opened, a hand-over round
  /// a corner) its column's witness starts there, so no falling crossing shows a column already
  /// over its capacity (a kelvin law's first force c v, or an elastic column's sway): it fails now.
  void fail_column_if_over(std::size_t i, double t, const VectorXd& y) {
    if (watches(i) && column_witness(i, y) <= 0.0) fail_column(i, t, y);
  }
  std::array<std::size_t, 4> column_of(std::size_t i) const {
    const StruckColumn& c = *struck_[i];
    return {static_cast<std::size_t>(c.building), static_cast<std::size_t>(c.storey), c.column,
            static_cast<std::size_t>(c.axis)};
  }

  std::vector<std::optional<OpenContact>> open_;  // set from onset until the gap opens
  std::vector<std::optional<StruckColumn>> struck_;
  std::set<std::array<std::size_t, 4>> failed_;  // struck columns failed by a push: building, storey, column, axis
};

void CompliantEvents::on_event(double t, VectorXd& y, const WitnessLayout::Crossed& crossed) {
  // A root is located to the solver's tolerance on either side of zero, so after the restart the
  // same function may cross again: each root acts only if the state at it moves in the direction
  // of its switch (closing gap, falling switch function, opening gap). A column fails where its
  // witness is at or below zero (just above it, the next root finds it).
  for (std::size_t i : crossed.column) {
    if (open_[i] && states_.is(i, ContactMode::compliant) && watches(i) && column_witness(i, y) <= 0.0)
      fail_column(i, t, y);
  }
  for (std::size_t i : crossed.edge) {
    if (!states_.is(i, ContactMode::compliant)) continue;
    if (const std::optional<std::size_t> j = context_.successor(i, y, true)) {
      hand_over(i, *j, t, y);
    } else {
      end_contact(i, t, y);
    }
  }
  for (std::size_t i : crossed.force) {
    if (!open_[i] || switch_rate(t, y, i) >= 0.0) continue;
    contact::CompliantContact& law = open_[i]->law;
    const bool acted = law.acts();
    if (!acted && system_.gap(y, i).gap_m >= 0.0) continue;  // already open: the gap root ends it
    law.toggle();
    if (acted && !law.acts()) {
      release(i, t, y);  // tensile from here on
    } else if (!acted) {
      states_.start_acting(i);  // pushing again before the gap opened: the same contact goes on
      fail_column_if_over(i, t, y);
    }  // else a jankowski contact changed phase and acts on
  }
  for (std::size_t i : crossed.gap) {
    const contact::GapState s = system_.gap(y, i);
    if (states_.is(i, ContactMode::released) || states_.is(i, ContactMode::compliant)) {
      if (s.gap_rate_mps >= 0.0) end_contact(i, t, y);  // the gap opened: the contact is over
      continue;
    }
    if (!states_.open(i)) continue;
    if (!context_.meets(i, y, s)) {
      context_.passed_beside_edge(i);
    } else if (s.gap_rate_mps < 0.0) {
      begin_contact(i, t, y);
    } else if (s.gap_m <= options_.contact_tolerance_m) {
      result_.touches.push_back(touch_record(system_, t, i, s));
      context_.mask(i, options_.reopen_gap_m, y);  // grazed: armed again once clearly open
    }
  }
}

void CompliantEvents::begin_contact(std::size_t i, double t, const VectorXd& y) {
  // The effective mass and approach speed at onset, held for the contact so that the damping
  // (and the Jacobian) stay smooth.
  const contact::GapState s = system_.gap(y, i);
  open_[i].emplace(OpenContact{
      contact::CompliantContact(options_.law, options_.contact_stiffness, options_.restitution, -s.gap_rate_mps,
                                system_.normal_inverse_mass(y, i), system_.candidates()[i].flexibility_m_per_kN),
      impact_at(system_, t, i, s)});
  open_[i]->record.peak_force_kN = std::max(0.0, force_kN(i, y));
  note_column_shear(i, t, y, open_[i]->record.peak_force_kN);
  states_.start_acting(i);
  fail_column_if_over(i, t, y);
}

ColumnShear CompliantEvents::column_shear(std::size_t i, const Eigen::Ref<const VectorXd>& y, double force_kN) const {
  const contact::Candidate& c = system_.candidates()[i];
  // The force pushes the column along +n; the floors' shares N₁ F and N₂ F (column_shape) are the
  // end reactions of the fixed–fixed member, which the sway shear V_s adds to below the load and
  // takes from above it.
  const int axis = capacity_axis(c);
  const int storey = c.lower_floor + 1;
  const double sway_kN =
      system_.column_sway_shear_kN(y, c.striking_building, storey, c.column_index, axis, context_.springs);
  const std::array<double, 2> shares = contact::column_shape(c.height_ratio);
  const double along_kN = force_kN * c.normal_rest[axis];
  return {.total_kN = std::max(std::abs(sway_kN + shares[0] * along_kN), std::abs(sway_kN - shares[1] * along_kN)),
          .sway_kN = sway_kN};
}

void CompliantEvents::note_column_shear(std::size_t i, double t, const VectorXd& y, double force_kN) {
  const contact::Candidate& c = system_.candidates()[i];
  // A column point needs its column (a scene's always has one; a test's may stand for it alone).
  if (!c.column || c.column_index >= system_.building(c.striking_building).definition.columns.size()) return;
  const ColumnShear shear = column_shear(i, y, force_kN);
  ImpactRecord& r = open_[i]->record;
  if (shear.total_kN <= r.column_total_shear_kN) return;
  r.column_total_shear_kN = shear.total_kN;
  r.column_total_shear_t_s = t;
  r.column_sway_shear_kN = shear.sway_kN;
}

void CompliantEvents::fail_column(std::size_t i, double t, const VectorXd& y) {
  const StruckColumn& column = *struck_[i];
  const double force = std::max(0.0, force_kN(i, y));
  const ColumnShear shear = column_shear(i, y, force);
  const ImpactRecord& r = open_[i]->record;
  StruckColumnFailure failure{};
  static_cast<ContactIdentity&>(failure) = r;
  failure.t_s = t;
  failure.column_key = model::column_key(system_.building(column.building).definition, column.column);
  failure.column_rest = r.vertex_rest;
  failure.storey = column.storey;
  failure.axis = column.axis;
  failure.capacity_kN = column.capacity_kN;
  failure.shear_kN = shear.total_kN;
  failure.sway_shear_kN = shear.sway_kN;
  failure.force_kN = force;
  failure.sway_over_capacity = std::abs(shear.sway_kN) >= column.capacity_kN;
  failed_.insert(column_of(i));
  if (column.spring && system_.springs()[*column.spring].loses_stiffness) {
    context_.lose_stiffness(*column.spring, t, y);
    failure.loses_stiffness = true;
    ++result_.statistics.yield_events;  // a branch change, as a sway failure's
  }
  result_.struck_column_failures.push_back(std::move(failure));
}

void CompliantEvents::end_contact(std::size_t i, double t, const VectorXd& y) {
  ImpactRecord& r = open_[i]->record;
  if (states_.is(i, ContactMode::compliant)) {  // slid off the edge or the run ended while pushing
    r.separation_velocity_mps = system_.gap(y, i).gap_rate_mps;
    r.duration_s = t - r.t_s;
  }
  // What the contact took from the slabs (dissipated, or still in its spring at the run's end)
  // counts as impact loss, as an impulse's does.
  r.energy_lost_kJ = -open_[i]->work_kJ;
  if (r.column > 0) {
    const contact::Candidate& c = system_.candidates()[i];
    const contact::ColumnDemand demand = contact::column_demand(r.peak_force_kN, c.storey_height_m, c.height_ratio);
    r.column_shear_kN = demand.shear_kN;
    r.column_moment_kNm = demand.moment_kNm;
    // The capacity along the plan axis nearer the struck edge's normal (the force's direction).
    const double capacity_kN = model::column_shear_capacity_kN(system_.building(c.striking_building), c.lower_floor + 1,
                                                               c.column_index, capacity_axis(c));
    if (capacity_kN > 0.0) {
      r.column_shear_ratio = demand.shear_kN / capacity_kN;
      r.column_total_shear_ratio = r.column_total_shear_kN / capacity_kN;
    }
  }
  recorder_.add_impact_loss(r.energy_lost_kJ);
  result_.impacts.push_back(r);
  recorder_.stream_new_impacts(result_.impacts);
  open_[i].reset();
  context_.mask(i, options_.reopen_gap_m, y);
}

void CompliantEvents::integrate(double t_a, double t_b, const VectorXd& y_b, const StateInterpolant& at) {
  // Composite Simpson on the step's interpolant: its error is of the interpolant's order, far
  // below the solver tolerance for the smooth force inside a contact (no switch inside a step).
  if (states_.acting().empty() || !(t_b > t_a)) return;
  VectorXd y(system_.state_size());
  const double h = (t_b - t_a) / kIntervals;
  const std::vector<std::size_t>& acting = states_.acting();
  std::vector<int> largest(acting.size(), 0);  // the sample of each contact's largest force in the step
  std::vector<double> largest_kN(acting.size(), -std::numeric_limits<double>::infinity());
  for (int k = 0; k <= kIntervals; ++k) {
    if (k == kIntervals) {
      y = y_b;
    } else {
      at(t_a + k * h, y);
    }
    const double weight = (k == 0 || k == kIntervals ? 1.0 : k % 2 ? 4.0 : 2.0) * h / 3.0;
    for (std::size_t n = 0; n < acting.size(); ++n) {
      const std::size_t i = acting[n];
      const double force = force_kN(i, y);
      OpenContact& open = *open_[i];
      open.record.peak_force_kN = std::max(open.record.peak_force_kN, force);
      if (force > largest_kN[n]) largest_kN[n] = force, largest[n] = k;
      note_column_shear(i, k == kIntervals ? t_b : t_a + k * h, y, std::max(0.0, force));
      open.record.impulse_kNs += weight * force;
      open.work_kJ += weight * force * system_.gap(y, i).gap_rate_mps;
    }
  }
  for (std::size_t n = 0; n < acting.size(); ++n) {
    // Only a step that holds the contact's largest force so far can raise it.
    if (largest_kN[n] >= open_[acting[n]]->record.peak_force_kN) locate_peak_force(acting[n], t_a, h, largest[n], at);
  }
}

double CompliantEvents::force_rate_kN_per_s(std::size_t i, double t, const VectorXd& y) const {
  VectorXd y_dot(system_.state_size());
  context_.derivative(t, y, y_dot);
  const contact::GapState s = system_.gap(y, i);
  const contact::ForceSlopes slopes = open_[i]->law.slopes(-s.gap_m, -s.gap_rate_mps);
  // F(δ, δ̇) with δ = −g: Ḟ = ∂F/∂δ δ̇ + ∂F/∂δ̇ δ̈.
  return -(slopes.per_overlap_kN_per_m * s.gap_rate_mps +
           slopes.per_rate_kNs_per_m * system_.gap_acceleration(y, y_dot, i));
}

void CompliantEvents::locate_peak_force(std::size_t i, double t_a, double h, int k, const StateInterpolant& at) {
  VectorXd y(system_.state_size());
  const auto rate = [&](double t) {
    at(t, y);
    return force_rate_kN_per_s(i, t, y);
  };
  // The sample k is the step's largest: Ḟ falls through zero beside it, after it where it still rises.
  const double rate_k = rate(t_a + k * h);
  const int first = rate_k > 0.0 ? k : k - 1;    // the piece [t_a + first h, + h] holding the turning point
  if (first < 0 || first >= kIntervals) return;  // it lies in a neighbouring step
  const double lo_s = t_a + first * h, hi_s = lo_s + h;
  const double rate_lo = first == k ? rate_k : rate(lo_s), rate_hi = first == k ? rate(hi_s) : rate_k;
  if (!(rate_lo > 0.0 && rate_hi <= 0.0)) return;  // no turning point there (a kink, or round-off)
  at(find_root(rate, lo_s, hi_s, rate_lo, rate_hi), y);
  OpenContact& open = *open_[i];
  open.record.peak_force_kN = std::max(open.record.peak_force_kN, force_kN(i, y));
}

void CompliantEvents::finish(double t, const VectorXd& y) {
  for (std::size_t i = 0; i < open_.size(); ++i) {
    if (open_[i]) end_contact(i, t, y);
  }
  // Compliant impacts are complete, so streamed, at their release; the result lists them by onset.
  std::stable_sort(result_.impacts.begin(), result_.impacts.end(),
                   [](const ImpactRecord& a, const ImpactRecord& b) { return a.t_s < b.t_s; });
}

}  // namespace

bool watches_struck_columns(const dynamics::CoupledSystem& system, const EventOptions& options) {
  if (options.law == contact::ContactLaw::impulse) return false;
  const std::vector<std::optional<StruckColumn>> struck = struck_columns(system);
  return std::any_of(struck.begin(), struck.end(), [](const auto& column) { return column.has_value(); });
}

std::unique_ptr<LawEvents> make_compliant_events(const EventContext& context) {
  return std::make_unique<CompliantEvents>(context);
}

}  // namespace pounding::solvers
