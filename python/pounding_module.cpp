// The bindings behind `import pounding` (python/pounding/__init__.py is the public API): the
// library called the way apps/commands.cpp calls it, its documents handed over as the JSON text the
// command line writes (so the keys cannot drift from summary.json, gap.json and the modes JSON)
// and its tables as numpy arrays. Runs release the GIL, so Python threads run them in parallel.

#include <algorithm>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <map>
#include <optional>
#include <tuple>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/methods.hpp"
#include "pounding/analysis/modal_summary.hpp"
#include "pounding/analysis/needed_gap.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/excitation/record_choice.hpp"
#include "pounding/excitation/spectrum.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/gap_writer.hpp"
#include "pounding/io/impact_schema.hpp"
#include "pounding/io/json_report.hpp"
#include "pounding/io/output_schema.hpp"
#include "pounding/io/provenance.hpp"
#include "pounding/io/record_list.hpp"
#include "pounding/io/run_report.hpp"
#include "pounding/io/run_writer.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/model/building.hpp"
#include "pounding/solvers/run_budget.hpp"
#include "pounding/version.hpp"

namespace py = pybind11;
using pounding::InputError;
using pounding::analysis::Scene;

namespace {

/// A run and what it was run on: the inputs of run_json(), full_report() and the arrays.
struct Run {
  pounding::analysis::RunReport report;
  pounding::io::Provenance provenance;
};

/// The needed-gap analysis of a scene, with the scene's name for gap_json().
struct Gap {
  std::string scene;
  pounding::analysis::NeededGap gap;
};

/// `rows` × `columns` doubles, filled by value(row, column).
template <typename Value>
py::array_t<double> matrix(std::size_t rows, std::size_t columns, Value value) {
  py::array_t<double> array({rows, columns});
  auto cells = array.mutable_unchecked<2>();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) cells(r, c) = value(r, c);
  }
  return array;
}

/// `scene`'s error with the scene file named, as the readers name it for the command line.
[[noreturn]] void rethrow_in_scene(const InputError& error, const Scene& scene) {
  throw error.in_context(scene.file.string());
}

Scene with_pair_gap(Scene scene, const std::string& first, const std::string& second, double gap_m) {
  try {
    scene.set_pair_gap(first, second, gap_m);
    scene.validate();
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

Scene with_gap(Scene scene, double gap_m) {
  try {
    scene.set_gap(gap_m);
    scene.validate();
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

/// The scene with its record turned to direction_deg (H1's; a pair's H2 at + 90°), as --direction-deg.
Scene with_direction(Scene scene, double direction_deg) {
  try {
    scene.excitation.direction_deg = direction_deg;
    scene.excitation.validate();
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

Scene with_restitution(Scene scene, double restitution) {
  try {
    scene.contact.restitution = restitution;
    scene.validate();
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

/// The scene with output.history and output.peaks replaced (None: kept), checked, as `run
/// --history --peaks` replace them.
Scene with_outputs(Scene scene, std::optional<bool> history, std::optional<std::vector<std::string>> peaks,
                   std::optional<bool> member_forces) {
  try {
    if (history) scene.output.history = *history;
    if (peaks) scene.output.peaks = std::move(*peaks);
    if (member_forces) scene.output.member_forces = *member_forces;
    scene.validate();
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

/// excitation::with_record(), as `run --record ...` applies it, then (`read`) the record read once
/// so that a record that cannot be read or scales beyond 10 g is refused now (io::read_scene does
/// the same). Without `read` only the choice and the file's existence are checked, as a record
/// list's line is (a sweep checks its records so, and leaves reading them to its runs).
Scene with_record(Scene scene, const pounding::excitation::RecordChoice& choice, bool read) {
  try {
    scene.excitation = pounding::excitation::with_record(scene.excitation, choice);
    if (read) pounding::excitation::load_ground_motion(pounding::analysis::resolved_excitation(scene));
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

/// A Python int, float or str as a setting's value (SolverSettings::set checks it against the
/// setting's type); anything else is refused naming `solver.<key>`.
pounding::analysis::SettingValue setting_value(pounding::analysis::Setting setting, py::handle value) {
  if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) return value.cast<int>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  const auto& spec = pounding::analysis::spec(setting);
  throw InputError("solver." + std::string(spec.key), py::str(py::repr(value)),
                   "expected " + pounding::analysis::expected_text(spec));
}

/// The scene with the method and settings replacing its own (as the options do in
/// cli::apply_run_options), checked, the contact law against the method too (as run_scene does):
/// what run() runs.
/// @pre every key of `settings` is a [solver] key (the Python layer refuses others by name).
Scene with_solver(Scene scene, const std::optional<std::string>& method, const py::dict& settings) {
  try {
    if (method) scene.solver = pounding::analysis::with_method(scene.solver, *method);
    for (const pounding::analysis::SettingSpec& spec : pounding::analysis::setting_specs()) {
      const py::str key(std::string(spec.key));
      if (settings.contains(key)) scene.solver.set(spec.id, setting_value(spec.id, settings[key]));
    }
    scene.validate();
    pounding::analysis::require_supported(pounding::analysis::contact_law_info(scene.contact.law),
                                          pounding::analysis::method_info(scene.solver.method));
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  return scene;
}

/// A Python keyword's value as a key's (key_spec.hpp): a whole number for an integer key (numpy's
/// too), a number for a number key, str for a text key, True or False for a boolean one.
/// @throws InputError naming `keyword`: a value of another type, or a whole number too large for
///   C++ (said with the key's range, which the library checks for every other value).
template <typename Owner>
pounding::analysis::KeyValue key_value(py::handle value, const pounding::analysis::KeySpec<Owner>& spec,
                                       const std::string& keyword) {
  const std::string_view type = pounding::analysis::type_name(spec);
  std::string text = py::str(py::repr(value));
  if (text.size() > 40) text = text.substr(0, 40) + "...";
  if (type == "string") {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    throw InputError(keyword, text, "expected a string");
  }
  if (type == "boolean") {  // set_key takes "true" or "false"
    if (py::isinstance<py::bool_>(value)) return std::string(value.cast<bool>() ? "true" : "false");
    throw InputError(keyword, text, "expected True or False");
  }
  const bool whole = !py::isinstance<py::bool_>(value) && PyIndex_Check(value.ptr()) != 0;
  if (whole && type == "integer") {
    const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
    int overflow = 0;
    const long number = PyLong_AsLongAndOverflow(index.ptr(), &overflow);
    if (overflow != 0) throw InputError(keyword, text, "must lie in " + pounding::range_text(*spec.range));
    return number;
  }
  if (type == "number" && !py::isinstance<py::bool_>(value) && py::hasattr(value, "__float__")) {
    return value.cast<double>();
  }
  throw InputError(keyword, text, type == "integer" ? "expected a whole number" : "expected a number");
}

/// The [contact] options given as Python keywords (python_keyword() of each row's option; the gap
/// is load_scene's own argument), keyed by option as io::SceneOverrides::contact takes them.
std::map<std::string, pounding::analysis::KeyValue, std::less<>> contact_options(const py::dict& keywords) {
  std::map<std::string, pounding::analysis::KeyValue, std::less<>> options;
  for (const auto& spec : pounding::analysis::contact_setting_specs()) {
    const std::string keyword = pounding::analysis::python_keyword(spec.option);
    if (keyword.empty() || !keywords.contains(keyword) || options.contains(spec.option)) continue;
    options.emplace(spec.option, key_value(keywords[py::str(keyword)], spec, keyword));
  }
  return options;
}

/// The run limits given as keywords (limit_specs(): the key is the keyword), checked.
/// @throws InputError naming the keyword.
pounding::analysis::RunLimits run_limits(const py::dict& keywords) {
  pounding::analysis::RunLimits limits;
  std::map<std::string, std::string> names;
  for (const auto& spec : pounding::analysis::limit_specs()) {
    const std::string keyword(spec.key);
    names["limits." + keyword] = keyword;
    if (keywords.contains(keyword)) {
      pounding::analysis::set_key(limits, spec, "limits", key_value(keywords[py::str(keyword)], spec, keyword));
    }
  }
  try {
    limits.validate();
  } catch (const InputError& error) {
    throw error.renamed(names);
  }
  return limits;
}

/// `pounding run` without files: with_solver(), the limits checked, then the run with the GIL
/// released.
Run run(Scene scene, const std::optional<std::string>& method, const py::dict& settings,
        const py::dict& limit_keywords) {
  scene = with_solver(std::move(scene), method, settings);
  pounding::analysis::RunLimits limits;
  try {
    limits = run_limits(limit_keywords);
  } catch (const InputError& error) {
    rethrow_in_scene(error, scene);
  }
  Run result;
  result.provenance = pounding::io::make_provenance(scene);
  py::gil_scoped_release unlocked;
  result.report = pounding::analysis::run_scene(scene, limits);
  return result;
}

/// Which of the fields marked for some scenes only the run's impacts carry (impact_schema.hpp).
pounding::io::ImpactFieldSet impact_fields(const Run& run) {
  return pounding::io::impact_field_set(run.report.candidates);
}

py::array_t<double> impact_table(const Run& run) {
  const auto& impacts = run.report.result.impacts;
  std::vector<std::vector<double>> rows;
  for (const auto& impact : impacts) {
    std::vector<double>& row = rows.emplace_back();
    for (const pounding::io::ImpactField* field : pounding::io::impact_fields(impact_fields(run))) {
      const std::vector<double> values = field->values(impact);
      row.insert(row.end(), values.begin(), values.end());
    }
  }
  return matrix(rows.size(), pounding::io::impact_csv_columns(impact_fields(run)).size(),
                [&](std::size_t r, std::size_t c) { return rows[r][c]; });
}

/// impacts.csv's columns with their types ("real", "integer", "flag").
/// `slab_to_column`, `row`: with the slab-to-column fields, the row fields.
std::vector<std::pair<std::string, std::string>> impact_columns(bool slab_to_column, bool row) {
  std::vector<std::pair<std::string, std::string>> columns;
  for (const pounding::io::ImpactField* field :
       pounding::io::impact_fields({.slab_to_column = slab_to_column, .row = row})) {
    using Type = pounding::io::ImpactField::Type;
    const char* type = field->type == Type::real ? "real" : field->type == Type::integer ? "integer" : "flag";
    for (const std::string& column : field->csv_columns()) columns.emplace_back(column, type);
  }
  return columns;
}

/// The history as history.csv holds it: one row a sample, t_s first, columns as history_columns.
py::array_t<double> history_table(const Run& run) {
  const pounding::solvers::History& h = run.report.result.history;
  return matrix(h.time_s.size(), h.columns.size(), [&](std::size_t r, std::size_t c) {
    return c == 0 ? h.time_s[r] : h.rows[r][static_cast<Eigen::Index>(c - 1)];
  });
}

/// contacts_history.csv's rows (one per contact and instant), its columns contact_force_columns().
py::array_t<double> contact_force_table(const Run& run) {
  const auto& samples = run.report.result.history.contact_forces;
  const auto& columns = pounding::io::contact_force_columns();
  return matrix(samples.size(), columns.size(),
                [&](std::size_t r, std::size_t c) { return columns[c].value(samples[r]); });
}

Gap find_needed_gap(const Scene& scene, const pounding::solvers::RunBudget& budget, bool all_angles) {
  Gap result{scene.name, {}};
  py::gil_scoped_release unlocked;
  result.gap = pounding::analysis::needed_gap(scene, budget);
  if (all_angles) pounding::analysis::add_all_angles(scene, result.gap, budget);
  return result;
}

py::array_t<double> touch_gap_table(const Gap& gap) {
  const auto& columns = gap.gap.history_touch_gap_m;
  return matrix(gap.gap.history_t_s.size(), columns.size(),
                [&](std::size_t r, std::size_t c) { return columns[c][r]; });
}

/// The records of a list file or folder (`pounding gap --records`, read by the same reader with the
/// same errors), one dict each: name, source ("set.txt:12") and what the line chose, as
/// Scene.with_record's arguments (file resolved against the list's folder; None: the scene's).
py::list record_list(const Scene& scene, const std::filesystem::path& list_or_folder) {
  py::list entries;
  for (const pounding::analysis::RecordEntry& entry :
       pounding::io::read_record_list(list_or_folder, scene.excitation)) {
    const pounding::excitation::RecordChoice& choice = entry.choice;
    py::dict item;
    item["name"] = entry.name;
    item["source"] = entry.source;
    item["file"] = choice.file ? py::cast(choice.file->string()) : py::none();
    item["format"] = choice.format;
    item["units"] = choice.units;
    item["dt_s"] = choice.dt_s;
    item["accel_column"] = choice.accel_column;
    item["scale_factor"] = choice.scale_factor;
    item["scale_to_pga_g"] = choice.pga_g;
    item["scale_to_sa"] = choice.sa;
    item["record2"] = choice.second_file ? py::cast(choice.second_file->string()) : py::none();
    item["record2_column"] = choice.second_accel_column;
    item["direction_deg"] = choice.direction_deg;
    entries.append(item);
  }
  return entries;
}

/// An Eigen matrix as a numpy array (a copy).
py::array_t<double> array_of(const Eigen::MatrixXd& m) {
  return matrix(
      static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols()),
      [&](std::size_t r, std::size_t c) { return m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)); });
}

/// Each building's assembled model, as the runs build it (model::make_building): M, K, C (3N×3N,
/// floor 1's u, v, φ first) and the mode shapes as columns, longest period first, mass-normalised.
py::list building_matrices(const Scene& scene) {
  py::list buildings;
  for (std::size_t i = 0; i < scene.buildings.size(); ++i) {
    pounding::model::Building building;
    try {
      building = pounding::model::make_building(scene.buildings[i]);
    } catch (const InputError& error) {
      throw error.in_context(scene.file.string(), "building[" + std::to_string(i + 1) + "]");
    }
    Eigen::MatrixXd shapes(building.dof(), static_cast<Eigen::Index>(building.modes.size()));
    for (std::size_t j = 0; j < building.modes.size(); ++j)
      shapes.col(static_cast<Eigen::Index>(j)) = building.modes[j].shape;
    py::dict item;
    item["M"] = array_of(building.mass_diagonal.asDiagonal().toDenseMatrix());
    item["K"] = array_of(building.stiffness);
    item["C"] = array_of(building.damping);
    item["shapes"] = array_of(shapes);
    buildings.append(item);
  }
  return buildings;
}

}  // namespace

PYBIND11_MODULE(_pounding, m) {
  m.doc() = "Bindings of the pounding library; use the package `pounding`, not this module.";

  // InputError becomes pounding.InputError (a ValueError defined in __init__.py) with its parts.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputError& error) {
      const py::object type = py::module_::import("pounding").attr("InputError");
      const py::object instance = type(error.what(), error.file(), error.key(), error.value(), error.reason());
      PyErr_SetObject(type.ptr(), instance.ptr());
    }
  });

  m.attr("__version__") = std::string(pounding::program_version());
  m.attr("git_commit") = std::string(pounding::git_commit());  // as `pounding --version`; empty if unknown
  m.def("setting_keys", [] {
    std::vector<std::string> keys;
    for (const auto& spec : pounding::analysis::setting_specs()) keys.emplace_back(spec.key);
    return keys;
  });
  m.def("method_names", [] {
    std::vector<std::string> names;
    for (const auto& method : pounding::analysis::methods()) names.emplace_back(method.name);
    return names;
  });
  m.def("impact_columns", &impact_columns, py::arg("slab_to_column") = false, py::arg("row") = false);

  py::class_<Scene>(m, "Scene",
                    "A scene read and checked by pounding.load_scene(); its with_* methods return changed copies")
      .def_readonly("name", &Scene::name, "The scene's name (its file's `name`)")
      .def_property_readonly(
          "file", [](const Scene& s) { return s.file; }, "The scene file it was read from")
      .def_property_readonly(
          "gap_m", [](const Scene& s) { return s.is_row() ? std::nullopt : std::optional(s.contact.gap_m); },
          "contact.gap_m: the clear gap at rest (m); None for a row (pair_gaps has its gaps)")
      .def_property_readonly(
          "restitution", [](const Scene& s) { return s.contact.restitution; },
          "contact.restitution: the coefficient of restitution")
      .def_property_readonly(
          "method", [](const Scene& s) { return s.solver.method; }, "solver.method (pounding.methods())")
      .def_property_readonly(
          "contact_law", [](const Scene& s) { return s.contact.law; }, "contact.law")
      .def_property_readonly(
          "contact_stiffness",
          [](const Scene& s) -> std::optional<double> {
            if (pounding::analysis::contact_law_info(s.contact.law).stiffness_key.empty()) return std::nullopt;
            return s.contact.used_stiffness();
          },
          "The stiffness the contact law uses, in its unit (the scene's, else the law's default); None for impulse")
      .def_property_readonly(
          "record_file", [](const Scene& s) { return s.excitation.file; }, "excitation.file: the record")
      .def_property_readonly(
          "record2_file",
          [](const Scene& s) -> std::optional<std::filesystem::path> {
            if (!s.excitation.second) return std::nullopt;
            return s.excitation.second->file;
          },
          "excitation.second.file: a pair's second horizontal component (None for one component)")
      .def_property_readonly(
          "history", [](const Scene& s) { return s.output.history; }, "output.history: whether runs keep the history")
      .def_property_readonly(
          "peaks", [](const Scene& s) { return s.output.peaks; }, "output.peaks: the peak groups runs report")
      .def_property_readonly(
          "member_forces", [](const Scene& s) { return s.output.member_forces; },
          "output.member_forces: whether runs record the storeys' and columns' forces")
      .def_property_readonly(
          "contact_free_reference", [](const Scene& s) { return s.output.contact_free_reference; },
          "output.contact_free_reference: whether runs also run without contact, for the pounding-induced demand")
      .def_property_readonly(
          "yielding",
          [](const Scene& s) {
            return std::any_of(s.buildings.begin(), s.buildings.end(),
                               [](const pounding::model::BuildingDefinition& b) { return b.hysteresis.yields(); });
          },
          "Whether some building's columns yield ([building.hysteresis])")
      .def_property_readonly(
          "building_names",
          [](const Scene& s) {
            std::vector<std::string> names;
            for (const auto& b : s.buildings) names.push_back(b.name);
            return names;
          },
          "The buildings' names, in the file's order (two, or a row's)")
      .def_property_readonly(
          "pair_gaps",
          [](const Scene& s) {
            std::vector<std::pair<std::string, double>> gaps;
            for (const pounding::analysis::BuildingPair& p : s.pairs()) {
              gaps.emplace_back(s.buildings[static_cast<std::size_t>(p.first)].name + ":" +
                                    s.buildings[static_cast<std::size_t>(p.second)].name,
                                p.gap_m);
            }
            return gaps;
          },
          "The neighbouring pairs' gaps, as [(\"B1:B2\", m), ...] (two buildings: the one pair, contact.gap_m)")
      .def(
          "pair_scenes",
          [](const Scene& s) {
            std::vector<std::tuple<std::string, double, Scene>> scenes;
            for (const pounding::analysis::BuildingPair& p : s.pairs()) {
              double turned_deg = 0.0;
              try {
                Scene two = s.pair_scene_facing_x(p, turned_deg);
                scenes.emplace_back(s.buildings[static_cast<std::size_t>(p.first)].name + ":" +
                                        s.buildings[static_cast<std::size_t>(p.second)].name,
                                    turned_deg, std::move(two));
              } catch (const InputError& error) {
                rethrow_in_scene(error, s);
              }
            }
            return scenes;
          },
          "Each neighbouring pair's scene of two buildings, turned in plan so that they face along x, as "
          "`pounding gap` analyses a row: [(\"B1:B2\", turned_deg, Scene), ...]")
      .def_property_readonly(
          "slab_to_column",
          [](const Scene& s) { return pounding::contact::has_column_pairs(pounding::analysis::scene_candidates(s)); },
          "Whether some slab can strike the other building's columns (docs/model.md 6b): its runs' impacts then "
          "carry the column's fields")
      .def("with_gap", &with_gap, py::arg("gap_m"),
           "The scene with building 2 moved along x to the clear gap gap_m (m), as `run --gap`")
      .def("with_pair_gap", &with_pair_gap, py::arg("first"), py::arg("second"), py::arg("gap_m"),
           "The scene with the neighbouring pair first:second (building names) gap_m (m) apart, as `run --gap "
           "FIRST:SECOND=M` (the pair's second building moves, with its neighbours beyond)")
      .def("with_outputs", &with_outputs, py::arg("history") = py::none(), py::arg("peaks") = py::none(),
           py::arg("member_forces") = py::none(),
           "The scene with output.history (bool), output.peaks (a list of peak groups: displacements, "
           "accelerations, drifts) and output.member_forces (bool: storey and column forces) replaced; None keeps "
           "the scene's")
      .def("with_direction", &with_direction, py::arg("direction_deg"),
           "The scene with excitation.direction_deg replaced (the record's angle from +x; a pair's second component "
           "at + 90 degrees), as `run --direction-deg`")
      .def("with_restitution", &with_restitution, py::arg("restitution"),
           "The scene with contact.restitution replaced, as `run --restitution`")
      .def(
          "_with_record",
          [](const Scene& scene, std::filesystem::path file, std::optional<std::string> format,
             std::optional<std::string> units, std::optional<double> scale_factor, std::optional<double> scale_to_pga_g,
             std::optional<double> direction_deg, std::optional<double> dt_s, std::optional<int> accel_column,
             std::optional<std::filesystem::path> record2, std::optional<int> record2_column,
             std::optional<std::string> scale_to_sa, bool read) {
            return with_record(scene,
                               {.file = std::move(file),
                                .format = std::move(format),
                                .units = std::move(units),
                                .dt_s = dt_s,
                                .accel_column = accel_column,
                                .scale_factor = scale_factor,
                                .pga_g = scale_to_pga_g,
                                .sa = std::move(scale_to_sa),
                                .direction_deg = direction_deg,
                                .second_file = std::move(record2),
                                .second_accel_column = record2_column},
                               read);
          },
          py::arg("file"), py::arg("format"), py::arg("units"), py::arg("scale_factor"), py::arg("scale_to_pga_g"),
          py::arg("direction_deg"), py::arg("dt_s"), py::arg("accel_column"), py::arg("record2"),
          py::arg("record2_column"), py::arg("scale_to_sa"), py::arg("read"))
      .def("_with_solver", &with_solver, py::arg("method"), py::arg("settings"));

  m.def(
      "load_scene",
      [](const std::filesystem::path& file, std::optional<double> gap_m, std::vector<std::string> gaps,
         const py::dict& contact) {
        return pounding::io::read_scene(file,
                                        {.gap_m = gap_m, .gaps = std::move(gaps), .contact = contact_options(contact)});
      },
      py::arg("file"), py::arg("gap_m"), py::arg("gaps"), py::arg("contact"));
  m.def(
      "scene_from_toml",
      [](const std::string& text, const std::filesystem::path& anchor, std::optional<double> gap_m,
         std::vector<std::string> gaps, const py::dict& contact) {
        Scene scene = pounding::io::parse_scene(
            text, anchor, {.gap_m = gap_m, .gaps = std::move(gaps), .contact = contact_options(contact)});
        scene.file.clear();  // built in code: no file to hash, provenance says so (scene_file null)
        return scene;
      },
      py::arg("text"), py::arg("anchor"), py::arg("gap_m"), py::arg("gaps"), py::arg("contact"));
  m.def("contact_keywords", [] {  // load_scene()'s keywords besides the gap, one per option
    std::vector<std::string> keywords;
    for (const auto& spec : pounding::analysis::contact_setting_specs()) {
      if (spec.option.empty() || spec.option == "--gap") continue;
      const std::string keyword = pounding::analysis::python_keyword(spec.option);
      if (std::find(keywords.begin(), keywords.end(), keyword) == keywords.end()) keywords.push_back(keyword);
    }
    return keywords;
  });
  m.def("contact_laws", [] {  // `pounding laws`' table: name, stiffness key and unit, default, methods
    py::list laws;
    for (const pounding::analysis::ContactLawInfo& law : pounding::analysis::contact_laws()) {
      py::list methods;
      for (std::string_view method : law.methods) methods.append(std::string(method));
      py::dict entry;
      entry["name"] = std::string(law.name);
      entry["stiffness_key"] =
          law.stiffness_key.empty() ? py::object(py::none()) : py::str(std::string(law.stiffness_key));
      entry["stiffness_unit"] = std::string(law.stiffness_unit);
      entry["default_stiffness"] = law.default_stiffness;
      entry["methods"] = methods;
      laws.append(entry);
    }
    return laws;
  });
  m.def("limit_keys", [] {
    std::vector<std::string> keys;
    for (const auto& spec : pounding::analysis::limit_specs()) keys.emplace_back(spec.key);
    return keys;
  });
  m.def(
      "contact_law_stiffness_key",
      [](const std::string& law) {
        return std::string(pounding::analysis::contact_law_info(law, "contact_law").stiffness_key);
      },
      py::arg("law"));
  m.def("record_list", &record_list, py::arg("scene"), py::arg("list_or_folder"));

  m.def("building_matrices", &building_matrices, py::arg("scene"));
  m.def(
      "ground_motion",
      [](const Scene& scene) {
        const pounding::excitation::GroundMotion motion = pounding::analysis::scene_ground_motion(scene);
        py::dict result;
        const auto& t = motion.time_s();
        result["time_s"] = py::array_t<double>(py::ssize_t(t.size()), t.data());
        for (int c = 0; c < motion.component_count(); ++c) {
          const auto& a = motion.accel_mps2(c);
          result[c == 0 ? "h1_mps2" : "h2_mps2"] = py::array_t<double>(py::ssize_t(a.size()), a.data());
        }
        if (!motion.is_pair()) result["h2_mps2"] = py::none();
        result["direction_deg"] = scene.excitation.direction_deg;
        result["record_scale"] = motion.record_scale();
        return result;
      },
      py::arg("scene"));
  m.def("default_periods_s", &pounding::excitation::default_periods_s);
  m.def(
      "response_spectrum",
      [](std::vector<double> time_s, std::vector<double> accel_mps2, std::vector<double> periods_s,
         double damping_ratio) {
        const pounding::excitation::SpectrumOptions options{.periods_s = std::move(periods_s),
                                                            .damping_ratio = damping_ratio};
        const auto ordinates =
            pounding::excitation::response_spectrum({std::move(time_s), std::move(accel_mps2)}, options);
        return matrix(ordinates.size(), 5, [&](std::size_t r, std::size_t c) {
          const auto& o = ordinates[r];
          const double values[] = {o.period_s, o.sd_m, o.psv_mps, o.psa_mps2, o.peak_time_s};
          return values[c];
        });
      },
      py::arg("time_s"), py::arg("accel_mps2"), py::arg("periods_s"), py::arg("damping_ratio"));
  m.def(
      "rotd_spectrum",
      [](std::vector<double> time_s, std::vector<double> first_mps2, std::vector<double> second_mps2,
         std::vector<double> periods_s, double damping_ratio, double angle_step_deg) {
        const pounding::excitation::SpectrumOptions options{.periods_s = std::move(periods_s),
                                                            .damping_ratio = damping_ratio};
        const auto ordinates = pounding::excitation::rotd_spectrum(
            {time_s, std::move(first_mps2)}, {time_s, std::move(second_mps2)}, options, angle_step_deg);
        return matrix(ordinates.size(), 6, [&](std::size_t r, std::size_t c) {
          const auto& o = ordinates[r];
          const double values[] = {o.period_s,          o.rotd50_sd_m,     o.rotd100_sd_m,
                                   o.rotd100_angle_deg, o.rotd50_psa_mps2, o.rotd100_psa_mps2};
          return values[c];
        });
      },
      py::arg("time_s"), py::arg("first_mps2"), py::arg("second_mps2"), py::arg("periods_s"), py::arg("damping_ratio"),
      py::arg("angle_step_deg"));
  m.def("output_schema_json", [] { return pounding::io::output_schema_json().dump(); });
  m.def("modes_json", [](const Scene& scene) {
    return pounding::io::modes_json(pounding::analysis::summarise_buildings(scene)).dump();
  });

  py::class_<Run>(m, "Run")
      .def("summary_json", [](const Run& r) { return pounding::io::run_json(r.report, r.provenance).dump(); })
      .def("full_report", [](const Run& r) { return pounding::io::full_report(r.report); })
      .def("brief_report", [](const Run& r) { return pounding::io::brief_report(r.report); })
      .def("impact_table", &impact_table)
      .def("impact_fields",
           [](const Run& r) {
             const pounding::io::ImpactFieldSet set = impact_fields(r);
             return std::pair{set.slab_to_column, set.row};
           })
      .def("history_columns", [](const Run& r) { return r.report.result.history.columns; })
      .def("history_table", &history_table)
      .def("contact_force_columns",
           [](const Run&) { return pounding::io::column_names(pounding::io::contact_force_columns()); })
      .def("contact_force_table", &contact_force_table)
      .def("yielding_csv", [](const Run& r) {
        std::ostringstream out;
        pounding::io::write_yielding_rows(r.report, out);
        return out.str();
      });
  m.def("run", &run, py::arg("scene"), py::arg("method"), py::arg("settings"), py::arg("limits"));

  py::class_<Gap>(m, "Gap")
      .def("gap_json", [](const Gap& g) { return pounding::io::gap_json(g.scene, g.gap).dump(); })
      .def("history_t_s",
           [](const Gap& g) {
             return py::array_t<double>(py::ssize_t(g.gap.history_t_s.size()), g.gap.history_t_s.data());
           })
      .def("touch_gap_table", &touch_gap_table)
      .def("angles_table", [](const Gap& g) {
        const std::vector<pounding::analysis::AngleGap> none;
        const auto& envelope = g.gap.all_angles ? g.gap.all_angles->envelope : none;
        return matrix(envelope.size(), 2, [&](std::size_t r, std::size_t c) {
          return c == 0 ? envelope[r].angle_deg : envelope[r].needed_gap_m;
        });
      });
  m.def(
      "needed_gap",
      [](const Scene& scene, std::optional<double> max_wall_time_s, bool all_angles) {
        pounding::solvers::RunBudget budget;
        if (max_wall_time_s) budget.max_wall_time_s = *max_wall_time_s;
        return find_needed_gap(scene, budget, all_angles);
      },
      py::arg("scene"), py::arg("max_wall_time_s"), py::arg("all_angles"));
}
