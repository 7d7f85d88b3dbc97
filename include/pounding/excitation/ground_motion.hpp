#pragma once
// The ground acceleration a_g(t) (m/s²) acting along direction β in plan, piecewise linear
// between samples, built from a record and the scene's processing options.

#include <filesystem>
#include <optional>
#include <vector>

#include "pounding/excitation/record_reader.hpp"

namespace pounding::excitation {

enum class AccelUnits { g, m_per_s2, cm_per_s2 };
/// Parses "g", "m/s2", "cm/s2"; empty when the name is unknown.
std::optional<AccelUnits> parse_accel_units(std::string_view name);

/// How a record file becomes the excitation. Processing order: read, override the time step,
/// cut [start, start + duration], convert to m/s², scale.
struct ExcitationSpec {
  std::filesystem::path file;
  RecordReadOptions read;
  AccelUnits units = AccelUnits::g;
  double g_mps2 = 9.81;                  // standard gravity used to convert g (m/s²)
  std::optional<double> dt_override_s;   // re-space the samples t_i = i·dt (any format)
  double start_s = 0.0;                  // cut start; times are shifted back by it (s)
  std::optional<double> duration_s;      // cut length; empty keeps the rest of the record
  std::optional<double> scale_to_pga_g;  // scale so max |a_g| equals this (in g)
  double scale_factor = 1.0;             // plain multiplier (excludes scale_to_pga_g)
  double direction_deg = 0.0;            // β: angle of the shaking direction from +x towards +y

  /// @throws InputError naming the `excitation.*` key and value.
  void validate() const;
};

class GroundMotion {
 public:
  /// @pre times strictly increasing, same size as accelerations, at least two samples.
  GroundMotion(std::vector<double> time_s, std::vector<double> accel_mps2, double direction_rad);

  /// a_g(t) in m/s², linear between samples, 0 outside the record.
  double accel_at(double t_s) const;

  const std::vector<double>& time_s() const { return time_s_; }
  const std::vector<double>& accel_mps2() const { return accel_mps2_; }
  double direction_rad() const { return direction_rad_; }
  double start_s() const { return time_s_.front(); }
  double end_s() const { return time_s_.back(); }
  /// max |a_g| (m/s²) and the time of that sample (s).
  double peak_mps2() const;
  double peak_time_s() const;

 private:
  std::vector<double> time_s_;
  std::vector<double> accel_mps2_;
  double direction_rad_;
  std::size_t peak_index_ = 0;
};

/// Reads, cuts, converts and scales the record of `spec` (spec.file must already be resolved).
/// @throws InputError for an invalid spec, a bad record file, or a cut that leaves < 2 samples.
GroundMotion load_ground_motion(const ExcitationSpec& spec);

/// The same processing applied to samples already in memory (`spec.file` names them in errors).
GroundMotion process_record(RecordSamples samples, const ExcitationSpec& spec);

}  // namespace pounding::excitation
