// `pounding settings`: the [solver] and [contact] settings tables (analysis::setting_specs(),
// analysis::contact_setting_specs()) as text, JSON, or the Markdown tables docs/scene-format.md
// holds (tools/doc_tables.py writes and checks them).

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "pounding/analysis/contact_laws.hpp"
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
  if (spec.range) {
    entry["range"] = {{"min", spec.range->min}, {"max", spec.range->max}, {"min_open", spec.range->min_open}};
    entry["unit"] = spec.range->unit;
  }
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

/// The [contact] key's default as the docs print it: ContactSettings' initialiser.
std::string contact_default(const analysis::ContactSettingSpec& spec) {
  if (spec.required) return "required";
  const analysis::ContactSettings defaults;
  return std::visit(
      [&](auto analysis::ContactSettings::*member) -> std::string {
        const auto& value = defaults.*member;
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::string>) {
          return fmt::format("\"{}\"", value);
        } else if constexpr (std::is_same_v<T, double>) {
          return fmt::format("{}", value);
        } else {  // a stiffness: each law using the key has its own
          std::vector<std::string> defaults;
          for (const analysis::ContactLawInfo& law : analysis::contact_laws()) {
            if (law.stiffness_key == spec.key)
              defaults.push_back(fmt::format("{} {:g}", law.name, law.default_stiffness));
          }
          return fmt::format("{}", fmt::join(defaults, ", "));
        }
      },
      spec.member);
}

std::string contact_type(const analysis::ContactSettingSpec& spec) {
  if (!spec.choices.empty()) {
    std::vector<std::string> names;
    for (std::string_view choice : spec.choices) names.push_back(fmt::format("`\"{}\"`", choice));
    return fmt::format("{}", fmt::join(names, ", "));
  }
  if (!spec.range) {  // the law
    std::vector<std::string> names;
    for (const analysis::ContactLawInfo& law : analysis::contact_laws())
      names.push_back(fmt::format("`\"{}\"`", law.name));
    return fmt::format("{}", fmt::join(names, ", "));
  }
  return "number in " + range_text(*spec.range);
}

void print_contact_markdown() {
  fmt::print("| key | option | type | default | meaning |\n|---|---|---|---|---|\n");
  for (const analysis::ContactSettingSpec& spec : analysis::contact_setting_specs()) {
    const bool literal =
        !spec.required && !std::holds_alternative<std::optional<double> analysis::ContactSettings::*>(spec.member);
    fmt::print("| `{}` | {} | {} | {} | {}{}{} |\n", spec.key,
               spec.option.empty() ? "" : fmt::format("`{}`", spec.option), contact_type(spec),
               literal ? fmt::format("`{}`", contact_default(spec)) : contact_default(spec), spec.description,
               spec.details.empty() ? "" : "; ", spec.details);
  }
}

nlohmann::json as_json(const analysis::ContactSettingSpec& spec) {
  nlohmann::json entry = {{"key", spec.key},
                          {"toml", "contact." + std::string(spec.key)},
                          {"option", spec.option},
                          {"required", spec.required},
                          {"description", spec.description},
                          {"details", spec.details}};
  if (spec.range) {
    entry["range"] = {{"min", spec.range->min}, {"max", spec.range->max}, {"min_open", spec.range->min_open}};
    entry["unit"] = spec.range->unit;
  }
  return entry;
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
      print_contact_markdown();
    } else {
      throw InputError("--markdown", *command.markdown, "expected solver or contact");
    }
    return 0;
  }
  if (command.json) {
    nlohmann::json solver = nlohmann::json::array(), contact = nlohmann::json::array();
    for (const SettingSpec& spec : analysis::setting_specs()) solver.push_back(as_json(spec));
    for (const analysis::ContactSettingSpec& spec : analysis::contact_setting_specs()) contact.push_back(as_json(spec));
    fmt::print("{}\n", nlohmann::json{{"solver", solver}, {"contact", contact}}.dump(2));
    return 0;
  }
  for (const SettingSpec& spec : analysis::setting_specs()) {
    fmt::print("solver.{:<20} {:<17} {:<8} default {:<18} {}\n{:28} {}\n", spec.key, spec.option,
               analysis::type_name(spec), analysis::default_text(spec), analysis::accepted_text(spec), "",
               fmt::format("{}: {}", fmt::join(users(spec), ", "), spec.description));
  }
  for (const analysis::ContactSettingSpec& spec : analysis::contact_setting_specs()) {
    fmt::print("contact.{:<19} {:<17} {:<8} default {:<18} {}\n{:28} {}\n", spec.key, spec.option,
               spec.range ? "number" : "string", contact_default(spec), spec.range ? range_text(*spec.range) : "a law",
               "", spec.description);
  }
  return 0;
}

}  // namespace pounding::cli
