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

#include "pounding/analysis/methods.hpp"
#include "pounding/contact/candidates.hpp"
#include "pounding/contact/column_contact.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/model/building.hpp"

namespace pounding::analysis {

struct ContactSettings {
  double gap_m = 0.0;              // clear distance along x between the facing sides at rest (m)
  double restitution = 0.5;        // Newton coefficient k ∈ [0, 1]
  double candidate_margin_m = 1.0; // reach of the candidate search beyond gap and edge ends (m)
  double hold_velocity_mps = 1e-3; // sticking threshold: slower separations of pressed pairs are held
  double hold_height_m = 1e-8;     // a pair whose next flight would rise less than this is held too
  // Floors of the two buildings whose elevations differ by at most this stand at one level and
  // can touch (m). 1 mm: far above the round-off of summed storey heights, far below any
  // storey height or slab thickness, so only floors the file puts at one height match.
  double level_tolerance_m = 1e-3;
  std::string law = "impulse";     // a name of contact_laws() (contact_laws.hpp)
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
  /// Sets the stiffness key of the law `law` names (--contact-stiffness); for the impulse law,
  /// kelvin's key, which the validator then refuses naming the law.
  void set_stiffness(double value);
};

/// One [contact] key, declared once: the scene reader, the range checks of Scene::validate(),
/// `pounding settings` and docs/scene-format.md's [contact] table come from its row. The
/// defaults are ContactSettings' initialisers (a required key has none).
struct ContactSettingSpec {
  std::string_view key;     // [contact] key, as `contact.<key>` in errors and summary.json
  std::string_view option{};  // the `run`/`check` option that replaces it; empty: none
  std::variant<double ContactSettings::*, std::optional<double> ContactSettings::*, std::string ContactSettings::*>
      member;
  bool required = false;
  std::optional<Range> range = std::nullopt;  // numbers: the values accepted
  std::vector<std::string_view> choices{};    // text other than the law: the values accepted
  std::string_view description{};             // one line, with units
  std::string_view details{};                 // the docs' meaning column, after the description
};

/// Every [contact] key, in the order the docs list them.
std::span<const ContactSettingSpec> contact_setting_specs();
/// @pre `key` is a [contact] key.
const ContactSettingSpec& contact_setting_spec(std::string_view key);

/// The peak groups `output.peaks` may list, in the order outputs list them: displacements (u, v,
/// φ, contact vertices' x), accelerations (absolute, of the CM), drifts (storey drift ratios).
inline constexpr std::array<std::string_view, 3> kPeakGroups{"displacements", "accelerations", "drifts"};

/// What `pounding run` records besides impacts and the energy audit (always), and how.
struct OutputSettings {
  bool history = true;               // history.csv and contacts_history.csv; false: neither computed nor written
  std::vector<int> history_floors;   // levels (1-based, as `check` lists them); empty: every level
  /// [output.floor_history]: more floors to write, by building name: any floor of either
  /// building (a roof above the other building, a floor with no counterpart), after the levels'
  /// slabs; one already written with a level is not repeated.
  std::vector<std::pair<std::string, std::vector<int>>> floor_history;
  double history_interval_s = 0.01;
  std::vector<std::string> peaks{kPeakGroups.begin(), kPeakGroups.end()};  // peak groups (kPeakGroups), any subset
  /// Also run the scene without contact (same method and settings) and report the pounding-
  /// induced change of the storeys' peak drifts (and ductilities): needs the drifts peak group.
  bool contact_free_reference = false;
  /// What the solvers record. @pre valid (Scene::validate).
  solvers::OutputSelection selection() const;
};

struct Scene {
  std::string name;
  std::filesystem::path file;  // where it was read from; empty for scenes built in code
  std::array<model::BuildingDefinition, 2> buildings;  // building 1 on the −x side
  excitation::ExcitationSpec excitation;
  ContactSettings contact;
  SolverSettings solver;  // as given (methods.hpp)
  OutputSettings output;

  /// output.floor_history as {building (0 or 1), floor}. @pre valid.
  std::vector<std::array<int, 2>> history_other_floors() const;
  /// The floor pairs at a common elevation (within contact.level_tolerance_m), lowest first.
  /// @pre buildings valid.
  std::vector<contact::Level> levels() const;
  /// The floors between two floors of the other building, below its roof, that meet its columns
  /// (contact::column_levels); empty when contact.slab_to_column is "off". @pre buildings valid.
  std::vector<contact::ColumnLevel> column_levels() const;
  /// The slab-to-column candidates on column_levels() (contact::find_column_candidates with the
  /// scene's gap and candidate margin). @pre buildings valid.
  std::vector<contact::Candidate> column_candidates() const;

  /// Moves building 2 along x so that the clear distance becomes `gap_m`.
  /// @throws InputError (key `contact.gap_m`) if the gap lies outside [0, 10] m.
  void set_gap(double gap_m);

  /// Checks each building, the contact and solver settings, and the pair: at least one level or
  /// slab-to-column floor, a compliant law and column storeys wherever slabs meet columns, building 2 on the +x side of
  /// building 1 facing it, the slabs not overlapping at rest, and contact.gap_m equal to the clear distance the slab
  /// outlines show. @throws InputError naming the key and value.
  void validate() const;
};

/// Slabs that strike columns need a compliant law: an impulse would need the column rigid and its
/// two floors' shares solved with the slab's, which the impact module (floor pair by floor pair)
/// does not do. Checked when a run starts (run_scene, `check`), after the command line's or
/// Python's overrides; not by Scene::validate(), so that `--contact-law` can mend a file.
/// @throws InputError(`contact.law`) naming the first such slab and its storey.
void require_column_contact_law(const Scene& scene);

}  // namespace pounding::analysis
