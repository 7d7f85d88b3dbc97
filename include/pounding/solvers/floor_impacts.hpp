#pragma once
// The impact step every solution path shares: gather the contacts of a group of levels (a level is
// the slab pair at a common elevation; in a row, the levels whose contacts share a slab form one
// group), solve their impulses together (the LCP of contact/impact.hpp), apply them, and record
// what happened.

#include <functional>
#include <set>
#include <vector>

#include "pounding/contact/impact.hpp"
#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

struct FloorContacts {
  std::vector<int> levels;                           // 1-based level indices, ascending
  std::vector<dynamics::CoupledSystem::Slab> slabs;  // the levels' slabs, each once
  std::vector<std::size_t> members;                  // candidate indices
  std::vector<contact::GapState> states;             // at the impact instant
  std::vector<contact::ContactRow> rows;             // impact-law rows (restitution per contact)
};

using TakeContact = std::function<bool(std::size_t, const contact::GapState&)>;

/// The levels joined to `level` (1-based) through the slabs they share, directly or through other
/// joined levels, among those with a candidate for which take(index, state) holds; `level` itself
/// always. Ascending. Two buildings' levels share no slab: {level}.
std::vector<int> joined_levels(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y, int level,
                               const TakeContact& take);

/// The groups of joined_levels() of each of `levels`, each group once. Levels whose contacts
/// share a slab (a row's middle building struck from both sides) are one impact problem; groups
/// share no slab, so they may be resolved one after another.
std::set<std::vector<int>> level_groups(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y,
                                        const std::set<int>& levels, const TakeContact& take);

/// The candidates of `levels` (1-based) for which take(index, state) holds, with restitution k each.
FloorContacts gather_floor_contacts(const dynamics::CoupledSystem& system, const dynamics::VectorXd& y,
                                    const std::vector<int>& levels, double restitution, const TakeContact& take);

/// Candidate `index` as the outputs name it (ContactIdentity: 1-based, the slab's building striking
/// a column).
ContactIdentity contact_identity(const contact::Candidate& c, std::size_t index);

/// An impact of candidate `index` at t where `gap` was evaluated: where it is (level, floors,
/// vertex, edge, contact point) and its approach velocity; the caller fills in the outcome.
ImpactRecord impact_at(const dynamics::CoupledSystem& system, double t, std::size_t index,
                       const contact::GapState& gap);

/// The record of candidate `index` touching (no impulse) at t in the state `gap`.
TouchRecord touch_record(const dynamics::CoupledSystem& system, double t, std::size_t index,
                         const contact::GapState& gap);

/// Solves the group's impulses together and adds the velocity change to y.
contact::ImpulseSolution apply_impulses(const dynamics::CoupledSystem& system, dynamics::VectorXd& y,
                                        const FloorContacts& contacts);

/// Appends an impact record for each member that took an impulse while approaching, and a touch
/// record for each member in `touched` that was not approaching. `holds[k]`: member k then went
/// into sustained contact; `were_held[k]`: it was held already, so its impulse is a share of the
/// neighbours' impact, not an impact (either empty: none). Returns the group's kinetic energy
/// lost (kJ).
double record_floor_outcome(const dynamics::CoupledSystem& system, double t, const FloorContacts& contacts,
                            const contact::ImpulseSolution& solution, const dynamics::VectorXd& y_before,
                            const dynamics::VectorXd& y_after, const std::set<std::size_t>& touched,
                            const std::vector<bool>& holds, const std::vector<bool>& were_held, RunResult& result);

}  // namespace pounding::solvers
