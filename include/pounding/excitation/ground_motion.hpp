#pragma once
// The ground acceleration (m/s²) in plan, piecewise linear between samples, built from a record
// and the scene's processing options: one component a_g(t) along direction β, or a pair of
// horizontal components, H1 along β and H2 along β + 90°, on one time base.

#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/excitation/record_reader.hpp"
#include "pounding/input_error.hpp"
#include "pounding/key_spec.hpp"

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
inline constexpr double kMaxPeakAccel_g = 10.0;               // processed peak |a_g|; recorded peaks stay below 5 g
inline constexpr double kGravityRange_mps2[2] = {9.0, 10.5};  // g_mps2: Earth's 9.78…9.83, or 10 for hand checks

/// The second horizontal component of a pair (H2), acting along direction_deg + 90°: its own
/// file, layout, units and re-spacing; the cut, the scaling, g and the direction are the pair's.
struct SecondComponentSpec {
  std::filesystem::path file;
  RecordReadOptions read;
  AccelUnits units = AccelUnits::g;
  std::optional<double> dt_override_s;  // re-space its samples t_i = i·dt (any format)
};

/// An InputError raised while reading a pair's second record (the keys that chose how it is read
/// are excitation.second.*), so that callers name those, not H1's.
class SecondComponentError : public InputError {
 public:
  explicit SecondComponentError(const InputError& error) : InputError(error) {}
};

/// The ASCE 7-16 §11.4.6 design response spectrum (5 % damped): S_DS, S_D1 in g, T_L in s.
struct DesignSpectrum {
  double sds_g = 0.0;
  double sd1_g = 0.0;
  double tl_s = 8.0;
  /// S_a(T) in g: S_DS(0.4 + 0.6 T/T0) below T0 = 0.2 S_D1/S_DS, S_DS up to TS = S_D1/S_DS, S_D1/T up
  /// to T_L, S_D1 T_L/T² beyond.
  double sa_g(double period_s) const;
};

/// Spectral scaling by one factor, of the record's 5 %-damped pseudo-spectral acceleration (of a
/// pair: its RotD100, the largest over every horizontal direction). Two forms:
/// - at a period, "0.5g@T1": the PSA there equals target_g. The period: "1.2" or "1.2s" (s), "B1"
///   or "B2" (that building's first period), "T1" (the longer of the two first periods);
/// - over a range, "asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2T1": the record's spectrum best fits the
///   design spectrum over kSaRangePeriods log-spaced periods in [from, to] × the period (T1, B1,
///   B2; or "0.1-1.5s" in seconds), in the least-squares sense of ln S_a (the factor is the
///   geometric mean of the target-to-record ratios, as the PEER ground-motion database scales).
struct SaScaling {
  double target_g = 0.0;                 // the point form's target
  std::optional<DesignSpectrum> design;  // the range form's target
  double from = 1.0, to = 1.0;           // the range form's periods, as multiples of period_s
  std::optional<double> period_s;        // a period given in s (1 for a range in s), or the building's once resolved
  int building = 0;                      // 1 or 2: that building's T1; 3: the longer T1 of both; 0: period_s given
  std::string text;                      // as written, for messages

  /// The periods (s) the factor is fitted at: period_s, or the range's log-spaced ones. @pre period_s set.
  std::vector<double> periods_s() const;
};
inline constexpr double kSaScalingDamping = 0.05;
inline constexpr double kMaxFreeVibration_s = 600.0;
inline constexpr int kSaRangePeriods = 50;

/// Parses either form (targets in (0, 10] g, periods in [0.01, 10] s, S_D1 ≤ 10 g, T_L in [1, 20] s).
/// @throws InputError naming `key` and the text when it is neither.
SaScaling parse_sa_scaling(const std::string& text, const std::string& key);

/// How a record file (or a pair) becomes the excitation. Processing order: read, override the
/// time step, cut [start, start + duration], convert to m/s², take a pair on the union of its
/// sample times over the span both cover, scale, append the quiet tail (free_vibration_s).
struct ExcitationSpec {
  std::filesystem::path file;
  RecordReadOptions read;
  AccelUnits units = AccelUnits::g;
  double g_mps2 = 9.81;                  // standard gravity used to convert g (m/s²)
  std::optional<double> dt_override_s;   // re-space the samples t_i = i·dt (any format)
  double start_s = 0.0;                  // cut start; times are shifted back by it (s)
  std::optional<double> duration_s;      // cut length; empty keeps the rest of the record
  std::optional<double> scale_to_pga_g;  // scale so max |a_g| (of a pair: of its larger component) equals this (g)
  double scale_factor = 1.0;             // plain multiplier (excludes scale_to_pga_g); a pair's both components
  std::optional<SaScaling> scale_to_sa;  // spectral scaling (excludes the other two); its period resolved before use
  double direction_deg = 0.0;            // β: angle of the shaking direction (H1's) from +x towards +y
  std::optional<SecondComponentSpec> second;  // H2 of a pair; empty: one component
  /// A quiet tail after the record (s, [0, kMaxFreeVibration_s]): zero samples at the record's
  /// sample spacing, as many as cover it (the last one at or past end + free_vibration_s), so that
  /// the buildings come to rest and the run's end reads their residual drift. a_g falls linearly
  /// from the record's last sample to 0 over the first interval, as between any two samples.
  double free_vibration_s = 0.0;

  /// @throws InputError naming the `excitation.*` key, its value and the range it must lie in.
  void validate() const;
};

/// One scalar [excitation] key (key_spec.hpp): the cut, the scaling, the direction, gravity and the
/// quiet tail. The scene reader, the range checks of ExcitationSpec::validate(), `pounding settings`
/// and docs/scene-format.md's table come from its row. The record's own keys (file, format, units,
/// layout) and `scale_to_sa` are read by their parsers.
using ExcitationKeySpec = KeySpec<ExcitationSpec>;
std::span<const ExcitationKeySpec> excitation_specs();

/// H2 of a pair in `file`, read as H1 (`first`) is: its format, units, time column, spacing
/// (format single) and re-spacing; the acceleration column left to the format's default (a pair
/// from one file names H2's column).
SecondComponentSpec second_like(const ExcitationSpec& first, std::filesystem::path file);

/// Thrown by GroundMotion::accel_at for a NaN or infinite time: a solver that diverged, never
/// bad input. Solvers end the run with a named status when they meet it.
class NonFiniteTime : public std::domain_error {
 public:
  explicit NonFiniteTime(double t_s);
};

/// The ground acceleration: one component, or a pair sharing one time base. Component 0 (H1)
/// acts along β = direction_rad(), component 1 (H2) along β + 90°, i.e. along (−sin β, cos β).
class GroundMotion {
 public:
  /// One component. @pre times strictly increasing, same size as accelerations, ≥ 2 samples.
  GroundMotion(std::vector<double> time_s, std::vector<double> accel_mps2, double direction_rad);
  /// A pair. @pre as above, both acceleration vectors the size of the times.
  GroundMotion(std::vector<double> time_s, std::vector<double> h1_mps2, std::vector<double> h2_mps2,
               double direction_rad);

  /// 1 or 2.
  int component_count() const { return static_cast<int>(accel_mps2_.size()); }
  bool is_pair() const { return component_count() == 2; }
  /// The component's acceleration in m/s², linear between samples, 0 outside the record.
  /// @pre 0 <= component < component_count().
  /// @throws NonFiniteTime if t_s is NaN or infinite (never reads outside the samples).
  double accel_at(double t_s, int component = 0) const;

  const std::vector<double>& time_s() const { return time_s_; }
  const std::vector<double>& accel_mps2(int component = 0) const {
    return accel_mps2_[static_cast<std::size_t>(component)];
  }
  /// β: H1's direction from +x towards +y (rad).
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
  /// The factor the record's values were multiplied by (scale_factor, scale_to_pga_g or
  /// scale_to_sa; 1 unscaled), in the record's own units: what a report quotes.
  double record_scale() const { return record_scale_; }
  void set_record_scale(double factor) { record_scale_ = factor; }
  /// A component's max |a| (m/s²) and the time of that sample (s).
  double peak_mps2(int component = 0) const;
  double peak_time_s(int component = 0) const;

 private:
  std::vector<double> time_s_;
  std::vector<std::vector<double>> accel_mps2_;  // one per component
  double direction_rad_;
  std::vector<std::size_t> peak_index_;  // one per component
  double record_scale_ = 1.0;

  void find_peaks();
};

/// Reads, cuts, converts and scales the record of `spec` (and of spec.second: a pair; files
/// already resolved). A spec.scale_to_sa naming a building's period must have been resolved
/// (analysis::scene_ground_motion does it from the scene's buildings).
/// @throws InputError for an invalid spec, a bad record file, times outside
///   [0, kMaxRecordDuration_s], a duration_s beyond a record's end, a pair whose components
///   share no time span, or a processed peak above kMaxPeakAccel_g.
GroundMotion load_ground_motion(const ExcitationSpec& spec);

/// The same processing applied to samples already in memory (`spec.file` names them in errors;
/// `second` holds H2's samples when spec.second is set, and is ignored otherwise).
GroundMotion process_record(RecordSamples samples, const ExcitationSpec& spec,
                            std::optional<RecordSamples> second = std::nullopt);

}  // namespace pounding::excitation
