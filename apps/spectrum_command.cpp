// `pounding spectrum`: elastic response spectra of records (and RotD of a pair), with the
// periods of a scene's buildings marked.

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "commands.hpp"
#include "plot_script.hpp"
#include "pounding/analysis/modal_summary.hpp"
#include "pounding/excitation/ground_motion.hpp"
#include "pounding/excitation/spectrum.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/output_files.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/io/sha256.hpp"
#include "pounding/io/spectrum_writer.hpp"

namespace pounding::cli {
namespace {

excitation::ExcitationSpec record_spec(const SpectrumCommand& command, std::size_t index) {
  const std::string& file = command.records[index];
  excitation::ExcitationSpec spec;
  spec.file = file;
  const bool at2 = [&] {
    std::string extension = std::filesystem::path(file).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::toupper);
    return extension == ".AT2";
  }();
  const std::string format = command.format.value_or(at2 ? "peer-at2" : "columns");
  const auto parsed_format = excitation::parse_record_format(format);
  if (!parsed_format) throw InputError("--format", format, "must be peer-at2, columns or single");
  spec.read.format = *parsed_format;
  const auto units = excitation::parse_accel_units(command.units);
  if (!units) throw InputError("--units", command.units, fmt::format("must be {}", excitation::kAccelUnitChoices));
  spec.units = *units;
  if (!command.accel_columns.empty()) {
    spec.read.accel_column = command.accel_columns[command.accel_columns.size() == 1 ? 0 : index];
  }
  if (spec.read.format == excitation::RecordFormat::single) {
    spec.read.dt_s = command.dt_s;
  } else {
    spec.dt_override_s = command.dt_s;
  }
  if (!std::filesystem::is_regular_file(file)) throw InputError("record", file, "no such file");
  return spec;
}

excitation::AccelerationHistory history_of(const excitation::GroundMotion& motion) {
  return {motion.time_s(), motion.accel_mps2()};
}

double shortest_spacing_s(const std::vector<double>& time_s) {
  double shortest = time_s.back() - time_s.front();
  for (std::size_t i = 1; i < time_s.size(); ++i) shortest = std::min(shortest, time_s[i] - time_s[i - 1]);
  return shortest;
}

/// The first three modes' periods of each building of the scene, labelled "B1 T1 (x)".
std::vector<io::MarkedPeriod> building_periods(const std::string& scene_file) {
  std::vector<io::MarkedPeriod> marked;
  const analysis::Scene scene = io::read_scene(scene_file);
  const auto buildings = analysis::summarise_buildings(scene);
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    const auto& modes = buildings[b].modes;
    for (std::size_t m = 0; m < std::min<std::size_t>(3, modes.size()); ++m) {
      const double period = modes[m].period_s;
      if (period < excitation::kMinPeriod_s || period > excitation::kMaxPeriod_s) continue;
      marked.push_back({fmt::format("B{} T{} ({})", b + 1, m + 1, model::to_string(modes[m].dominant)), period, {}});
    }
  }
  return marked;
}

void print_spectra(const io::SpectrumReport& report) {
  fmt::print("Pseudo-acceleration spectra, {:g} % damping (PSA in g, Sd in m):\n", 100.0 * report.damping_ratio);
  std::string header = fmt::format("  {:>9}", "T (s)");
  for (std::size_t r = 0; r < report.records.size(); ++r)
    header += fmt::format("  {:>9} {:>10}", fmt::format("PSA{}", r + 1), fmt::format("Sd{}", r + 1));
  if (!report.rotd.empty()) header += fmt::format("  {:>9} {:>9} {:>6}", "RotD50", "RotD100", "θ100");
  fmt::print("{}\n", header);
  for (std::size_t i = 0; i < report.records.front().ordinates.size(); ++i) {
    std::string row = fmt::format("  {:9.4f}", report.records.front().ordinates[i].period_s);
    for (const io::RecordSpectrum& record : report.records) {
      const auto& o = record.ordinates[i];
      row += fmt::format("  {:9.4f} {:10.3e}", o.psa_mps2 / report.g_mps2, o.sd_m);
    }
    if (!report.rotd.empty()) {
      const auto& o = report.rotd[i];
      row += fmt::format("  {:9.4f} {:9.4f} {:5.0f}°", o.rotd50_psa_mps2 / report.g_mps2,
                         o.rotd100_psa_mps2 / report.g_mps2, o.rotd100_angle_deg);
    }
    fmt::print("{}\n", row);
  }
  for (const io::MarkedPeriod& m : report.marked) {
    std::string row = fmt::format("  {} = {:.4f} s:", m.label, m.period_s);
    for (std::size_t r = 0; r < m.psa_mps2.size(); ++r) {
      row += fmt::format(" PSA{} {:.4f} g", r + 1, m.psa_mps2[r] / report.g_mps2);
    }
    fmt::print("{}\n", row);
  }
}

}  // namespace

int run_spectrum(const SpectrumCommand& command, const std::string& command_line) {
  if (command.rotd && command.records.size() != 2) {
    throw InputError("--rotd", std::to_string(command.records.size()) + " records", "needs exactly two (a pair)");
  }
  excitation::SpectrumOptions options{.periods_s = command.periods_s, .damping_ratio = command.damping_ratio};
  try {
    options.validate();
  } catch (const InputError& error) {
    throw InputError(error.key() == "damping_ratio" ? "--damping" : "--periods", error.value(), error.reason());
  }
  if (options.periods_s.empty()) options.periods_s = excitation::default_periods_s();
  std::sort(options.periods_s.begin(), options.periods_s.end());
  const std::size_t columns = command.accel_columns.size();
  if (columns > 1 && columns != command.records.size()) {
    throw InputError("--record-column", std::to_string(columns) + " columns",
                     fmt::format("give one for every record or one per record ({})", command.records.size()));
  }
  io::require_writable_folder(command.out_dir, "--out");

  io::SpectrumReport report;
  report.damping_ratio = options.damping_ratio;
  report.command_line = command_line;
  if (!command.scene.empty()) report.marked = building_periods(command.scene);
  std::vector<excitation::AccelerationHistory> histories;
  for (std::size_t r = 0; r < command.records.size(); ++r) {
    const std::string& file = command.records[r];
    const excitation::ExcitationSpec spec = record_spec(command, r);
    const excitation::GroundMotion motion = excitation::load_ground_motion(spec);
    histories.push_back(history_of(motion));
    report.records.push_back({file, io::sha256_file_hex(file), spec.read.accel_column.value_or(0), motion.peak_mps2(),
                              shortest_spacing_s(motion.time_s()),
                              excitation::response_spectrum(histories.back(), options)});
    for (io::MarkedPeriod& m : report.marked) {
      const excitation::SpectrumOptions at{.periods_s = {m.period_s}, .damping_ratio = options.damping_ratio};
      m.psa_mps2.push_back(excitation::response_spectrum(histories.back(), at).front().psa_mps2);
    }
  }
  if (command.rotd)
    report.rotd = excitation::rotd_spectrum(histories[0], histories[1], options, command.angle_step_deg);
  print_spectra(report);
  io::write_spectrum(command.out_dir, report);
  fmt::print("Wrote {}/spectrum.csv{}, spectrum.json\n", command.out_dir, command.rotd ? ", rotd.csv" : "");
  if (!command.no_plot) draw_with_script("plot_spectrum.py", command.out_dir, "spectrum.png");
  return 0;
}

}  // namespace pounding::cli
