#pragma once
// Elastic response spectra of ground-acceleration records, exact for the piecewise-linear
// record: the SDOF x'' + 2ζωx' + ω²x = −a_g(t) is advanced by its closed-form solution over each
// record interval (Nigam & Jennings 1969), and the peak |x| is located between samples, not only
// at them (docs/model.md, "Response spectra"). x is the relative displacement (m); the pseudo
// quantities follow as PSV = ωSd (m/s) and PSA = ω²Sd (m/s²).

#include <vector>

namespace pounding::excitation {

/// A record as the spectra see it: strictly increasing times (s) and a_g (m/s²), linear between
/// samples. Zero before the first and after the last sample (no free vibration is added after
/// the record's end: the spectra, as published ones, are peaks over the record's duration).
struct AccelerationHistory {
  std::vector<double> time_s;
  std::vector<double> accel_mps2;
};

struct SpectrumOptions {
  /// Natural periods (s), each in [kMinPeriod_s, kMaxPeriod_s]; default: default_periods_s().
  std::vector<double> periods_s;
  /// Critical damping ratio ζ ∈ [0, 1): 0.05 for the design spectra of ASCE 7 and EC8.
  double damping_ratio = 0.05;
  /// @throws InputError naming `periods_s[i]` or `damping_ratio` and the value.
  void validate() const;
};

inline constexpr double kMinPeriod_s = 1e-3;
inline constexpr double kMaxPeriod_s = 100.0;
inline constexpr int kMaxSpectrumPeriods = 10'000;

/// 0.01 s to 10 s, 20 periods per decade, log-spaced (61 periods).
std::vector<double> default_periods_s();

struct SpectrumOrdinate {
  double period_s = 0.0;
  double sd_m = 0.0;         // peak |x|: spectral displacement
  double psv_mps = 0.0;      // ω·Sd
  double psa_mps2 = 0.0;     // ω²·Sd
  double peak_time_s = 0.0;  // when |x| peaks
};

/// The spectrum of one component.
/// @pre history has ≥ 2 samples with strictly increasing times (a GroundMotion's are).
/// @throws InputError from options.validate().
std::vector<SpectrumOrdinate> response_spectrum(const AccelerationHistory& history, const SpectrumOptions& options);

/// Orientation-independent spectra of a pair of horizontal components (Boore 2010): for each
/// period, the peak |x1 cos θ + x2 sin θ| over time for every angle θ ∈ [0°, 180°) at
/// `angle_step_deg`; RotD50 is the median over θ, RotD100 the largest (its angle from the first
/// component towards the second). The pair is taken on the union of both sample grids, each
/// interpolated linearly, which is exact for piecewise-linear records.
struct RotDOrdinate {
  double period_s = 0.0;
  double rotd50_sd_m = 0.0;
  double rotd100_sd_m = 0.0;
  double rotd100_angle_deg = 0.0;
  double rotd50_psa_mps2 = 0.0;   // ω²·RotD50 Sd
  double rotd100_psa_mps2 = 0.0;  // ω²·RotD100 Sd
};

/// @throws InputError for an angle step outside (0, 90] degrees or options out of range.
std::vector<RotDOrdinate> rotd_spectrum(const AccelerationHistory& first, const AccelerationHistory& second,
                                        const SpectrumOptions& options, double angle_step_deg = 1.0);

/// Both records on the union of their sample times (each interpolated linearly, zero outside its
/// own samples): the common time base on which a pair acts together, exactly.
std::pair<AccelerationHistory, AccelerationHistory> on_common_time_base(const AccelerationHistory& first,
                                                                        const AccelerationHistory& second);

/// The factor that scales `history` so its PSA at `period_s` (damping ζ) equals `target_psa_mps2`.
/// @throws InputError when the record's PSA there is zero or the target is not positive.
double scale_to_psa(const AccelerationHistory& history, double period_s, double damping_ratio, double target_psa_mps2);

}  // namespace pounding::excitation
