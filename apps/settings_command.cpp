// `pounding settings`: the [solver] settings table (analysis::setting_specs()) as text, JSON, or
// the Markdown tables docs/scene-format.md holds (tools/settings_doc.py writes and checks them).

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "commands.hpp"

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
  nlohmann::json entry = {{"key", spec.key},          {"toml", "solver." + std::string(spec.key)},
                          {"option", spec.option},    {"python", spec.key},
                          {"type", analysis::type_name(spec)}, {"methods", users(spec)},
                          {"description", spec.description},   {"details", spec.details}};
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

void print_markdown() {
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
    print_markdown();
    return 0;
  }
  if (command.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const SettingSpec& spec : analysis::setting_specs()) list.push_back(as_json(spec));
    fmt::print("{}\n", list.dump(2));
    return 0;
  }
  for (const SettingSpec& spec : analysis::setting_specs()) {
    fmt::print("solver.{:<20} {:<17} {:<8} default {:<18} {}\n{:28} {}\n", spec.key, spec.option,
               analysis::type_name(spec), analysis::default_text(spec), analysis::accepted_text(spec), "",
               fmt::format("{}: {}", fmt::join(users(spec), ", "), spec.description));
  }
  return 0;
}

}  // namespace pounding::cli
