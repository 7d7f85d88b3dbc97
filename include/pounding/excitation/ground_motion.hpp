#pragma once
// The ground acceleration a_g(t) (m/s²) acting along direction β in plan, piecewise linear
// between samples, built from a record and the scene's processing options.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "pounding/excitation/record_reader.hpp"

namespace pounding::excitation {

enum class AccelUnits { g, m_per_s2, cm_per_s2, in_per_s2, ft_per_s2 };
/// The unit names parse_accel_units() takes, for messages and help.
inline constexpr std::string_view kAccelUnitChoices = "g, m/s2, cm/s2, in/s2 or ft/s2";
/// Parses "g", "m/s2", "cm/s2", "in/s2", "ft/s2"; empty when the name is unknown.
std::optional<AccelUnits> parse_accel_units(std::string_view name);

// Physical ranges of the excitation (docs/scene-format.md lists them next to their keys).
inline constexpr double kMaxRecordDuration_s = 3600.0;  // record times lie in [0, this]
inline constexpr double kMinSampleSpacing_s = 1e-5;     // dt_s in [this, kMaxSampleSpacing_s]: 100 kHz
inline constexpr double kMaxSampleSpacing_s = 1.0;
inline constexpr double kMaxPeakAccel_g = 10.0;         // processed peak |a_g|; recorded peaks stay below 5 g
inline constexpr double kGravityRange_mps2[2] = {9.0, 10.5};  // g_mps2: Earth's 9.78…9.83, or 10 for hand checks

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

  /// @throws InputError naming the `excitation.*` key, its value and the range it must lie in.
  void validate() const;
};

/// Thrown by GroundMotion::accel_at for a NaN or infinite time: a solver that diverged, never
/// bad input. Solvers end the run with a named status when they meet it.
class NonFiniteTime : public std::domain_error {
 public:
  explicit NonFiniteTime(double t_s);
};

class GroundMotion {
 public:
  /// @pre times strictly increasing, same size as accelerations, at least two samples.
  GroundMotion(std::vector<double> time_s, std::vector<double> accel_mps2, double direction_rad);

  /// a_g(t) in m/s², linear between samples, 0 outside the record.
  /// @throws NonFiniteTime if t_s is NaN or infinite (never reads outside the samples).
  double accel_at(double t_s) const;

  const std::vector<double>& time_s() const { return time_s_; }
  const std::vector<double>& accel_mps2() const { return accel_mps2_; }
  double direction_rad() const { return direction_rad_; }
  double start_s() const { return time_s_.front(); }
  /// The first sample clearly after t (s), where the forcing's slope may change: the stop time
  /// no integrator step may cross. Empty past the last sample.
  std::optional<double> next_sample_after(double t_s) const;
  double end_s() const { return time_s_.back(); }
  /// The record's sample spacing (s): the median interval, so that the short last interval of a
  /// cut or an uneven sampling does not stand for the whole record.
  double sample_spacing_s() const;
  /// A fixed step of step_s (s) is longer than the sample spacing: it leaves samples out.
  bool skips_samples(double step_s) const { return step_s > sample_spacing_s() * (1.0 + 1e-9); }
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
/// @throws InputError for an invalid spec, a bad record file, times outside
///   [0, kMaxRecordDuration_s], a duration_s beyond the record's end, or a processed peak above
///   kMaxPeakAccel_g.
GroundMotion load_ground_motion(const ExcitationSpec& spec);

/// The same processing applied to samples already in memory (`spec.file` names them in errors).
GroundMotion process_record(RecordSamples samples, const ExcitationSpec& spec);

}  // namespace pounding::excitation
