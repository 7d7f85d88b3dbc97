#include "pounding/solvers/floor_impacts.hpp"

#include <algorithm>
#include <array>

namespace pounding::solvers {

namespace {

using Slab = dynamics::CoupledSystem::Slab;

std::array<Slab, 2> slabs_of(const contact::Level& level) {
  return {Slab{level.pair[0], level.floors[0]}, Slab{level.pair[1], level.floors[1]}};
}

bool share_a_slab(const contact::Level& a, const contact::Level& b) {
  for (const Slab& s : slabs_of(a)) {
    for (const Slab& t : slabs_of(b)) {
      if (s == t) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<int> joined_levels(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y, int level,
                               const TakeContact& take) {
  const std::vector<contact::Level>& levels = system.levels();
  const auto has_contact = [&](int l) {
    for (std::size_t i = 0; i < system.candidates().size(); ++i) {
      if (system.candidates()[i].level == l && take(i, system.gap(y, i))) return true;
    }
    return false;
  };
  std::vector<int> joined{level};
  for (std::size_t next = 0; next < joined.size(); ++next) {
    const contact::Level& from = levels.at(static_cast<std::size_t>(joined[next] - 1));
    for (const contact::Level& other : levels) {
      if (std::find(joined.begin(), joined.end(), other.index) != joined.end()) continue;
      if (share_a_slab(from, other) && has_contact(other.index)) joined.push_back(other.index);
    }
  }
  std::sort(joined.begin(), joined.end());
  return joined;
}

std::set<std::vector<int>> level_groups(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y,
                                        const std::set<int>& levels, const TakeContact& take) {
  std::set<std::vector<int>> groups;
  for (int level : levels) groups.insert(joined_levels(system, y, level, take));
  return groups;
}

FloorContacts gather_floor_contacts(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y,
                                    const std::vector<int>& levels, double restitution, const TakeContact& take) {
  FloorContacts contacts;
  contacts.levels = levels;
  for (int level : levels) {
    for (const Slab& slab : slabs_of(system.levels().at(static_cast<std::size_t>(level - 1)))) {
      if (std::find(contacts.slabs.begin(), contacts.slabs.end(), slab) == contacts.slabs.end())
        contacts.slabs.push_back(slab);
    }
  }
  for (std::size_t i = 0; i < system.candidates().size(); ++i) {
    const contact::Candidate& c = system.candidates()[i];
    if (!std::binary_search(levels.begin(), levels.end(), c.level)) continue;
    const contact::GapState s = system.gap(y, i);
    if (!take(i, s)) continue;
    contacts.members.push_back(i);
    contacts.states.push_back(s);
    contacts.rows.push_back({system.slab_row(s, c, contacts.slabs), s.gap_rate_mps, restitution});
  }
  return contacts;
}

ContactIdentity contact_identity(const contact::Candidate& c, std::size_t index) {
  const auto [striker, struck] = contact::striker_and_struck(c);
  return {.candidate = index,
          .level = c.level,
          .buildings = {c.pair[0] + 1, c.pair[1] + 1},
          .floors = c.floors,
          .elevation_m = c.elevation_m,
          .striking_building = striker + 1,
          .struck_building = struck + 1,
          .vertex = contact::vertex_number(c),
          .edge = c.edge_index + 1,
          .column = c.column ? static_cast<int>(c.column_index) + 1 : 0};
}

TouchRecord touch_record(const dynamics::CoupledSystem& system, double t, std::size_t index,
                         const contact::GapState& gap) {
  TouchRecord r{contact_identity(system.candidates()[index], index)};
  r.t_s = t;
  r.point = gap.contact_point;
  r.gap_rate_mps = gap.gap_rate_mps;
  r.gap_m = gap.gap_m;
  return r;
}

ImpactRecord impact_at(const dynamics::CoupledSystem& system, double t, std::size_t index,
                       const contact::GapState& gap) {
  const contact::Candidate& c = system.candidates()[index];
  ImpactRecord r{contact_identity(c, index)};
  r.t_s = t;
  r.vertex_rest = c.vertex_rest;
  r.point = gap.contact_point;
  r.approach_velocity_mps = -gap.gap_rate_mps;
  if (c.column) r.height_ratio = c.height_ratio;
  return r;
}

contact::ImpulseSolution apply_impulses(const dynamics::CoupledSystem& system, dynamics::VectorXd& y,
                                        const FloorContacts& contacts) {
  contact::ImpulseSolution solution = contact::solve_impulses(contacts.rows, system.slab_inverse_mass(contacts.slabs));
  system.add_slab_velocities(y, contacts.slabs, solution.velocity_change);
  return solution;
}

double record_floor_outcome(const dynamics::CoupledSystem& system, double t, const FloorContacts& contacts,
                            const contact::ImpulseSolution& solution, const dynamics::VectorXd& y_before,
                            const dynamics::VectorXd& y_after, const std::set<std::size_t>& touched,
                            const std::vector<bool>& holds, const std::vector<bool>& were_held, RunResult& result) {
  const std::vector<Slab>& slabs = contacts.slabs;
  const dynamics::VectorXd v_after = system.slab_velocities(y_after, slabs);
  for (std::size_t k = 0; k < contacts.members.size(); ++k) {
    const std::size_t i = contacts.members[k];
    if (!were_held.empty() && were_held[k]) continue;  // a held contact's share: not an impact
    const contact::GapState& s = contacts.states[k];
    const double impulse = solution.impulses_kNs[k];
    const double rate_before = contacts.rows[k].gap_rate_mps;
    const double rate_after = contact::gap_rate(contacts.rows[k].jacobian, v_after);
    // Closing by rounding alone is not approaching: its round-off impulse is no impact.
    const double round_off_mps = system.gap_rate_round_off_mps(y_before, i);
    if (impulse > 0.0 && rate_before < -round_off_mps) {
      ImpactRecord r = impact_at(system, t, i, s);
      r.approach_velocity_mps = -rate_before;
      r.separation_velocity_mps = rate_after;
      r.impulse_kNs = impulse;
      r.energy_lost_kJ = -impulse * (rate_before + rate_after) / 2.0;  // the shares sum to the group's loss
      r.starts_hold = !holds.empty() && holds[k];
      result.impacts.push_back(r);
    } else if (touched.count(i) && rate_before >= -round_off_mps) {
      // A closing contact that took no impulse was stopped by its neighbours' (a coincident
      // corner, a dependent row): it is part of their impact, not a touch.
      result.touches.push_back(touch_record(system, t, i, s));
    }
  }
  const dynamics::VectorXd inverse_mass = system.slab_inverse_mass(slabs);
  return contact::kinetic_energy(system.slab_velocities(y_before, slabs), inverse_mass) -
         contact::kinetic_energy(v_after, inverse_mass);
}

}  // namespace pounding::solvers
