#pragma once
// One whole analysis as a scene file describes it: two buildings, the excitation, the contact
// parameters, and the solver and output settings.

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pounding/key_spec.hpp"
#include "pounding/analysis/methods.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/contact/column_contact.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/model/building.hpp"

namespace pounding::analysis {

/// A row's stated gap of one neighbouring pair ([contact.gaps] "NAME:NAME" = gap_m).
struct PairGap {
  std::string first, second;  // building names, as the key gives them
  double gap_m = 0.0;
};

struct ContactSettings {
  double gap_m = 0.0;  // two buildings: clear distance along x between the facing sides at rest (m)
  /// A row (three or more buildings): the neighbouring pairs' gaps as the file states them, each
  /// checked against the outlines (which decide the gaps); optional, any subset of the pairs.
  std::vector<PairGap> gaps;
  double restitution = 0.5;         // Newton coefficient k ∈ [0, 1]
  double candidate_margin_m = 1.0;  // reach of the candidate search beyond gap and edge ends (m)
  double hold_velocity_mps = 1e-3;  // sticking threshold: slower separations of pressed pairs are held
  double hold_height_m = 1e-8;      // a pair whose next flight would rise less than this is held too
  // Floors of the two buildings whose elevations differ by at most this stand at one level and
  // can touch (m). 1 mm: far above the round-off of summed storey heights, far below any
  // storey height or slab thickness, so only floors the file puts at one height match.
  double level_tolerance_m = 1e-3;
  std::string law = "impulse";  // a name of contact_laws() (contact_laws.hpp)
  /// "on": a slab between two floors of the other building meets that building's facade columns
  /// (docs/model.md §6b); "off": such slabs are left out (only common levels touch).
  std::string slab_to_column = "on";
  /// kelvin's spring (kN/m); unset: the law's published default. Refused for the other laws.
  std::optional<double> stiffness_kN_per_m;
  /// hertzdamp's k_h or jankowski's β (kN/m^1.5); unset: the law's default. Refused for the others.
  std::optional<double> stiffness_kN_per_m1_5;
  /// The stiffness a run uses, in the law's unit (contact_laws.hpp): the given one or the law's
  /// default (0 for impulse).
  double used_stiffness() const;
  /// Sets the stiffness key of the law `law` names (--contact-stiffness) and clears the other
  /// (a stiffness the scene gave for its own law, which --contact-law replaced); for the impulse
  /// law, kelvin's key, which the validator then refuses naming the law.
  void set_stiffness(double value);
};

/// One [contact] key, declared once (key_spec.hpp): the scene reader, the `run`/`check` options
/// and Python's load_scene() keywords, the range checks of Scene::validate(), `pounding settings`
/// and docs/scene-format.md's [contact] table come from its row. The defaults are ContactSettings'
/// initialisers (a required key has none).
using ContactSettingSpec = KeySpec<ContactSettings>;

/// Every [contact] key, in the order the docs list them.
std::span<const ContactSettingSpec> contact_setting_specs();
/// @pre `key` is a [contact] key.
const ContactSettingSpec& contact_setting_spec(std::string_view key);

/// The peak groups `output.peaks` may list, in the order outputs list them: displacements (u, v,
/// φ, contact vertices' x), accelerations (absolute, of the CM), drifts (storey drift ratios).
inline constexpr std::array<std::string_view, 3> kPeakGroups{"displacements", "accelerations", "drifts"};

/// What `pounding run` records besides impacts and the energy audit (always), and how.
struct OutputSettings {
  bool history = true;              // history.csv and contacts_history.csv; false: neither computed nor written
  std::vector<int> history_floors;  // levels (1-based, as `check` lists them); empty: every level
  /// [output.floor_history]: more floors to write, by building name: any floor of either
  /// building (a roof above the other building, a floor with no counterpart), after the levels'
  /// slabs; one already written with a level is not repeated.
  std::vector<std::pair<std::string, std::vector<int>>> floor_history;
  double history_interval_s = 0.01;
  std::vector<std::string> peaks{kPeakGroups.begin(), kPeakGroups.end()};  // peak groups (kPeakGroups), any subset
  /// Also run the scene without contact (same method and settings) and report the pounding-
  /// induced change of the storeys' peak drifts (and ductilities): needs the drifts peak group.
  bool contact_free_reference = false;
  /// Storey and column forces (solvers/member_forces.hpp): their peaks in summary.json and, with
  /// the history, their histories in history.csv's last columns.
  bool member_forces = false;
  /// What the solvers record. @pre valid (Scene::validate).
  solvers::OutputSelection selection() const;
};

/// One scalar [output] key (key_spec.hpp): the scene reader, the range checks of
/// Scene::validate(), `pounding settings` and docs/scene-format.md's [output] table come from its
/// row. The lists (`peaks`, `history_floors`, `[output.floor_history]`) are read and checked on
/// their own, since their checks need the scene's levels and buildings.
using OutputSpec = KeySpec<OutputSettings>;
std::span<const OutputSpec> output_specs();

/// Two buildings whose slabs can touch: `first` < `second` (0-based in the scene), standing
/// `gap_m` apart at rest (the shortest distance between their outlines; two buildings: the clear
/// distance along x), `direction` the unit plan direction in which `second` moves away from `first`.
struct BuildingPair {
  int first = 0;
  int second = 1;
  double gap_m = 0.0;
  model::Point2 direction = model::Point2::UnitX();
};

struct Scene {
  std::string name;
  std::filesystem::path file;  // where it was read from; empty for scenes built in code
  /// Two or more. Two: building 1 on the −x side, `contact.gap_m` apart. More (a row): any plan
  /// arrangement, the pairs standing within contact.candidate_margin_m of each other neighbours.
  std::vector<model::BuildingDefinition> buildings = std::vector<model::BuildingDefinition>(2);
  excitation::ExcitationSpec excitation;
  ContactSettings contact;
  SolverSettings solver;  // as given (methods.hpp)
  OutputSettings output;

  bool is_row() const { return buildings.size() > 2; }
  /// The neighbouring pairs, in order of (first, second). Two buildings: the one pair, its gap
  /// contact.gap_m. A row: every pair whose outlines stand at most contact.candidate_margin_m
  /// apart (farther pairs cannot touch within the candidate search's reach), its gap read from the
  /// outlines. @pre buildings' slabs valid and not overlapping.
  std::vector<BuildingPair> pairs() const;
  /// The two-building scene of `pair`: its two buildings (first, second), contact.gap_m its gap,
  /// the rest of this scene's settings. Rows find levels and candidates pair by pair through it.
  Scene pair_scene(const BuildingPair& pair) const;
  /// pair_scene() turned in plan by a multiple of 90° about the origin (slabs, CMs, columns with
  /// their b and h, storey matrices, and the ground motion's direction together, so the motion is
  /// the same) so that the pair's second building stands on the +x side of its first, as the
  /// needed-gap analysis (a gap widened along x) takes two buildings. Sets `turned_deg` to the
  /// turn (counter-clockwise). @throws InputError when the pair does not face along a plan axis.
  Scene pair_scene_facing_x(const BuildingPair& pair, double& turned_deg) const;
  /// A building's index by name. @throws InputError(`key`) naming the buildings when none has it.
  int building_index(const std::string& building_name, const std::string& key) const;
  /// The neighbouring pair named "NAME:NAME" (either order). @throws InputError(`key`, text)
  /// naming the neighbouring pairs when the text is not two names or they are no such pair.
  BuildingPair named_pair(const std::string& names, const std::string& key) const;

  /// output.floor_history as {building (0-based), floor}. @pre valid.
  std::vector<std::array<int, 2>> history_other_floors() const;
  /// The floor pairs at a common elevation (within contact.level_tolerance_m), lowest first; a
  /// row: pair by pair (pairs()), numbered on. @pre buildings valid.
  std::vector<contact::Level> levels() const;
  /// The floors between two floors of the other building, below its roof, that meet its columns
  /// (contact::column_levels); empty when contact.slab_to_column is "off". Building indices 0 and
  /// 1 of the pair: @pre two buildings (a row: of each pair_scene()), valid.
  std::vector<contact::ColumnLevel> column_levels() const;
  /// The slab-to-column candidates (contact::find_column_candidates with each pair's gap and the
  /// candidate margin), pair by pair. @pre buildings valid.
  std::vector<contact::Candidate> column_candidates() const;

  /// Moves building 2 along x so that the clear distance becomes `gap_m`.
  /// @throws InputError (key `contact.gap_m`) if the gap lies outside [0, 10] m, or for a row.
  void set_gap(double gap_m);
  /// Sets the gap of the neighbouring pair of the buildings named `first` and `second` (any
  /// order): moves the pair's second building along the pair's direction, with every building
  /// that neighbours it on the far side (reachable from it through neighbouring pairs without
  /// this one); the others stay. Two buildings: set_gap. @throws InputError (key
  /// `contact.gaps."A:B"`) for unknown names, a pair that is no neighbouring pair, a gap outside
  /// [0, 10] m, a pair on a ring of neighbours (moving one side would move the other), or a move
  /// that does not give the gap (the pair's nearest points are not along one direction).
  void set_pair_gap(const std::string& first, const std::string& second, double gap_m);

  /// Checks each building, the contact and solver settings, and the pair: at least one level or
  /// slab-to-column floor, a compliant law and column storeys wherever slabs meet columns, building 2 on the +x side of
  /// building 1 facing it, the slabs not overlapping at rest, and contact.gap_m equal to the clear distance the slab
  /// outlines show. A row: no two slabs overlapping at rest, names distinct, at least one neighbouring pair,
  /// each pair as above (levels, column storeys) except the side, contact.gaps matching the outlines, no gap_m.
  /// @throws InputError naming the key and value.
  void validate() const;
};

/// Slabs that strike columns need a compliant law: an impulse would need the column rigid and its
/// two floors' shares solved with the slab's, which the impact module (slab to slab) does not do.
/// Checked when a run starts (run_scene, `check`), after the command line's or Python's
/// overrides; not by Scene::validate(), so that `--contact-law` can mend a file.
/// @throws InputError(`contact.law`) naming the first such slab (of a row: in its first such pair)
/// and its storey.
void require_compliant_law_where_needed(const Scene& scene);

}  // namespace pounding::analysis
