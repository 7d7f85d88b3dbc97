#include "pounding/io/json_report.hpp"

#include "pounding/io/output_files.hpp"
#include <stdexcept>

namespace pounding::io {

nlohmann::json modes_json(const std::vector<analysis::BuildingSummary>& buildings) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& building : buildings) {
    nlohmann::json periods = nlohmann::json::array();
    nlohmann::json modes = nlohmann::json::array();
    for (std::size_t k = 0; k < building.modes.size(); ++k) {
      const model::Mode& mode = building.modes[k];
      periods.push_back(mode.period_s);
      modes.push_back({{"mode", k + 1},
                       {"period_s", mode.period_s},
                       {"frequency_hz", 1.0 / mode.period_s},
                       {"dominant", model::to_string(mode.dominant)},
                       {"effective_mass_ratio",
                        {{"x", mode.effective_mass_ratio_x},
                         {"y", mode.effective_mass_ratio_y},
                         {"rz", mode.effective_mass_ratio_rz}}}});
    }
    list.push_back({{"name", building.name},
                    {"storeys", building.storeys},
                    {"dof", building.dof},
                    {"total_mass_t", building.total_mass_t},
                    {"frame_factor", building.frame_factor},
                    {"frame_factor_solved", building.frame_factor_solved},
                    {"rayleigh", {{"a0_per_s", building.rayleigh.a0_per_s}, {"a1_s", building.rayleigh.a1_s}}},
                    {"periods_s", periods},
                    {"modes", modes}});
  }
  return {{"buildings", list}};
}

namespace {

template <class Json>
void write_indented(const Json& document, const std::filesystem::path& file) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_atomically(file, [&](std::ostream& out) { out << document.dump(2) << '\n'; });
}

}  // namespace

void write_json(const nlohmann::json& document, const std::filesystem::path& file) { write_indented(document, file); }

void write_json(const nlohmann::ordered_json& document, const std::filesystem::path& file) {
  write_indented(document, file);
}

}  // namespace pounding::io
