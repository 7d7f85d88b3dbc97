#pragma once
// The outputs of `pounding spectrum`: spectrum.csv (one row per record and period), rotd.csv
// (a pair's RotD50/RotD100) and spectrum.json (everything, with units and provenance).

#include <filesystem>
#include <string>
#include <vector>

#include "pounding/excitation/spectrum.hpp"

namespace pounding::io {

struct RecordSpectrum {
  std::filesystem::path file;
  std::string sha256;
  int accel_column = 0;          // the column read (from 1); 0: the format's default
  double peak_accel_mps2 = 0.0;  // max |a_g| of the processed record
  double dt_s = 0.0;             // its shortest sample spacing
  std::vector<excitation::SpectrumOrdinate> ordinates;
};

/// A period to mark on the spectra (a building's mode), with the record's PSA there.
struct MarkedPeriod {
  std::string label;  // e.g. "B1 T1 (x)"
  double period_s = 0.0;
  std::vector<double> psa_mps2;  // per record, at exactly this period
};

struct SpectrumReport {
  double damping_ratio = 0.05;
  double g_mps2 = 9.81;  // converts PSA to g in the tables
  std::vector<RecordSpectrum> records;
  std::vector<excitation::RotDOrdinate> rotd;  // empty: no pair asked for
  std::vector<MarkedPeriod> marked;
  std::string command_line;
};

/// Writes spectrum.csv, rotd.csv (when report.rotd is not empty) and spectrum.json into folder,
/// each whole or not at all. @throws std::runtime_error naming a file that cannot be written.
void write_spectrum(const std::filesystem::path& folder, const SpectrumReport& report);

}  // namespace pounding::io
