// The impulse law's events (law_events.hpp): velocity jumps, sustained contacts and their releases.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "law_events.hpp"
#include "pounding/solvers/floor_impacts.hpp"

namespace pounding::solvers {

namespace {

using dynamics::VectorXd;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

class ImpulseEvents final : public LawEvents {
 public:
  explicit ImpulseEvents(const EventContext& context)
      : LawEvents(context), hold_record_(system_.candidates().size(), -1) {}

  void add_forces(const Eigen::Ref<const VectorXd>&, Eigen::Ref<VectorXd>) const override {}
  void add_force_jacobian(const Eigen::Ref<const VectorXd>&, Eigen::SparseMatrix<double>&) const override {}
  void write_witnesses(double t, const Eigen::Ref<const VectorXd>& y, const WitnessLayout& layout,
                       Eigen::Ref<VectorXd> g) const override;
  std::vector<ContactForce> contact_forces(double t, const VectorXd& y) const override;
  double constraint_power(double t, const VectorXd& y) const override;
  void on_event(double t, VectorXd& y, const WitnessLayout::Crossed& crossed) override;
  void integrate(double, double, const VectorXd&, const StateInterpolant&) override {}
  void after_step(double t, const VectorXd& y) override { update_hold_records(t, y); }
  void finish(double t, const VectorXd& y) override {
    for (std::size_t i : std::vector<std::size_t>(states_.held())) release(i, t, y, "end of run");
  }

 private:
  void handle_event(double t, VectorXd& y, const std::vector<std::size_t>& gap_roots);
  void hold(std::size_t i, double t);
  void release(std::size_t i, double t, const VectorXd& y, const std::string& reason);
  /// Held contact i's point slid off its edge's end: candidate j holds on, in the same sustained
  /// contact (docs/model.md §5a); the next settle_holds decides whether it stays pressed.
  void hand_over(std::size_t i, std::size_t j, const VectorXd& y) {
    if (!states_.hold(j)) return;
    hold_record_[j] = hold_record_[i];
    hold_record_[i] = -1;
    states_.release_hold(i, options_.contact_tolerance_m, system_.gap(y, i).gap_m);
    ++result_.statistics.corner_handovers;
  }
  void settle_holds(double t, const VectorXd& y);
  /// Whether candidate i in state s takes part in an impact at this instant.
  bool takes_part(std::size_t i, const contact::GapState& s, const std::set<std::size_t>& fired,
                  const VectorXd& y) const;
  /// g̈ of each member of `contacts` in state y with the contacts `held` kept closed.
  VectorXd free_gap_accelerations(double t, const VectorXd& y, const std::vector<std::size_t>& held,
                                  const FloorContacts& contacts) const;
  std::vector<bool> settle_floor(double t, VectorXd& y, FloorContacts& contacts,
                                 contact::ImpulseSolution& solution) const;
  void stick(const FloorContacts& contacts, const std::vector<bool>& holding, VectorXd& y,
             contact::ImpulseSolution& solution) const;
  void resolve_floor(double t, VectorXd& y, const std::vector<int>& levels, const std::set<std::size_t>& fired);
  void update_hold_records(double t, const VectorXd& y);
  /// The held contacts' forces (kN, compressive positive) at (t, y), in the order of states_.held().
  VectorXd hold_forces(double t, const Eigen::Ref<const VectorXd>& y) const {
    VectorXd y_dot(system_.state_size()), forces(static_cast<Eigen::Index>(states_.held().size()));
    system_.constrained_rhs(t, y, states_.held(), y_dot, forces, context_.springs);
    return forces;
  }

  std::vector<int> hold_record_;  // index into result_.sustained_contacts while held
};

void ImpulseEvents::write_witnesses(double t, const Eigen::Ref<const VectorXd>& y, const WitnessLayout& layout,
                                    Eigen::Ref<VectorXd> g) const {
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return;
  const VectorXd forces = hold_forces(t, y);
  for (std::size_t r = 0; r < held.size(); ++r) {
    g[layout.at(Witness::force, held[r])] = forces[static_cast<Eigen::Index>(r)];
    g[layout.at(Witness::edge, held[r])] = edge_witness(system_.gap(y, held[r]));
  }
}

std::vector<ContactForce> ImpulseEvents::contact_forces(double t, const VectorXd& y) const {
  std::vector<ContactForce> forces;
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return forces;
  const VectorXd held_forces = hold_forces(t, y);
  for (std::size_t r = 0; r < held.size(); ++r) forces.push_back({held[r], held_forces[static_cast<Eigen::Index>(r)]});
  return forces;
}

double ImpulseEvents::constraint_power(double t, const VectorXd& y) const {
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return 0.0;
  const VectorXd forces = hold_forces(t, y);
  double power = 0.0;
  for (std::size_t r = 0; r < held.size(); ++r) power += forces[r] * system_.gap(y, held[r]).gap_rate_mps;
  return power;
}

void ImpulseEvents::on_event(double t, VectorXd& y, const WitnessLayout::Crossed& crossed) {
  for (std::size_t i : crossed.edge) {
    if (const std::optional<std::size_t> j =
            states_.is(i, ContactMode::held) ? context_.successor(i, y, false) : std::nullopt) {
      hand_over(i, *j, y);
    } else {
      release(i, t, y, "slid off the edge");
    }
  }
  for (std::size_t i : crossed.force) release(i, t, y, "tensile force");
  handle_event(t, y, crossed.gap);
}

void ImpulseEvents::handle_event(double t, VectorXd& y, const std::vector<std::size_t>& gap_roots) {
  std::set<std::size_t> fired;
  std::set<int> levels;
  for (std::size_t i : gap_roots) {
    const contact::GapState s = system_.gap(y, i);
    if (!context_.meets(i, y, s)) {
      context_.passed_beside_edge(i);
      continue;
    }
    context_.note_overlap(t, y, i, s);
    fired.insert(i);
    levels.insert(system_.candidates()[i].level);
  }
  // Contacts that share a slab are one impact problem (level_groups), each group solved once.
  const TakeContact take = [&](std::size_t i, const contact::GapState& s) { return takes_part(i, s, fired, y); };
  for (const std::vector<int>& group : level_groups(system_, y, levels, take)) resolve_floor(t, y, group, fired);
  settle_holds(t, y);
  update_hold_records(t, y);  // a hold may end before the next step does
}

void ImpulseEvents::hold(std::size_t i, double t) {
  if (!states_.hold(i)) return;
  SustainedContactRecord record{contact_identity(system_.candidates()[i], i)};
  record.start_s = t;
  hold_record_[i] = static_cast<int>(result_.sustained_contacts.size());
  result_.sustained_contacts.push_back(record);
}

void ImpulseEvents::release(std::size_t i, double t, const VectorXd& y, const std::string& reason) {
  // At g ≈ 0, opening slowly: armed again once clearly open.
  if (!states_.release_hold(i, options_.contact_tolerance_m, system_.gap(y, i).gap_m)) return;
  SustainedContactRecord& record = result_.sustained_contacts[hold_record_[i]];
  record.release_s = t;
  record.release_reason = reason;
  hold_record_[i] = -1;
}

void ImpulseEvents::settle_holds(double t, const VectorXd& y) {
  // A velocity jump anywhere (stiffness-proportional damping couples adjacent floors) or a
  // release changes the force every held contact needs; a force root cannot see a force that
  // jumped to tensile at the restart. So after every event the held set is settled again, all
  // together: the held contacts that the complementarity problem leaves without force while
  // their gap would open are released.
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return;
  // A twin held beside its contact (coincident corners: the same row twice) gets no force and
  // zero acceleration; only an opening acceleration clearly above round-off releases a pair.
  const contact::LcpSolution solution = system_.hold_complementarity(t, y, held, context_.springs);
  result_.statistics.note_lcp(solution.exact, solution.residual);
  const double round_off = 1e-9 * (1.0 + solution.w.cwiseAbs().maxCoeff());
  std::vector<std::size_t> separating;
  for (std::size_t r = 0; r < held.size(); ++r) {
    const auto k = static_cast<Eigen::Index>(r);
    if (solution.x[k] <= 0.0 && solution.w[k] > round_off) separating.push_back(held[r]);
  }
  for (std::size_t i : separating) release(i, t, y, "tensile force");
}

bool ImpulseEvents::takes_part(std::size_t i, const contact::GapState& s, const std::set<std::size_t>& fired,
                               const VectorXd& y) const {
  // Every contact of the group's slabs that is closed now takes part, so simultaneous contacts
  // are solved together, never one after another.
  const bool closed =
      std::abs(s.gap_m) <= options_.contact_tolerance_m && s.on_segment() && !context_.slides_along_face(i, y, s);
  return states_.is(i, ContactMode::held) || fired.count(i) || closed;
}

VectorXd ImpulseEvents::free_gap_accelerations(double t, const VectorXd& y, const std::vector<std::size_t>& held,
                                               const FloorContacts& contacts) const {
  VectorXd y_dot(system_.state_size()), forces(static_cast<Eigen::Index>(held.size()));
  system_.constrained_rhs(t, y, held, y_dot, forces, context_.springs);
  VectorXd accel(static_cast<Eigen::Index>(contacts.members.size()));
  for (std::size_t k = 0; k < contacts.members.size(); ++k) {
    accel[static_cast<Eigen::Index>(k)] = system_.gap_acceleration(y, y_dot, contacts.members[k]);
  }
  return accel;
}

std::vector<bool> ImpulseEvents::settle_floor(double t, VectorXd& y, FloorContacts& contacts,
                                              contact::ImpulseSolution& solution) const {
  // First the impact law with restitution k. A contact that then separates slower than the hold
  // velocity, or would fly lower than the hold height, is held if the force holding it is
  // compressive; held contacts are solved again with k = 0. Repeats until the held set no longer
  // changes; stick() then brings the held ones to ġ = 0 exactly.
  const std::size_t n = contacts.members.size();
  std::vector<bool> holding(n, false);
  VectorXd y_after = y;
  for (std::size_t pass = 0; pass <= n; ++pass) {
    for (std::size_t k = 0; k < n; ++k) contacts.rows[k].restitution = holding[k] ? 0.0 : options_.restitution;
    y_after = y;
    solution = apply_impulses(system_, y_after, contacts);
    result_.statistics.note_lcp(solution.exact, solution.lcp_residual);
    const VectorXd v_after = system_.slab_velocities(y_after, contacts.slabs);

    std::vector<std::size_t> trial;  // held elsewhere, plus this group's slow separations
    for (std::size_t i : states_.held()) {
      if (!std::binary_search(contacts.levels.begin(), contacts.levels.end(), system_.candidates()[i].level))
        trial.push_back(i);
    }
    const std::size_t others = trial.size();
    const VectorXd accel = free_gap_accelerations(t, y_after, trial, contacts);
    std::vector<std::size_t> slow;
    for (std::size_t k = 0; k < n; ++k) {
      const double rate = contact::gap_rate(contacts.rows[k].jacobian, v_after);
      const double apex_m = accel[k] < 0.0 ? rate * rate / (-2.0 * accel[k]) : kInfinity;
      if (rate < options_.hold_velocity_mps || apex_m < options_.hold_height_m) {
        trial.push_back(contacts.members[k]);
        slow.push_back(k);
      }
    }
    // Held if the physical force is compressive: the drift correction (3ġ/τ at the slow ġ the
    // impulse left) would pull a gently pressed pair apart, and stick() brings ġ to 0 anyway.
    std::vector<bool> proposal(n, false);
    if (!slow.empty()) {
      const std::vector<bool> pressing = system_.physical_hold_forces(t, y_after, trial, context_.springs).pressing;
      for (std::size_t s = 0; s < slow.size(); ++s) proposal[slow[s]] = pressing[others + s];
    }
    if (proposal == holding) break;
    holding = proposal;
  }
  stick(contacts, holding, y_after, solution);
  y = y_after;
  return holding;
}

void ImpulseEvents::stick(const FloorContacts& contacts, const std::vector<bool>& holding, VectorXd& y,
                          contact::ImpulseSolution& solution) const {
  // A contact goes into hold separating at up to hold_velocity_mps (the bounce sequence it cuts
  // off would have brought it to rest). Left to the drift correction, that speed would open the
  // gap by ~v·τ and do work against the constraint; instead the held contacts are brought to
  // ġ = 0 together here, and the kinetic energy this takes counts as impact loss.
  // The group's other contacts keep what the impact gave them (the rebound of one that took an
  // impulse, else not closing): a pull on the held ones must not leave a neighbour on the same
  // slabs closing again at once, to be struck again a little deeper.
  std::vector<std::size_t> held, kept;
  for (std::size_t k = 0; k < holding.size(); ++k) (holding[k] ? held : kept).push_back(k);
  if (held.empty()) return;
  const VectorXd velocities = system_.slab_velocities(y, contacts.slabs);
  std::vector<Eigen::RowVectorXd> rows;
  for (std::size_t k : held) rows.push_back(contacts.rows[k].jacobian);
  std::vector<contact::KeptRow> kept_rows;
  for (std::size_t k : kept) {
    const double rate = contact::gap_rate(contacts.rows[k].jacobian, velocities);
    kept_rows.push_back({contacts.rows[k].jacobian, solution.impulses_kNs[k] > 0.0 ? std::max(rate, 0.0) : 0.0});
  }
  const contact::ImpulseSolution closing =
      contact::closing_impulses_keeping(rows, kept_rows, system_.slab_inverse_mass(contacts.slabs), velocities);
  system_.add_slab_velocities(y, contacts.slabs, closing.velocity_change);
  solution.velocity_change += closing.velocity_change;
  for (std::size_t r = 0; r < held.size(); ++r) solution.impulses_kNs[held[r]] += closing.impulses_kNs[r];
  for (std::size_t r = 0; r < kept.size(); ++r) solution.impulses_kNs[kept[r]] += closing.impulses_kNs[held.size() + r];
}

void ImpulseEvents::resolve_floor(double t, VectorXd& y, const std::vector<int>& levels,
                                  const std::set<std::size_t>& fired) {
  FloorContacts contacts =
      gather_floor_contacts(system_, y, levels, options_.restitution,
                            [&](std::size_t i, const contact::GapState& s) { return takes_part(i, s, fired, y); });
  const VectorXd y_before = y;
  contact::ImpulseSolution solution;
  std::vector<bool> were_held(contacts.members.size());
  for (std::size_t k = 0; k < contacts.members.size(); ++k)
    were_held[k] = states_.is(contacts.members[k], ContactMode::held);
  const std::vector<bool> holding = settle_floor(t, y, contacts, solution);
  recorder_.add_impact_loss(
      record_floor_outcome(system_, t, contacts, solution, y_before, y, fired, holding, were_held, result_));
  recorder_.stream_new_impacts(result_.impacts);
  for (std::size_t k = 0; k < contacts.members.size(); ++k) {
    const std::size_t i = contacts.members[k];
    if (were_held[k]) result_.sustained_contacts[hold_record_[i]].impulse_kNs += solution.impulses_kNs[k];
    if (holding[k]) {
      hold(i, t);
    } else if (states_.is(i, ContactMode::held)) {
      release(i, t, y, "separated by an impact");
    } else {
      context_.mask(i, options_.reopen_gap_m, y);
    }
  }
}

void ImpulseEvents::update_hold_records(double t, const VectorXd& y) {
  const std::vector<std::size_t>& held = states_.held();
  if (held.empty()) return;
  const VectorXd forces = hold_forces(t, y);
  for (std::size_t r = 0; r < held.size(); ++r) {
    SustainedContactRecord& record = result_.sustained_contacts[hold_record_[held[r]]];
    record.max_force_kN = std::max(record.max_force_kN, forces[r]);
    record.max_gap_drift_m = std::max(record.max_gap_drift_m, std::abs(system_.gap(y, held[r]).gap_m));
  }
}

}  // namespace

std::unique_ptr<LawEvents> make_impulse_events(const EventContext& context) {
  return std::make_unique<ImpulseEvents>(context);
}

}  // namespace pounding::solvers
