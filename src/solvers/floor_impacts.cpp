#include "pounding/solvers/floor_impacts.hpp"

namespace pounding::solvers {

FloorContacts gather_floor_contacts(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y, int level,
                                    double restitution,
                                    const std::function<bool(std::size_t, const contact::GapState&)>& take) {
  FloorContacts contacts;
  contacts.level = level;
  const contact::Level& on = system.levels().at(static_cast<std::size_t>(level - 1));
  contacts.slabs = {on.pair, on.floors};
  for (std::size_t i = 0; i < system.candidates().size(); ++i) {
    const contact::Candidate& c = system.candidates()[i];
    if (c.level != level) continue;
    const contact::GapState s = system.gap(y, i);
    if (!take(i, s)) continue;
    contacts.members.push_back(i);
    contacts.states.push_back(s);
    contacts.rows.push_back({system.pair_row(s, c), s.gap_rate_mps, restitution});
  }
  return contacts;
}

TouchRecord touch_record(const dynamics::CoupledSystem& system, double t, std::size_t index,
                         const contact::GapState& gap) {
  const contact::Candidate& c = system.candidates()[index];
  return {t,
          c.level,
          c.floors,
          c.elevation_m,
          c.striking_building + 1,
          contact::vertex_number(c),
          index,
          gap.contact_point,
          gap.gap_rate_mps,
          gap.gap_m,
          {c.pair[0] + 1, c.pair[1] + 1}};
}

ImpactRecord impact_at(const dynamics::CoupledSystem& system, double t, std::size_t index,
                       const contact::GapState& gap) {
  const contact::Candidate& c = system.candidates()[index];
  ImpactRecord r;
  r.t_s = t;
  r.level = c.level;
  r.floors = c.floors;
  r.elevation_m = c.elevation_m;
  r.striking_building = c.striking_building + 1;
  r.buildings = {c.pair[0] + 1, c.pair[1] + 1};
  r.vertex = contact::vertex_number(c);
  r.struck_edge = c.edge_index + 1;
  r.candidate = index;
  r.vertex_rest = c.vertex_rest;
  r.point = gap.contact_point;
  r.approach_velocity_mps = -gap.gap_rate_mps;
  if (c.column) {
    r.column = static_cast<int>(c.column_index) + 1;
    r.height_ratio = c.height_ratio;
  }
  return r;
}

contact::ImpulseSolution apply_impulses(const dynamics::CoupledSystem& system, dynamics::VectorXd& y,
                                        const FloorContacts& contacts) {
  contact::ImpulseSolution solution = contact::solve_impulses(contacts.rows, system.pair_inverse_mass(contacts.slabs));
  system.add_pair_velocities(y, contacts.slabs, solution.velocity_change);
  return solution;
}

double record_floor_outcome(const dynamics::CoupledSystem& system, double t, const FloorContacts& contacts,
                            const contact::ImpulseSolution& solution, const dynamics::VectorXd& y_before,
                            const dynamics::VectorXd& y_after, const std::set<std::size_t>& touched,
                            const std::vector<bool>& holds, const std::vector<bool>& were_held,
                            RunResult& result) {
  const dynamics::CoupledSystem::SlabPair& slabs = contacts.slabs;
  const contact::Vector6d v_after = system.pair_velocities(y_after, slabs);
  for (std::size_t k = 0; k < contacts.members.size(); ++k) {
    const std::size_t i = contacts.members[k];
    if (!were_held.empty() && were_held[k]) continue;  // a held contact's share: not an impact
    const contact::GapState& s = contacts.states[k];
    const double impulse = solution.impulses_kNs[k];
    const double rate_before = contacts.rows[k].gap_rate_mps;
    const double rate_after = contacts.rows[k].jacobian.dot(v_after);
    // Closing by rounding alone is not approaching: its round-off impulse is no impact.
    const double round_off_mps = system.gap_rate_round_off_mps(y_before, i);
    if (impulse > 0.0 && rate_before < -round_off_mps) {
      ImpactRecord r = impact_at(system, t, i, s);
      r.approach_velocity_mps = -rate_before;
      r.separation_velocity_mps = rate_after;
      r.impulse_kNs = impulse;
      r.energy_lost_kJ = -impulse * (rate_before + rate_after) / 2.0;  // the shares sum to the pair's loss
      r.starts_hold = !holds.empty() && holds[k];
      result.impacts.push_back(r);
    } else if (touched.count(i) && rate_before >= -round_off_mps) {
      // A closing contact that took no impulse was stopped by its neighbours' (a coincident
      // corner, a dependent row): it is part of their impact, not a touch.
      result.touches.push_back(touch_record(system, t, i, s));
    }
  }
  const contact::Vector6d inverse_mass = system.pair_inverse_mass(slabs);
  return contact::kinetic_energy(system.pair_velocities(y_before, slabs), inverse_mass) -
         contact::kinetic_energy(v_after, inverse_mass);
}

}  // namespace pounding::solvers
