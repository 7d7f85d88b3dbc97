#include "pounding/analysis/scene.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/limit_states.hpp"
#include "pounding/contact/impact.hpp"
#include "pounding/input_error.hpp"

namespace pounding::analysis {
namespace {

constexpr double kGapTolerance_m = 1e-6;

constexpr Range kHistoryInterval{1e-4, 10.0, "s"};

// `--contact-stiffness` sets the stiffness key of the law in force (ContactSettings::set_stiffness).
void set_stiffness_option(ContactSettings& contact, const KeyValue& value) {
  const std::optional<double> stiffness = number_of(value);
  if (!stiffness) throw InputError("contact.stiffness", std::get<std::string>(value), "expected a number");
  contact.set_stiffness(*stiffness);
}

// The [contact] keys. Ranges: seismic joints are centimetres to a metre; pounding approaches at
// 0.1 to 1 m/s; floors up to a slab's thickness apart still meet face on (validate_levels() also
// keeps the tolerance below half of every storey, so a floor meets at most one of the other
// building); stiffness from a soft pad (1 kN/m) to far stiffer than concrete (1e12 kN/m: contact
// periods of microseconds for floor masses of tonnes, below which no integrator resolves the
// contact), and the Hertz laws' k δ^(1/2) at 1 mm of overlap spans the same within a factor 30.
// Built on first use, so other files' static initialisers may read it.
const std::vector<ContactSettingSpec>& contact_specs() {
  static const std::vector<ContactSettingSpec> kSpecs = {
      {.key = "gap_m",
       .option = "--gap",
       .member = &ContactSettings::gap_m,
       .required = true,
       .range = Range{0.0, 10.0, "m"},
       .description = "clear distance along x between the facing sides at rest (m)",
       .details = "it must equal what the slab outlines show (to 1 µm); `--gap` moves building 2 (slab, CM, "
                  "columns) along x to another gap. Two buildings only: a row takes its gaps per pair from the "
                  "outlines ([`[contact.gaps]`](#contactgaps-rows))"},
      {.key = "restitution",
       .option = "--restitution",
       .member = &ContactSettings::restitution,
       .required = true,
       .range = contact::kRestitutionRange,
       .description = "Newton coefficient k"},
      {.key = "candidate_margin_m",
       .member = &ContactSettings::candidate_margin_m,
       .range = Range{0.0, 10.0, "m", true},
       .description = "reach of the candidate search (m)",
       .details = "a vertex is a candidate against an edge facing it when, at rest, it lies in front of the edge "
                  "at most `gap_m` + margin away and projects onto the edge or at most margin beyond an end. 1 m is "
                  "far above storey drifts and far below slab sizes; raise it only for very large motions"},
      {.key = "hold_velocity_mps",
       .member = &ContactSettings::hold_velocity_mps,
       .range = Range{0.0, 0.1, "m/s", true},
       .description = "sticking threshold (m/s)",
       .details = "after an impact, a pair that separates slower than this while pressed together is held in "
                  "sustained contact instead of bouncing on (docs/model.md §7)"},
      {.key = "hold_height_m",
       .member = &ContactSettings::hold_height_m,
       .range = Range{0.0, 1e-3, "m", true},
       .description = "a pressed pair whose next flight would rise less than this (m), v⁺²/(2|g̈|), is held",
       .details = "whatever `hold_velocity_mps` says: such a bounce is below what the integrators resolve at their "
                  "default tolerances, and chasing it only accumulates round-off (and energy). Raise it towards "
                  "the tolerance of a loose run; at most 1 mm, far below any flight that matters"},
      {.key = "law",
       .option = "--contact-law",
       .member = &ContactSettings::law,
       .description = "how contacts push",
       .details = "`impulse` is the paper's rigid impact with restitution and held contacts; `kelvin` a "
                  "spring–dashpot element while the slabs overlap; `hertzdamp` a Hertz spring with damping ∝ δ^1.5 "
                  "(Muthukumar & DesRoches 2006); `hertzdamp-ye` the same with Ye, Li & Zhu's (2009) damping, "
                  "whose rebound follows e; `jankowski` a Hertz spring with a dashpot while approaching "
                  "(Jankowski 2005) ([model.md §6a](model.md#6a-compliant-contact-kelvin-hertzdamp-jankowski), "
                  "which also says which law to use for what). The compliant laws run on cvode-bdf, cvode-adams, "
                  "arkode-erk and arkode-dirk; hht and exact refuse them (exit 2). `jankowski` and `hertzdamp-ye` "
                  "refuse `restitution = 0` (their damping is infinite there)",
       .option_help = contact_laws_help},
      {.key = "slab_to_column",
       .member = &ContactSettings::slab_to_column,
       .choices = {"on", "off"},
       .description = "whether a slab between two floors of the other building meets its facade columns",
       .details = "`\"on\"`: such a slab strikes the columns of the other building's facing facade at its "
                  "height, the force shared by the column's two floors and the column's local flexibility in "
                  "series with the law ([model.md §6b](model.md#6b-slab-to-column-contact)); it needs a "
                  "compliant law. `\"off\"` leaves those slabs out: only floors at a common level touch"},
      {.key = "stiffness_kN_per_m",
       .option = "--contact-stiffness",
       .member = &ContactSettings::stiffness_kN_per_m,
       .range = Range{1.0, 1e12, "kN/m", false, "[1, 1e12]"},
       .description = "kelvin only: the element's spring k (kN/m)",
       .details = "refused for the other laws, naming the law and its key, like a solver setting the method does "
                  "not use. The default is Jankowski's (2005) linear viscoelastic fit to concrete-on-concrete "
                  "impact tests, 93.5 kN/mm, as quoted: not checked against the paper here; the dashpot follows "
                  "from `restitution`",
       .set = set_stiffness_option,
       .option_help = contact_stiffness_help},
      {.key = "stiffness_kN_per_m1_5",
       .option = "--contact-stiffness",
       .member = &ContactSettings::stiffness_kN_per_m1_5,
       .range = Range{1.0, 1e13, "kN/m^1.5", false, "[1, 1e13]"},
       .description = "hertzdamp's and hertzdamp-ye's k_h or jankowski's β (kN/m^1.5)",
       .details = "refused for impulse and kelvin; `--contact-stiffness` sets it when one of these laws is in "
                  "force. Defaults as quoted, not checked against the papers: hertzdamp and hertzdamp-ye 25 000 "
                  "kip/in^1.5 (Muthukumar & DesRoches 2006, concrete bridge decks), jankowski 2.75e9 N/m^1.5 "
                  "(Jankowski 2005, the same concrete tests as kelvin's default). The damping follows from "
                  "`restitution` (and for the hertzdamp laws the approach speed at onset)",
       .set = set_stiffness_option,
       .option_help = contact_stiffness_help},
      {.key = "level_tolerance_m",
       .member = &ContactSettings::level_tolerance_m,
       .range = Range{0.0, 0.5, "m", true},
       .description =
           "floors of the two buildings whose elevations differ by at most this form a level and can touch (m)",
       .details = "must also lie below half of every storey height. 1 mm is far above the round-off of summed "
                  "storey heights (3.3 + 3.3 + 3.3 against 4.95 + 4.95) and far below any offset a designer would "
                  "mean, so floors match exactly when the file puts them at one height. Raise it (e.g. to a slab "
                  "thickness, at most 0.5 m) only to treat slightly offset slabs as meeting face on"},
  };
  return kSpecs;
}

const Range& range_of(std::string_view key) { return *contact_setting_spec(key).range; }

void validate_gap(const std::string& key, double gap_m) { require_range(key, gap_m, range_of("gap_m")); }

std::string building_key(std::size_t index) { return fmt::format("building[{}]", index + 1); }

/// "B1 and B2", "B1, B2 and B3".
std::string building_names(const Scene& scene) {
  std::string names;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    names += (b == 0 ? "" : b + 1 == scene.buildings.size() ? " and " : ", ") + scene.buildings[b].name;
  }
  return names;
}

/// "contact.gaps.\"A:B\"", the key of a row's pair gap.
std::string pair_gap_key(const std::string& first, const std::string& second) {
  return fmt::format("contact.gaps.\"{}:{}\"", first, second);
}

void validate_contact(const ContactSettings& contact) {
  // The law first: a stiffness given for a law that has none is refused as not applying, whatever
  // its value; the ranges of every key come from the table.
  const ContactLawInfo& law = contact_law_info(contact.law);
  auto check_stiffness = [&](std::string_view key, const std::optional<double>& value) {
    if (!value || law.stiffness_key == key) return;
    throw InputError("contact." + std::string(key), format_value(*value),
                     law.stiffness_key.empty()
                         ? fmt::format("does not apply to law {} (it uses no stiffness)", law.name)
                         : fmt::format("does not apply to law {}: its stiffness is {} ({})", law.name,
                                       law.stiffness_key, law.stiffness_unit));
  };
  check_stiffness("stiffness_kN_per_m", contact.stiffness_kN_per_m);
  check_stiffness("stiffness_kN_per_m1_5", contact.stiffness_kN_per_m1_5);
  validate_keys(contact, contact_setting_specs(), "contact");
  if (contact::refuses_plastic(law.law) && contact.restitution == 0.0) {
    const char* damping = law.law == contact::ContactLaw::jankowski
                              ? "damping ratio 9 sqrt(5) (1 - e^2) / (2e (e (9 pi - 16) + 16))"
                              : "damping 8 (1 - e) / (5e)";
    throw InputError("contact.restitution", "0",
                     fmt::format("must be positive for law {}: its {} is infinite at e = 0 (use kelvin or hertzdamp "
                                 "for a plastic contact)",
                                 law.name, damping));
  }
}

void validate_levels(const Scene& scene) {
  // Below half a storey height a floor can meet at most one floor of the other building.
  const double tolerance = scene.contact.level_tolerance_m;
  for (std::size_t b = 0; b < scene.buildings.size(); ++b) {
    const std::vector<double>& heights = scene.buildings[b].storey_height_m;
    for (std::size_t s = 0; s < heights.size(); ++s) {
      if (!(tolerance < heights[s] / 2.0)) {
        throw InputError("contact.level_tolerance_m", format_value(tolerance),
                         fmt::format("must be below half of every storey height ({}.storey_height_m[{}] is {} m)",
                                     building_key(b), s + 1, heights[s]));
      }
    }
  }
  if (scene.is_row() || !scene.levels().empty() || !scene.column_candidates().empty()) return;
  const auto elevations = [&](std::size_t b) { return model::floor_elevations(scene.buildings[b]); };
  const bool columns_off = scene.contact.slab_to_column == "off";
  throw InputError(building_key(1) + ".storey_height_m",
                   fmt::format("[{}]", fmt::join(scene.buildings[1].storey_height_m, ", ")),
                   fmt::format("no floor of building 2 stands at the elevation of a floor of building 1 "
                               "(building 1's floors at {:.6g} m, building 2's at {:.6g} m, matched within "
                               "contact.level_tolerance_m = {} m){}: nothing could touch",
                               fmt::join(elevations(0), ", "), fmt::join(elevations(1), ", "), tolerance,
                               columns_off ? ", and contact.slab_to_column = \"off\" leaves out the slabs that "
                                             "would strike columns"
                               : scene.column_levels().empty()
                                   ? ""
                                   : ", and no facade column stands within reach of a slab between floors (a column "
                                     "counts when its centre lies within half its section of a facing slab edge)"));
}

/// Where slabs meet columns, column storeys: a storey given as a matrix has no columns to strike.
/// (The law is checked when a run starts, require_compliant_law_where_needed, after the overrides.)
void validate_column_storeys(const Scene& scene) {
  if (scene.is_row()) {
    for (const BuildingPair& pair : scene.pairs()) validate_column_storeys(scene.pair_scene(pair));
    return;
  }
  for (const contact::ColumnLevel& level : scene.column_levels()) {
    const std::size_t b = static_cast<std::size_t>(1 - level.slab_building);
    if (scene.buildings[b].uses_columns()) continue;
    throw InputError(fmt::format("{}.storey_stiffness[{}]", building_key(b), level.storey), "",
                     fmt::format("is a matrix, but {} floor {} ({:.6g} m) would strike the columns of {}'s storey {}: "
                                 "give that building's columns (or set contact.slab_to_column = \"off\")",
                                 scene.buildings[static_cast<std::size_t>(level.slab_building)].name, level.slab_floor,
                                 level.elevation_m, scene.buildings[b].name, level.storey));
  }
}

/// [output.floor_history]: a building's name, then floors in 1..its storeys, none twice.
void validate_floor_history(const Scene& scene) {
  for (const auto& entry : scene.output.floor_history) {
    const std::string& name = entry.first;  // not a structured binding: the lambda below captures it
    const std::vector<int>& floors = entry.second;
    const auto building = std::find_if(scene.buildings.begin(), scene.buildings.end(),
                                       [&](const model::BuildingDefinition& b) { return b.name == name; });
    const std::string key = fmt::format("output.floor_history.{}", name);
    if (building == scene.buildings.end()) {
      throw InputError(key, "", fmt::format("names no building (the buildings are {})", building_names(scene)));
    }
    std::set<int> seen;
    for (std::size_t i = 0; i < floors.size(); ++i) {
      const std::string floor_key = fmt::format("{}[{}]", key, i + 1);
      if (floors[i] < 1 || floors[i] > building->storeys) {
        throw InputError(floor_key, std::to_string(floors[i]),
                         fmt::format("lists floors of {}, numbered 1..{}", name, building->storeys));
      }
      if (!seen.insert(floors[i]).second) throw InputError(floor_key, std::to_string(floors[i]), "is listed twice");
    }
  }
}

/// Whether output.peaks keeps the storeys' drift peaks, which the pounding-induced demand and the
/// drift limit states are judged on.
bool keeps_drift_peaks(const OutputSettings& output) {
  return std::find(output.peaks.begin(), output.peaks.end(), kPeakGroups[2]) != output.peaks.end();
}

void validate_output(const OutputSettings& output, std::size_t levels) {
  std::set<int> seen;
  for (std::size_t i = 0; i < output.history_floors.size(); ++i) {
    const int level = output.history_floors[i];
    const std::string key = fmt::format("output.history_floors[{}]", i + 1);
    if (level < 1 || static_cast<std::size_t>(level) > levels) {
      throw InputError(key, std::to_string(level),
                       fmt::format("lists levels (floor pairs at a common elevation, as `pounding check` "
                                   "prints them), numbered 1..{}",
                                   levels));
    }
    if (!seen.insert(level).second) throw InputError(key, std::to_string(level), "is listed twice");
  }
  validate_keys(output, output_specs(), "output");
  for (std::size_t i = 0; i < output.peaks.size(); ++i) {
    const std::string key = fmt::format("output.peaks[{}]", i + 1), value = fmt::format("\"{}\"", output.peaks[i]);
    if (std::find(kPeakGroups.begin(), kPeakGroups.end(), output.peaks[i]) == kPeakGroups.end()) {
      throw InputError(key, value,
                       fmt::format("expected one of {} (or an empty list for no peaks)", fmt::join(kPeakGroups, ", ")));
    }
    if (std::find(output.peaks.begin(), output.peaks.begin() + static_cast<std::ptrdiff_t>(i), output.peaks[i]) !=
        output.peaks.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw InputError(key, value, "is listed twice");
    }
  }
  if (output.contact_free_reference && !keeps_drift_peaks(output)) {
    throw InputError("output.contact_free_reference", "true",
                     "compares the storeys' peak drifts: output.peaks must include \"drifts\"");
  }
}

/// Drift limit states are judged on the storeys' located peak drifts.
void validate_limit_state_outputs(const Scene& scene) {
  const auto assessed = std::find_if(scene.buildings.begin(), scene.buildings.end(),
                                     [](const model::BuildingDefinition& b) { return b.drift_limits.has_value(); });
  if (assessed == scene.buildings.end() || keeps_drift_peaks(scene.output)) return;
  std::vector<std::string> quoted;
  for (const std::string& group : scene.output.peaks) quoted.push_back(fmt::format("\"{}\"", group));
  throw InputError("output.peaks", fmt::format("[{}]", fmt::join(quoted, ", ")),
                   fmt::format("must include \"drifts\": building '{}' has [building.limit_states], judged on the "
                               "storeys' peak drifts",
                               assessed->name));
}

void validate_pair(const Scene& scene) {
  const model::Polygon& left = scene.buildings[0].slab;
  const model::Polygon& right = scene.buildings[1].slab;
  if (model::interiors_overlap(left, right)) {
    throw InputError(building_key(1) + ".slab", "", "overlaps the slab of building 1 at rest");
  }
  const std::optional<double> clearance = model::horizontal_clearance(left, right);
  if (!clearance || *clearance < 0.0) {
    throw InputError(building_key(1) + ".slab", "",
                     "building 2 must stand on the +x side of building 1, facing it over a "
                     "common range of y");
  }
  if (std::abs(*clearance - scene.contact.gap_m) > kGapTolerance_m) {
    throw InputError("contact.gap_m", format_value(scene.contact.gap_m),
                     fmt::format("disagrees with the slab outlines, whose clear distance along x "
                                 "is {} m",
                                 *clearance));
  }
}

/// A row's buildings: distinct names that a pair's key can hold, no two slabs overlapping at rest.
/// First, as the other checks find the row's pairs from its outlines.
void validate_row_buildings(const Scene& scene) {
  for (std::size_t i = 0; i < scene.buildings.size(); ++i) {
    const std::string& name = scene.buildings[i].name;
    if (name.find_first_of(":=") != std::string::npos) {
      throw InputError(building_key(i) + ".name", fmt::format("\"{}\"", name),
                       "holds ':' or '=': a row names its pairs NAME:NAME (and --gap NAME:NAME=m)");
    }
    for (std::size_t j = i + 1; j < scene.buildings.size(); ++j) {
      if (name == scene.buildings[j].name) {
        throw InputError(building_key(j) + ".name", fmt::format("\"{}\"", scene.buildings[j].name),
                         fmt::format("is also {}'s: the buildings of a row need distinct names (gaps and outputs "
                                     "name them)",
                                     building_key(i)));
      }
      if (model::interiors_overlap(scene.buildings[i].slab, scene.buildings[j].slab)) {
        throw InputError(building_key(j) + ".slab", "",
                         fmt::format("overlaps the slab of {} at rest", scene.buildings[i].name));
      }
    }
  }
}

/// A row: a neighbouring pair, each able to touch (a level or a slab facing a column, as two
/// buildings must), the stated gaps those of neighbouring pairs and equal to the outlines', no
/// contact.gap_m (checked by the reader).
void validate_row(const Scene& scene) {
  const std::vector<BuildingPair> pairs = scene.pairs();
  if (pairs.empty()) {
    throw InputError("contact.candidate_margin_m", format_value(scene.contact.candidate_margin_m),
                     fmt::format("is the farthest two buildings of a row may stand apart to touch, and no two of {} "
                                 "stand that close: nothing could touch",
                                 building_names(scene)));
  }
  for (const BuildingPair& pair : pairs) {
    const Scene two = scene.pair_scene(pair);
    if (!two.levels().empty() || !two.column_candidates().empty()) continue;
    throw InputError(
        pair_gap_key(two.buildings[0].name, two.buildings[1].name), format_value(pair.gap_m),
        fmt::format("is a neighbouring pair ({:.6g} m apart) that could never touch: no floors at a "
                    "common elevation and no slab facing a column{}. Move them farther apart than "
                    "contact.candidate_margin_m = {} m, or let their slabs meet",
                    pair.gap_m, scene.contact.slab_to_column == "off" ? " (contact.slab_to_column = \"off\")" : "",
                    scene.contact.candidate_margin_m));
  }
  for (const PairGap& stated : scene.contact.gaps) {
    const std::string key = pair_gap_key(stated.first, stated.second);
    const int a = scene.building_index(stated.first, key), b = scene.building_index(stated.second, key);
    if (a == b) throw InputError(key, format_value(stated.gap_m), "names one building twice");
    const auto pair = std::find_if(pairs.begin(), pairs.end(), [&](const BuildingPair& p) {
      return (p.first == a && p.second == b) || (p.first == b && p.second == a);
    });
    if (pair == pairs.end()) {
      const double distance = model::clearance(scene.buildings[a].slab, scene.buildings[b].slab).distance_m;
      throw InputError(key, format_value(stated.gap_m),
                       fmt::format("names no neighbouring pair: the slabs stand {:.6g} m apart, farther than "
                                   "contact.candidate_margin_m = {} m",
                                   distance, scene.contact.candidate_margin_m));
    }
    if (std::abs(pair->gap_m - stated.gap_m) > kGapTolerance_m) {
      throw InputError(key, format_value(stated.gap_m),
                       fmt::format("disagrees with the slab outlines, whose clear distance is {:.9g} m", pair->gap_m));
    }
  }
}

}  // namespace

solvers::OutputSelection OutputSettings::selection() const {
  auto asked = [&](std::string_view group) { return std::find(peaks.begin(), peaks.end(), group) != peaks.end(); };
  return {.history = history,
          .displacement_peaks = asked(kPeakGroups[0]),
          .acceleration_peaks = asked(kPeakGroups[1]),
          .drift_peaks = asked(kPeakGroups[2]),
          .member_forces = member_forces};
}

std::span<const ContactSettingSpec> contact_setting_specs() { return contact_specs(); }

std::span<const OutputSpec> output_specs() {
  static const std::vector<OutputSpec> kSpecs = {
      {.key = "history",
       .member = &OutputSettings::history,
       .description = "write `history.csv` and `contacts_history.csv`",
       .details = "`false`: neither is computed nor written (an earlier run's in the output folder are removed); "
                  "`pounding run --history off` replaces it"},
      {.key = "contact_free_reference",
       .member = &OutputSettings::contact_free_reference,
       .description = "also run the scene with the same method and settings but no contact candidates",
       .details = "the buildings move as if they never met; peaks only, no files of its own. Writes "
                  "`pounding_demand` in `summary.json`: per building and storey the peak drift ratio at the CM in "
                  "x and y with contact, without, and their ratio (and, for yielding columns, the storey's largest "
                  "ductility and column shear likewise), with the report's \"Pounding-induced demand\" lines; needs "
                  "the `drifts` group; `--contact-free-reference` on `pounding run`"},
      {.key = "member_forces",
       .member = &OutputSettings::member_forces,
       .description = "record the storeys' shears and torques and the columns' shears and end moments",
       .details = "the columns' own forces (a yielding column's spring force), without damping or P-Delta "
                  "([model.md](model.md) §2c); their peaks in `summary.json`'s `member_forces` and the run's text, "
                  "their histories as `history.csv`'s last columns (`B{b}_s{j}_Vx_kN`, `_Vy_kN`, `_T_kNm`, then per "
                  "column `B{b}_s{j}_col{n}_Vx_kN`, `_Vy_kN`, `_Mx_kNm`, `_My_kNm`); with `contact_free_reference`, "
                  "the storey shears with and without contact; `--member-forces` on `pounding run`"},
      {.key = "history_interval_s",
       .member = &OutputSettings::history_interval_s,
       .range = kHistoryInterval,
       .description = "sampling interval of `history.csv` and `contacts_history.csv` (s)",
       .details = "a compliant contact lasts a few ms at stiff settings, so resolving its force needs 1e-4"},
  };
  return kSpecs;
}

const ContactSettingSpec& contact_setting_spec(std::string_view key) {
  for (const ContactSettingSpec& spec : contact_specs()) {
    if (spec.key == key) return spec;
  }
  throw std::logic_error("no [contact] key " + std::string(key));
}

double ContactSettings::used_stiffness() const {
  const ContactLawInfo& info = contact_law_info(law);
  const std::optional<double>& given =
      info.stiffness_key == "stiffness_kN_per_m1_5" ? stiffness_kN_per_m1_5 : stiffness_kN_per_m;
  return given.value_or(info.default_stiffness);
}

void ContactSettings::set_stiffness(double value) {
  // The option is the stiffness: a scene's key of another law (the scene's own law, before
  // --contact-law changed it) no longer applies.
  stiffness_kN_per_m.reset();
  stiffness_kN_per_m1_5.reset();
  (contact_law_info(law).stiffness_key == "stiffness_kN_per_m1_5" ? stiffness_kN_per_m1_5 : stiffness_kN_per_m) = value;
}

void Scene::set_gap(double gap_m) {
  if (is_row()) {
    const std::vector<BuildingPair> neighbours = pairs();
    const BuildingPair example = neighbours.empty() ? BuildingPair{} : neighbours.front();
    throw InputError("contact.gap_m", format_value(gap_m),
                     fmt::format("is one gap, and the {} buildings of a row have one per neighbouring pair: name "
                                 "the pair (--gap {}:{}={})",
                                 buildings.size(), buildings[static_cast<std::size_t>(example.first)].name,
                                 buildings[static_cast<std::size_t>(example.second)].name, gap_m));
  }
  validate_gap("contact.gap_m", gap_m);
  const model::Point2 shift(gap_m - contact.gap_m, 0.0);
  model::BuildingDefinition& right = buildings[1];
  right.slab = right.slab.translated(shift);
  right.centre_of_mass += shift;
  for (model::Column& column : right.columns) column.position_m += shift;
  contact.gap_m = gap_m;
}

std::vector<BuildingPair> Scene::pairs() const {
  if (!is_row()) return {BuildingPair{.first = 0, .second = 1, .gap_m = contact.gap_m}};
  std::vector<BuildingPair> pairs;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    for (std::size_t j = i + 1; j < buildings.size(); ++j) {
      const model::Clearance apart = model::clearance(buildings[i].slab, buildings[j].slab);
      if (apart.distance_m > contact.candidate_margin_m) continue;
      pairs.push_back({static_cast<int>(i), static_cast<int>(j), apart.distance_m, apart.direction});
    }
  }
  return pairs;
}

Scene Scene::pair_scene(const BuildingPair& pair) const {
  Scene two = *this;
  two.buildings = {buildings[static_cast<std::size_t>(pair.first)], buildings[static_cast<std::size_t>(pair.second)]};
  two.contact.gap_m = pair.gap_m;
  two.contact.gaps.clear();
  return two;
}

namespace {

/// `definition` turned by `quarters` × 90° counter-clockwise about the origin.
void turn_building(model::BuildingDefinition& definition, int quarters) {
  constexpr double kCos[] = {1.0, 0.0, -1.0, 0.0}, kSin[] = {0.0, 1.0, 0.0, -1.0};
  const double c = kCos[quarters], s = kSin[quarters];
  const auto turn = [&](const model::Point2& p) { return model::Point2(c * p.x() - s * p.y(), s * p.x() + c * p.y()); };
  std::vector<model::Point2> outline;
  for (const model::Point2& p : definition.slab.vertices()) outline.push_back(turn(p));
  definition.slab = model::Polygon(outline);
  definition.centre_of_mass = turn(definition.centre_of_mass);
  for (model::Column& column : definition.columns) {
    column.position_m = turn(column.position_m);
    if (quarters % 2 != 0) std::swap(column.b_m, column.h_m);  // b lies along x
  }
  Eigen::Matrix3d t = Eigen::Matrix3d::Identity();  // (u, v, φ) turned: K' = T K Tᵀ
  t.topLeftCorner<2, 2>() << c, -s, s, c;
  for (Eigen::Matrix3d& k : definition.storey_stiffness) k = t * k * t.transpose();
}

}  // namespace

Scene Scene::pair_scene_facing_x(const BuildingPair& pair, double& turned_deg) const {
  Scene two = pair_scene(pair);
  const model::Point2& d = pair.direction;
  constexpr double kAxis = 1e-9;
  int quarters = 0;  // the turn that brings d onto +x
  if (std::abs(d.y()) < kAxis) {
    quarters = d.x() > 0.0 ? 0 : 2;
  } else if (std::abs(d.x()) < kAxis) {
    quarters = d.y() > 0.0 ? 3 : 1;
  } else {
    throw InputError(fmt::format("pair {}:{}", two.buildings[0].name, two.buildings[1].name), "",
                     fmt::format("faces along ({:.6g}, {:.6g}), not along a plan axis: the needed gap widens a gap "
                                 "along x or y only",
                                 d.x(), d.y()),
                     file.string());
  }
  for (model::BuildingDefinition& b : two.buildings) turn_building(b, quarters);
  const std::optional<double> along_x = model::horizontal_clearance(two.buildings[0].slab, two.buildings[1].slab);
  if (!along_x || std::abs(*along_x - pair.gap_m) > kGapTolerance_m) {  // corner to corner
    throw InputError(fmt::format("pair {}:{}", two.buildings[0].name, two.buildings[1].name), "",
                     fmt::format("stands corner to corner ({:.6g} m apart, not across facing sides): the needed gap "
                                 "widens a gap between facing sides",
                                 pair.gap_m),
                     file.string());
  }
  turned_deg = 90.0 * quarters;
  two.excitation.direction_deg = std::fmod(two.excitation.direction_deg + turned_deg, 360.0);
  return two;
}

int Scene::building_index(const std::string& building_name, const std::string& key) const {
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    if (buildings[b].name == building_name) return static_cast<int>(b);
  }
  throw InputError(key, fmt::format("\"{}\"", building_name),
                   fmt::format("names no building (the buildings are {})", building_names(*this)));
}

BuildingPair Scene::named_pair(const std::string& names, const std::string& key) const {
  std::string listed;
  for (const BuildingPair& p : pairs()) {
    listed += fmt::format("{}{}:{}", listed.empty() ? "" : ", ", buildings[static_cast<std::size_t>(p.first)].name,
                          buildings[static_cast<std::size_t>(p.second)].name);
  }
  const std::size_t colon = names.find(':');
  if (colon == std::string::npos || names.find(':', colon + 1) != std::string::npos) {
    throw InputError(key, names, fmt::format("expected NAME:NAME, a neighbouring pair ({})", listed));
  }
  const int a = building_index(names.substr(0, colon), key), b = building_index(names.substr(colon + 1), key);
  for (const BuildingPair& p : pairs()) {
    if ((p.first == a && p.second == b) || (p.first == b && p.second == a)) return p;
  }
  throw InputError(key, names, fmt::format("names no neighbouring pair (the pairs are {})", listed));
}

void Scene::set_pair_gap(const std::string& first, const std::string& second, double gap_m) {
  const std::string key = pair_gap_key(first, second);
  const int a = building_index(first, key), b = building_index(second, key);
  if (!is_row()) {
    if (a == b) throw InputError(key, format_value(gap_m), "names one building twice");
    set_gap(gap_m);
    return;
  }
  validate_gap(key, gap_m);
  const std::vector<BuildingPair> neighbours = pairs();
  const auto pair = std::find_if(neighbours.begin(), neighbours.end(), [&](const BuildingPair& p) {
    return (p.first == a && p.second == b) || (p.first == b && p.second == a);
  });
  if (pair == neighbours.end()) throw InputError(key, format_value(gap_m), "names no neighbouring pair");
  if (std::abs(gap_m - pair->gap_m) <= kGapTolerance_m) return;  // as it stands (a ring's too)
  if (gap_m > contact.candidate_margin_m) {
    throw InputError(key, format_value(gap_m),
                     fmt::format("is wider than contact.candidate_margin_m = {} m: the two would no longer be "
                                 "neighbours, and could not touch (raise the margin to study wider gaps)",
                                 contact.candidate_margin_m));
  }
  // The buildings on the second's side: reachable from it through neighbouring pairs but this one.
  std::vector<bool> moves(buildings.size(), false);
  std::vector<int> stack{pair->second};
  moves[static_cast<std::size_t>(pair->second)] = true;
  while (!stack.empty()) {
    const int from = stack.back();
    stack.pop_back();
    for (const BuildingPair& p : neighbours) {
      if (&p == &*pair || (p.first != from && p.second != from)) continue;
      const int to = p.first == from ? p.second : p.first;
      if (to == pair->first) {
        throw InputError(key, format_value(gap_m),
                         "lies on a ring of neighbouring pairs (moving one of the two would move the other): move "
                         "the buildings in the file instead");
      }
      if (!moves[static_cast<std::size_t>(to)]) {
        moves[static_cast<std::size_t>(to)] = true;
        stack.push_back(to);
      }
    }
  }
  const model::Point2 shift = (gap_m - pair->gap_m) * pair->direction;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    if (!moves[i]) continue;
    model::BuildingDefinition& moved = buildings[i];
    moved.slab = moved.slab.translated(shift);
    moved.centre_of_mass += shift;
    for (model::Column& column : moved.columns) column.position_m += shift;
  }
  const double reached = model::clearance(buildings[static_cast<std::size_t>(pair->first)].slab,
                                          buildings[static_cast<std::size_t>(pair->second)].slab)
                             .distance_m;
  if (std::abs(reached - gap_m) > kGapTolerance_m) {
    throw InputError(key, format_value(gap_m),
                     fmt::format("cannot be set by moving {} along one direction (the move gives {} m): move the "
                                 "buildings in the file instead",
                                 buildings[static_cast<std::size_t>(pair->second)].name, reached));
  }
  for (PairGap& stated : contact.gaps) {
    const int sa = building_index(stated.first, key), sb = building_index(stated.second, key);
    if ((sa == a && sb == b) || (sa == b && sb == a)) stated.gap_m = gap_m;
  }
}

std::vector<contact::Level> Scene::levels() const {
  if (is_row()) {
    std::vector<contact::Level> levels;
    for (const BuildingPair& pair : pairs()) {
      for (contact::Level level : pair_scene(pair).levels()) {
        level.index = static_cast<int>(levels.size()) + 1;
        level.pair = {pair.first, pair.second};
        levels.push_back(level);
      }
    }
    return levels;
  }
  return contact::common_levels({model::floor_elevations(buildings[0]), model::floor_elevations(buildings[1])},
                                contact.level_tolerance_m);
}

namespace {

/// require_compliant_law_where_needed() on a two-building scene; errors name `file`.
void require_no_column_contact(const Scene& pair, const std::string& file) {
  const std::vector<contact::ColumnLevel> levels = pair.column_levels();
  if (levels.empty()) return;
  const contact::ColumnLevel& first = levels.front();
  throw InputError(
      "contact.law", fmt::format("\"{}\"", pair.contact.law),
      fmt::format("cannot resolve slab-to-column contact: {} floor {} ({:.6g} m) stands between floors of {} and would "
                  "strike the columns of its storey {} (and {} such floor{} in all). Use a compliant law (kelvin, "
                  "hertzdamp, hertzdamp-ye or jankowski), whose force the column's two floors share, or set "
                  "contact.slab_to_column = \"off\" to leave such contacts out",
                  pair.buildings[first.slab_building].name, first.slab_floor, first.elevation_m,
                  pair.buildings[1 - first.slab_building].name, first.storey, levels.size(),
                  levels.size() == 1 ? "" : "s"),
      file);
}

}  // namespace

void require_compliant_law_where_needed(const Scene& scene) {
  if (contact_law_info(scene.contact.law).law != contact::ContactLaw::impulse) return;
  if (!scene.is_row()) return require_no_column_contact(scene, scene.file.string());
  for (const BuildingPair& pair : scene.pairs()) require_no_column_contact(scene.pair_scene(pair), scene.file.string());
}

std::vector<contact::Candidate> Scene::column_candidates() const {
  if (is_row()) {
    std::vector<contact::Candidate> candidates;
    for (const BuildingPair& pair : pairs()) {
      std::vector<contact::Candidate> found = pair_scene(pair).column_candidates();
      contact::place_in_pair(found, {pair.first, pair.second}, 0);
      candidates.insert(candidates.end(), found.begin(), found.end());
    }
    return candidates;
  }
  return contact::find_column_candidates({&buildings[0], &buildings[1]}, column_levels(),
                                         {.margin_m = contact.candidate_margin_m, .gap_m = contact.gap_m});
}

std::vector<contact::ColumnLevel> Scene::column_levels() const {
  if (contact.slab_to_column == "off" || is_row()) return {};
  return contact::column_levels({model::floor_elevations(buildings[0]), model::floor_elevations(buildings[1])},
                                contact.level_tolerance_m);
}

void Scene::validate() const {
  if (name.empty()) throw InputError("name", "\"\"", "must not be empty", file.string());
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    try {
      buildings[i].validate();
      if (buildings[i].drift_limits) validate_drift_limits(*buildings[i].drift_limits);
      if (buildings[i].shear_capacity) validate_shear_capacity(*buildings[i].shear_capacity);
      if (buildings[i].flexural_strength) validate_flexural_strength(buildings[i]);
    } catch (const InputError& error) {
      throw error.in_context(file.string(), building_key(i));
    }
  }
  try {
    if (is_row()) validate_row_buildings(*this);
    excitation.validate();
    validate_contact(contact);
    validate_levels(*this);
    validate_column_storeys(*this);
    solver.validate();
    validate_output(output, levels().size());
    validate_limit_state_outputs(*this);
    validate_floor_history(*this);
    is_row() ? validate_row(*this) : validate_pair(*this);
  } catch (const InputError& error) {
    throw error.in_context(file.string());
  }
}

std::vector<std::array<int, 2>> Scene::history_other_floors() const {
  std::vector<std::array<int, 2>> floors;
  for (const auto& [name, listed] : output.floor_history) {
    const int b = building_index(name, "output.floor_history." + name);
    for (int floor : listed) floors.push_back({b, floor});
  }
  return floors;
}

}  // namespace pounding::analysis
