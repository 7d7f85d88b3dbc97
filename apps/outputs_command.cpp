// `pounding outputs`: every output field (io::output_schema_json(): history.csv's columns,
// impacts, per-floor peaks, the energy audit, contacts_history.csv and yielding.csv) as text, JSON, or the Markdown
// tables docs/guide/output-columns.md holds (tools/doc_tables.py writes and checks them).

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>

#include "commands.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/output_schema.hpp"

namespace pounding::cli {
namespace {

/// A unit token of the column names ("mps2") as a reader writes it ("m/s²"); none: "–".
std::string unit_text(const std::string& unit) {
  static const std::map<std::string, std::string> kReadable = {
      {"mps", "m/s"}, {"mps2", "m/s²"}, {"radps2", "rad/s²"}, {"kNs", "kN·s"}};
  if (unit.empty()) return "–";
  const auto found = kReadable.find(unit);
  return found == kReadable.end() ? unit : found->second;
}

/// The field's name as its file spells it, and what else the table shows about it.
std::string name_of(const nlohmann::ordered_json& field) {
  if (field.contains("column")) return field["column"];
  return field["key"];
}

std::string extra_of(const std::string& section, const nlohmann::ordered_json& field) {
  if (section == "history") return field["per"];
  if (section == "peaks") return field["group"];
  if (section == "yielding") return field["kind"];
  if (section == "impacts")
    return fmt::format("{}", fmt::join(field["csv_columns"].get<std::vector<std::string>>(), ", "));
  return "";
}

void print_markdown(const std::string& section, const nlohmann::ordered_json& fields) {
  static const std::map<std::string, std::string> kExtraHeading = {
      {"history", "one per"}, {"peaks", "group"}, {"impacts", "impacts.csv columns"}, {"yielding", "kind"}};
  const auto extra = kExtraHeading.find(section);
  const bool has_extra = extra != kExtraHeading.end();
  fmt::print("| {} | unit |{} meaning |\n|---|---|{}---|\n",
             fields.empty() || fields[0].contains("column") ? "column" : "key",
             has_extra ? " " + extra->second + " |" : "", has_extra ? "---|" : "");
  for (const auto& field : fields) {
    const std::string extra_text = extra_of(section, field);
    fmt::print("| `{}` | {} |{} {} |\n", name_of(field), unit_text(field["unit"]),
               has_extra ? fmt::format(" {} |", section == "impacts" ? "`" + extra_text + "`" : extra_text) : "",
               field["description"].get<std::string>());
  }
}

}  // namespace

int run_outputs(const OutputsCommand& command) {
  const nlohmann::ordered_json schema = io::output_schema_json();
  if (command.markdown) {
    if (!schema.contains(*command.markdown)) {
      std::vector<std::string> sections;
      for (const auto& [section, fields] : schema.items()) sections.push_back(section);
      throw InputError("--markdown", *command.markdown, fmt::format("expected one of {}", fmt::join(sections, ", ")));
    }
    print_markdown(*command.markdown, schema[*command.markdown]);
    return 0;
  }
  if (command.json) {
    fmt::print("{}\n", schema.dump(2));
    return 0;
  }
  for (const auto& [section, fields] : schema.items()) {
    fmt::print("{}:\n", section);
    for (const auto& field : fields) {
      fmt::print("  {:<28} {:<7} {}\n", name_of(field), unit_text(field["unit"]),
                 field["description"].get<std::string>());
    }
  }
  return 0;
}

}  // namespace pounding::cli
