// `pounding settings`: the [solver] and [contact] settings, the run limits, the [excitation] and
// [output] keys and the building's key tables (analysis::setting_specs(), contact_setting_specs(),
// limit_specs(), excitation::excitation_specs(), output_specs(), model::hysteresis_specs(),
// drift_limit_specs(), shear_capacity_specs(), flexural_strength_specs()) as text, JSON, or the
// Markdown tables docs/scene-format.md and docs/guide/limits.md hold (tools/doc_tables.py writes
// and checks them).

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/limit_states.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/analysis/scene.hpp"
#include "pounding/input_error.hpp"

namespace pounding::cli {
namespace {

using analysis::SettingSpec;

/// The methods a setting applies to.
std::vector<std::string> users(const SettingSpec& spec) {
  std::vector<std::string> names;
  for (const analysis::MethodInfo& method : analysis::methods()) {
    if (analysis::applies(method, spec.id)) names.emplace_back(method.name);
  }
  return names;
}

std::string meaning(const SettingSpec& spec) {
  return spec.details.empty() ? std::string(spec.description) : fmt::format("{}; {}", spec.description, spec.details);
}

/// A key's range in its JSON entry: `range` (min, max, min_open) and `unit`.
void add_range(const Range& range, nlohmann::json& entry) {
  entry["range"] = {{"min", range.min}, {"max", range.max}, {"min_open", range.min_open}};
  entry["unit"] = range.unit;
}

nlohmann::json as_json(const SettingSpec& spec) {
  nlohmann::json entry = {{"key", spec.key},
                          {"toml", "solver." + std::string(spec.key)},
                          {"option", spec.option},
                          {"python", spec.key},
                          {"type", analysis::type_name(spec)},
                          {"methods", users(spec)},
                          {"description", spec.description},
                          {"details", spec.details}};
  entry["default"] = spec.id == analysis::Setting::order
                         ? nlohmann::json(nullptr)
                         : std::visit([](const auto& v) { return nlohmann::json(v); }, spec.default_value);
  if (spec.range) add_range(*spec.range, entry);
  if (!spec.choices.empty()) entry["choices"] = spec.choices;
  return entry;
}

/// "number in [1e-14, 0.1]", "integer 0..60", `"reduced"` or `"dense"`.
std::string type_column(const SettingSpec& spec) {
  if (!spec.choices.empty()) {
    std::vector<std::string> quoted;
    for (const std::string& choice : spec.choices) quoted.push_back(fmt::format("`\"{}\"`", choice));
    return fmt::format("{}", fmt::join(quoted, ", "));
  }
  if (spec.id == analysis::Setting::order) return "integer";
  return fmt::format("{} {}{}", analysis::type_name(spec), spec.member.index() == 0 ? "" : "in ",
                     analysis::accepted_text(spec));
}

/// A [contact] key's or run limit's default as the docs print it: its member's initialiser; an
/// unset stiffness, each law's own (contact_laws()).
template <typename Owner>
std::string key_default(const analysis::KeySpec<Owner>& spec) {
  if (!spec.default_note.empty() || !std::holds_alternative<std::optional<double> Owner::*>(spec.member))
    return analysis::default_text(spec);
  std::vector<std::string> defaults;
  for (const analysis::ContactLawInfo& law : analysis::contact_laws()) {
    if (law.stiffness_key == spec.key) defaults.push_back(fmt::format("{} {:g}", law.name, law.default_stiffness));
  }
  return fmt::format("{}", fmt::join(defaults, ", "));
}

/// The values accepted: the choices, true or false, the contact laws (contact.law, whose names the
/// law table holds), or "number in [0, 10] m" (", or one a storey" for a per-storey key).
template <typename Owner>
std::string key_type(const analysis::KeySpec<Owner>& spec) {
  if (!spec.type_note.empty()) return std::string(spec.type_note);
  std::vector<std::string> names;
  for (std::string_view choice : spec.choices) names.push_back(fmt::format("`\"{}\"`", choice));
  if (std::holds_alternative<bool Owner::*>(spec.member)) names = {"`true`", "`false`"};
  if (!spec.range && names.empty()) {
    for (const analysis::ContactLawInfo& law : analysis::contact_laws())
      names.push_back(fmt::format("`\"{}\"`", law.name));
  }
  if (!names.empty()) return fmt::format("{}", fmt::join(names, ", "));
  return fmt::format("{} in {}{}", analysis::type_name(spec), range_text(*spec.range),
                     is_per_storey(spec) ? ", or one a storey" : "");
}

/// The docs' default column: the literal default in backticks, a note or a law's own as text.
template <typename Owner>
std::string default_column(const analysis::KeySpec<Owner>& spec) {
  const bool literal = spec.default_note.empty() && !spec.required &&
                       !std::holds_alternative<std::optional<double> Owner::*>(spec.member);
  return literal ? fmt::format("`{}`", key_default(spec)) : key_default(spec);
}

/// The rows' meaning column: the description and details, and the laws a key applies to.
template <typename Owner>
std::string meaning(const analysis::KeySpec<Owner>& spec) {
  std::vector<std::string> quoted;
  for (std::string_view value : spec.applies_to) quoted.push_back(fmt::format("`{}`", value));
  return fmt::format("{}{}{}{}", spec.description, spec.details.empty() ? "" : "; ", spec.details,
                     spec.applies_to.empty() ? "" : fmt::format("; only for {}", fmt::join(quoted, ", ")));
}

/// The rows as the docs' table, after `first_row` (a key the rows do not hold) when given.
template <typename Owner>
void print_keys_markdown(std::span<const analysis::KeySpec<Owner>> specs, std::string_view first_row = {}) {
  fmt::print("| key | option | type | default | meaning |\n|---|---|---|---|---|\n{}", first_row);
  for (const analysis::KeySpec<Owner>& spec : specs) {
    fmt::print("| `{}` | {} | {} | {} | {} |\n", spec.key, spec.option.empty() ? "" : fmt::format("`{}`", spec.option),
               key_type(spec), default_column(spec), meaning(spec));
  }
}

/// [building.hysteresis]: `law` (its choices the law names), then the rows.
void print_hysteresis_markdown() {
  std::vector<std::string> names;
  for (std::string_view name : model::hysteretic_law_names()) names.push_back(fmt::format("`\"{}\"`", name));
  print_keys_markdown(
      model::hysteresis_specs(),
      fmt::format(
          "| `law` |  | {} | required in the table | the columns' force–drift law ([model.md](model.md) §2a) |\n",
          fmt::join(names, ", ")));
}

template <typename Owner>
nlohmann::json as_json(const analysis::KeySpec<Owner>& spec, std::string_view section) {
  nlohmann::json entry = {{"key", spec.key},
                          {"toml", fmt::format("{}.{}", section, spec.key)},
                          {"option", spec.option},
                          {"python", analysis::python_keyword(spec.option)},
                          {"type", analysis::type_name(spec)},
                          {"required", spec.required},
                          {"default", key_default(spec)},
                          {"description", spec.description},
                          {"details", spec.details}};
  if (spec.range) add_range(*spec.range, entry);
  if (!spec.choices.empty()) entry["choices"] = spec.choices;
  if (!spec.applies_to.empty()) entry["applies_to"] = spec.applies_to;
  return entry;
}

template <typename Owner>
void print_keys_text(std::span<const analysis::KeySpec<Owner>> specs, std::string_view section) {
  for (const analysis::KeySpec<Owner>& spec : specs) {
    const std::string name = fmt::format("{}.{}", section, spec.key);
    constexpr std::size_t kNameWidth = 27;
    if (name.size() > kNameWidth) fmt::print("{}\n", name);  // a line of its own: the columns stay aligned
    fmt::print("{:<27} {:<17} {:<8} default {:<18} {}\n{:28} {}\n", name.size() > kNameWidth ? "" : name, spec.option,
               analysis::type_name(spec), key_default(spec),
               spec.range                                           ? range_text(*spec.range)
               : !spec.type_note.empty()                            ? std::string(spec.type_note)
               : std::holds_alternative<bool Owner::*>(spec.member) ? "true or false"
               : spec.choices.empty()                               ? "a law"
                                                                    : "a choice",
               "", spec.description);
  }
}

/// The drift limits' keys, then each structural type's default limits.
void print_limit_states_markdown() {
  print_keys_markdown(analysis::drift_limit_specs());
  fmt::print("\n| `structural_type` | FEMA 356 Table C1-3 | IO | LS | CP |\n|---|---|---|---|---|\n");
  for (const analysis::StructuralType& type : analysis::structural_types()) {
    fmt::print("| `\"{}\"`{} | {} | {:g} % | {:g} % | {:g} % |\n", type.name,
               &type == analysis::structural_types().data() ? " (default)" : "", type.description,
               100.0 * type.drift_ratios[0], 100.0 * type.drift_ratios[1], 100.0 * type.drift_ratios[2]);
  }
}

nlohmann::json structural_types_json() {
  nlohmann::json types = nlohmann::json::array();
  for (const analysis::StructuralType& type : analysis::structural_types()) {
    types.push_back({{"name", type.name}, {"description", type.description}, {"drift_ratios", type.drift_ratios}});
  }
  return types;
}

void print_solver_markdown() {
  fmt::print("| method | uses |\n|---|---|\n");
  for (const analysis::MethodInfo& method : analysis::methods()) {
    std::vector<std::string> keys;
    for (analysis::Setting s : method.settings) keys.push_back(fmt::format("`{}`", analysis::spec(s).key));
    fmt::print("| `{}`{} | {} |\n", method.name, &method == analysis::methods().data() ? " (default)" : "",
               keys.empty() ? "none" : fmt::format("{}", fmt::join(keys, ", ")));
  }
  std::vector<std::string> names;
  for (const analysis::MethodInfo& method : analysis::methods()) names.push_back(fmt::format("`\"{}\"`", method.name));
  fmt::print("\n| key | option | type | default | meaning |\n|---|---|---|---|---|\n");
  fmt::print("| `method` | `--method` | {} | `\"{}\"` | solution path (`pounding methods` describes each) |\n",
             fmt::join(names, ", "), analysis::methods().front().name);
  for (const SettingSpec& spec : analysis::setting_specs()) {
    const std::string default_value = analysis::default_text(spec);
    fmt::print("| `{}` | `{}` | {} | {} | {} |\n", spec.key, spec.option, type_column(spec),
               spec.id == analysis::Setting::order ? default_value : fmt::format("`{}`", default_value), meaning(spec));
  }
}

}  // namespace

int run_settings(const SettingsCommand& command) {
  if (command.markdown) {
    if (*command.markdown == "solver") {
      print_solver_markdown();
    } else if (*command.markdown == "contact") {
      print_keys_markdown(analysis::contact_setting_specs());
    } else if (*command.markdown == "limits") {
      print_keys_markdown(analysis::limit_specs());
    } else if (*command.markdown == "excitation") {
      print_keys_markdown(excitation::excitation_specs());
    } else if (*command.markdown == "output") {
      print_keys_markdown(analysis::output_specs());
    } else if (*command.markdown == "hysteresis") {
      print_hysteresis_markdown();
    } else if (*command.markdown == "limit_states") {
      print_limit_states_markdown();
    } else if (*command.markdown == "shear_capacity") {
      print_keys_markdown(analysis::shear_capacity_specs());
    } else if (*command.markdown == "flexural_strength") {
      print_keys_markdown(analysis::flexural_strength_specs());
    } else {
      throw InputError("--markdown", *command.markdown,
                       "expected solver, contact, limits, excitation, output, hysteresis, limit_states, "
                       "shear_capacity or flexural_strength");
    }
    return 0;
  }
  if (command.json) {
    nlohmann::json solver = nlohmann::json::array(), contact = nlohmann::json::array(),
                   limits = nlohmann::json::array();
    for (const SettingSpec& spec : analysis::setting_specs()) solver.push_back(as_json(spec));
    for (const auto& spec : analysis::contact_setting_specs()) contact.push_back(as_json(spec, "contact"));
    for (const auto& spec : analysis::limit_specs()) limits.push_back(as_json(spec, "limits"));
    nlohmann::json excitation = nlohmann::json::array(), output = nlohmann::json::array();
    for (const auto& spec : excitation::excitation_specs()) excitation.push_back(as_json(spec, "excitation"));
    for (const auto& spec : analysis::output_specs()) output.push_back(as_json(spec, "output"));
    nlohmann::json hysteresis = nlohmann::json::array();
    for (const auto& spec : model::hysteresis_specs()) hysteresis.push_back(as_json(spec, "building.hysteresis"));
    nlohmann::json limit_states = nlohmann::json::array();
    for (const auto& spec : analysis::drift_limit_specs())
      limit_states.push_back(as_json(spec, "building.limit_states"));
    nlohmann::json shear_capacity = nlohmann::json::array();
    for (const auto& spec : analysis::shear_capacity_specs())
      shear_capacity.push_back(as_json(spec, "building.shear_capacity"));
    nlohmann::json flexural_strength = nlohmann::json::array();
    for (const auto& spec : analysis::flexural_strength_specs())
      flexural_strength.push_back(as_json(spec, "building.flexural_strength"));
    fmt::print("{}\n", nlohmann::json{{"solver", solver},
                                      {"contact", contact},
                                      {"limits", limits},
                                      {"excitation", excitation},
                                      {"output", output},
                                      {"hysteresis", hysteresis},
                                      {"limit_states", limit_states},
                                      {"shear_capacity", shear_capacity},
                                      {"flexural_strength", flexural_strength},
                                      {"structural_types", structural_types_json()}}
                           .dump(2));
    return 0;
  }
  for (const SettingSpec& spec : analysis::setting_specs()) {
    fmt::print("solver.{:<20} {:<17} {:<8} default {:<18} {}\n{:28} {}\n", spec.key, spec.option,
               analysis::type_name(spec), analysis::default_text(spec), analysis::accepted_text(spec), "",
               fmt::format("{}: {}", fmt::join(users(spec), ", "), spec.description));
  }
  print_keys_text(analysis::contact_setting_specs(), "contact");
  print_keys_text(analysis::limit_specs(), "limits");
  print_keys_text(excitation::excitation_specs(), "excitation");
  print_keys_text(analysis::output_specs(), "output");
  print_keys_text(model::hysteresis_specs(), "building.hysteresis");
  print_keys_text(analysis::drift_limit_specs(), "building.limit_states");
  print_keys_text(analysis::shear_capacity_specs(), "building.shear_capacity");
  print_keys_text(analysis::flexural_strength_specs(), "building.flexural_strength");
  return 0;
}

}  // namespace pounding::cli
