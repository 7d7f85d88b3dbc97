#include "pounding/excitation/ground_motion.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <numbers>

#include "pounding/excitation/spectrum.hpp"
#include "pounding/input_error.hpp"

namespace pounding::excitation {
namespace {

double unit_to_mps2(AccelUnits units, double g_mps2) {
  switch (units) {
    case AccelUnits::g: return g_mps2;
    case AccelUnits::m_per_s2: return 1.0;
    case AccelUnits::cm_per_s2: return 0.01;
    case AccelUnits::in_per_s2: return 0.0254;  // exact, by the definition of the inch
    case AccelUnits::ft_per_s2: return 0.3048;
  }
  return 1.0;
}

/// Linear interpolation of (t, a) at `at`. @pre t.front() <= at <= t.back(), at finite.
double interpolate(const std::vector<double>& t, const std::vector<double>& a, double at) {
  if (at >= t.back()) return a.back();
  const auto upper = std::upper_bound(t.begin(), t.end(), at);
  // Clamped so that no time, even one breaking the precondition, reads outside the samples.
  const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(upper - t.begin()), 1, t.size() - 1);
  const double s = (at - t[i - 1]) / (t[i] - t[i - 1]);
  return a[i - 1] + s * (a[i] - a[i - 1]);
}

/// Keeps [start, end] of the record, shifted back by `start_s`. The end values are interpolated so
/// the cut is exactly as long as asked; samples within a millionth of a step of a bound are
/// taken as lying on it (i·dt carries round-off).
RecordSamples cut(const RecordSamples& in, double start_s, double end_s) {
  const double slack = 1e-6 * (in.time_s[1] - in.time_s[0]);
  RecordSamples out;
  auto push = [&](double t, double a) {
    out.time_s.push_back(t - start_s);
    out.accel.push_back(a);
  };
  const double from_s = std::max(start_s, in.time_s.front());  // a record may begin after 0
  push(from_s, interpolate(in.time_s, in.accel, from_s));
  for (std::size_t i = 0; i < in.time_s.size(); ++i) {
    if (in.time_s[i] > from_s + slack && in.time_s[i] < end_s - slack) push(in.time_s[i], in.accel[i]);
  }
  push(end_s, interpolate(in.time_s, in.accel, end_s));
  return out;
}

/// Where one component's samples come from: the keys and file its messages name.
struct ComponentSource {
  std::string file;
  std::string key_prefix;      // "excitation." or "excitation.second."
  bool times_from_dt = false;  // a dt_s key set the times (a re-spacing, or format single)
  std::optional<double> dt_override_s;
  AccelUnits units = AccelUnits::g;
};

ComponentSource first_source(const ExcitationSpec& spec) {
  return {spec.file.string(), "excitation.", spec.dt_override_s || spec.read.dt_s, spec.dt_override_s, spec.units};
}

ComponentSource second_source(const SecondComponentSpec& second) {
  return {second.file.string(), "excitation.second.", second.dt_override_s || second.read.dt_s, second.dt_override_s,
          second.units};
}

/// Record times must lie in [0, kMaxRecordDuration_s]; the key blamed is the one that set them.
void check_record_times(const RecordSamples& samples, const ComponentSource& source) {
  const std::string key = source.key_prefix + (source.times_from_dt ? "dt_s" : "file");
  const double first = samples.time_s.front(), last = samples.time_s.back();
  if (first < 0.0 || last > kMaxRecordDuration_s) {
    throw InputError(key, format_value(first < 0.0 ? first : last),
                     fmt::format("record times must lie in [0, {}] s (this record spans {} s to {} s)",
                                 kMaxRecordDuration_s, first, last),
                     source.file);
  }
}

/// max |a| (m/s²), 0 for no samples; NaN never compares larger, so a NaN sample is not it.
double peak_of(const std::vector<double>& accel) {
  double peak = 0.0;
  for (double a : accel) peak = std::max(peak, std::abs(a));
  return peak;
}

/// The processed peak must stay physical: records never exceed a few g, so more is a unit or
/// scaling mistake (and 1e308 overflows the solver).
void check_peak(const std::vector<double>& accel_mps2, const ExcitationSpec& spec, const ComponentSource& source) {
  const double peak = peak_of(accel_mps2);
  if (peak <= kMaxPeakAccel_g * spec.g_mps2) return;  // false for NaN/inf
  std::string key = spec.scale_factor != 1.0 ? "excitation.scale_factor" : source.key_prefix + "units";
  std::string value = spec.scale_factor != 1.0 ? format_value(spec.scale_factor) : "";
  if (spec.scale_to_sa) key = "excitation.scale_to_sa", value = spec.scale_to_sa->text;
  throw InputError(key, value,
                   fmt::format("the processed record peaks at |a_g| = {:.6g} m/s2 ({:.6g} g), above the limit of {} g",
                               peak, peak / spec.g_mps2, kMaxPeakAccel_g),
                   source.file);
}

/// One component re-spaced, checked, cut to [start_s, start_s + duration_s] (shifted to start at
/// 0 s) and converted to m/s² with the spec's scale_factor.
RecordSamples cut_and_convert(RecordSamples samples, const ExcitationSpec& spec, const ComponentSource& source) {
  if (source.dt_override_s) {
    for (std::size_t i = 0; i < samples.time_s.size(); ++i) {
      samples.time_s[i] = static_cast<double>(i) * *source.dt_override_s;
    }
  }
  check_record_times(samples, source);
  const double record_end_s = samples.time_s.back();
  if (spec.start_s >= record_end_s) {
    throw InputError("excitation.start_s", format_value(spec.start_s),
                     fmt::format("starts after the record ends at {} s", record_end_s), source.file);
  }
  const double slack_s = 1e-6 * (samples.time_s[1] - samples.time_s[0]);
  if (spec.duration_s && spec.start_s + *spec.duration_s > record_end_s + slack_s) {
    // Outside the record a_g is 0: a longer run would only be free vibration nobody asked for.
    throw InputError("excitation.duration_s", format_value(*spec.duration_s),
                     fmt::format("the record ends {} s after start_s; give at most that", record_end_s - spec.start_s),
                     source.file);
  }
  const double end_s = spec.duration_s ? std::min(spec.start_s + *spec.duration_s, record_end_s) : record_end_s;
  if (spec.start_s > 0.0 || end_s < record_end_s) samples = cut(samples, spec.start_s, end_s);
  const double factor = unit_to_mps2(source.units, spec.g_mps2) * spec.scale_factor;
  for (double& a : samples.accel) a *= factor;
  return samples;
}

/// The median interval of `times` (s): a cut's short first or last interval does not stand for
/// the record.
double median_spacing_s(const std::vector<double>& times) {
  std::vector<double> intervals(times.size() - 1);
  for (std::size_t k = 0; k + 1 < times.size(); ++k) intervals[k] = times[k + 1] - times[k];
  const auto middle = intervals.begin() + static_cast<std::ptrdiff_t>(intervals.size() / 2);
  std::nth_element(intervals.begin(), middle, intervals.end());
  return *middle;
}

/// Both components on the union of their sample times over the span both cover, each linear
/// between its own samples, so the pair is exactly the two records there. An H2 time closer than
/// a millionth of the finer spacing to an H1 time counts as that one (0.02·3 and 0.005·12 differ
/// by round-off): H1's own times are kept and the pair has no sliver intervals to stop at.
/// @throws InputError naming excitation.second.file when the records share no time span.
std::array<RecordSamples, 2> on_common_span(const RecordSamples& h1, const RecordSamples& h2,
                                            const ComponentSource& second) {
  const double from_s = std::max(h1.time_s.front(), h2.time_s.front());
  const double to_s = std::min(h1.time_s.back(), h2.time_s.back());
  if (!(to_s > from_s)) {
    throw InputError(second.key_prefix + "file", second.file,
                     fmt::format("the pair shares no time span: H1 spans {} s to {} s, H2 {} s to {} s",
                                 h1.time_s.front(), h1.time_s.back(), h2.time_s.front(), h2.time_s.back()));
  }
  const double same_s = 1e-6 * std::min(median_spacing_s(h1.time_s), median_spacing_s(h2.time_s));
  const auto inside = [&](double t) { return t > from_s + same_s && t < to_s - same_s; };
  std::vector<double> times{from_s, to_s};
  for (double t : h1.time_s) {
    if (inside(t)) times.push_back(t);
  }
  for (double t : h2.time_s) {
    if (!inside(t)) continue;
    const auto near = std::lower_bound(h1.time_s.begin(), h1.time_s.end(), t - same_s);
    if (near == h1.time_s.end() || *near > t + same_s) times.push_back(t);
  }
  std::sort(times.begin(), times.end());
  std::array<RecordSamples, 2> pair;
  for (int c = 0; c < 2; ++c) {
    const RecordSamples& in = c == 0 ? h1 : h2;
    pair[c].time_s = times;
    for (double t : times) pair[c].accel.push_back(interpolate(in.time_s, in.accel, t));
  }
  return pair;
}

/// The record's PSA (m/s²) at each of `periods_s`: of one component its own, of a pair its
/// RotD100 (at one period in 0.1° steps, within 4e-7 of the largest over every angle, cos 0.05°;
/// over a range in 1° steps, within 4e-5).
std::vector<double> record_psa_mps2(const std::vector<RecordSamples>& components, std::vector<double> periods_s) {
  const bool one_period = periods_s.size() == 1;
  const SpectrumOptions options{.periods_s = std::move(periods_s), .damping_ratio = kSaScalingDamping};
  std::vector<double> psa;
  if (components.size() == 1) {
    for (const SpectrumOrdinate& o : response_spectrum({components[0].time_s, components[0].accel}, options)) {
      psa.push_back(o.psa_mps2);
    }
  } else {
    for (const RotDOrdinate& o :
         rotd_spectrum({components[0].time_s, components[0].accel}, {components[1].time_s, components[1].accel},
                       options, one_period ? 0.1 : 1.0)) {
      psa.push_back(o.rotd100_psa_mps2);
    }
  }
  return psa;
}

/// The factor of spec.scale_to_sa (SaScaling) for `components` (one, or a pair on one time base).
double sa_factor(const std::vector<RecordSamples>& components, const ExcitationSpec& spec) {
  const SaScaling& scaling = *spec.scale_to_sa;
  if (!scaling.period_s) {
    throw InputError("excitation.scale_to_sa", scaling.text,
                     "names a building's period: the record must be read with its scene", spec.file.string());
  }
  const std::vector<double> periods = scaling.periods_s();
  const std::vector<double> psa_mps2 = record_psa_mps2(components, periods);
  double log_ratio = 0.0;
  for (std::size_t k = 0; k < periods.size(); ++k) {
    if (!(psa_mps2[k] > 0.0)) {
      throw InputError("excitation.scale_to_sa", scaling.text,
                       fmt::format("the record's spectral acceleration at {} s is zero", periods[k]),
                       spec.file.string());
    }
    const double target_g = scaling.design ? scaling.design->sa_g(periods[k]) : scaling.target_g;
    if (periods.size() == 1) return target_g * spec.g_mps2 / psa_mps2[k];
    log_ratio += std::log(target_g * spec.g_mps2 / psa_mps2[k]);
  }
  return std::exp(log_ratio / static_cast<double>(periods.size()));
}

/// A number filling all of `text`, or empty.
std::optional<double> whole_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

double DesignSpectrum::sa_g(double period_s) const {
  const double t0 = 0.2 * sd1_g / sds_g, ts = sd1_g / sds_g;
  if (period_s < t0) return sds_g * (0.4 + 0.6 * period_s / t0);
  if (period_s <= ts) return sds_g;
  if (period_s <= tl_s) return sd1_g / period_s;
  return sd1_g * tl_s / (period_s * period_s);
}

std::vector<double> SaScaling::periods_s() const {
  if (!design) return {*period_s};
  std::vector<double> periods;
  for (int k = 0; k < kSaRangePeriods; ++k) {
    periods.push_back(*period_s * from * std::pow(to / from, static_cast<double>(k) / (kSaRangePeriods - 1)));
  }
  return periods;
}

namespace {

constexpr double kMaxSaPeriod_s = 10.0, kMinSaPeriod_s = 0.01;
const std::string kSaForms =
    "expected TARGETg@PERIOD or asce7(SDS=..,SD1=..[,TL=..])@RANGE: 0.5g@T1 (the longer first period of the two "
    "buildings), 0.5g@B1 or 0.5g@B2 (that building's), 0.5g@1.2s (a period in s); "
    "asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2T1 (also B1, B2) or @0.1-1.5s";

/// "asce7(SDS=1.0,SD1=0.6,TL=8)" (TL optional, 8 s).
DesignSpectrum parse_design(const std::string& text, const std::string& key, const std::string& whole) {
  const std::string prefix = "asce7(";
  if (text.rfind(prefix, 0) != 0 || text.back() != ')') throw InputError(key, whole, kSaForms);
  DesignSpectrum design;
  bool sds = false, sd1 = false;
  std::size_t at = prefix.size();
  while (at < text.size() - 1) {
    std::size_t end = text.find(',', at);
    if (end == std::string::npos) end = text.size() - 1;
    const std::string item = text.substr(at, end - at);
    const std::size_t equals = item.find('=');
    const std::optional<double> value =
        equals == std::string::npos ? std::nullopt : whole_number(item.substr(equals + 1));
    const std::string name = equals == std::string::npos ? item : item.substr(0, equals);
    if (!value) throw InputError(key, whole, kSaForms);
    if (name == "SDS") {
      design.sds_g = *value, sds = true;
    } else if (name == "SD1") {
      design.sd1_g = *value, sd1 = true;
    } else if (name == "TL") {
      design.tl_s = *value;
    } else {
      throw InputError(key, whole, kSaForms);
    }
    at = end + 1;
  }
  if (!sds || !sd1) throw InputError(key, whole, "asce7(...) needs SDS and SD1 (g)");
  if (!(design.sds_g > 0.0 && design.sds_g <= kMaxPeakAccel_g && design.sd1_g > 0.0 &&
        design.sd1_g <= kMaxPeakAccel_g)) {
    throw InputError(key, whole, fmt::format("SDS and SD1 must lie in (0, {}] g", kMaxPeakAccel_g));
  }
  if (!(design.tl_s >= 1.0 && design.tl_s <= 20.0)) throw InputError(key, whole, "TL must lie in [1, 20] s");
  return design;
}

/// "T1", "B1", "B2" into scaling.building; false for anything else.
bool read_building_period(const std::string& text, SaScaling& scaling) {
  if (text != "T1" && text != "B1" && text != "B2") return false;
  scaling.building = text == "T1" ? 3 : text[1] - '0';
  return true;
}

/// "0.2-2T1", "0.2T1-2T1", "0.1-1.5s": the range form's periods.
void parse_range(std::string range, const std::string& key, const std::string& whole, SaScaling& scaling) {
  const std::size_t dash = range.find('-');
  if (dash == std::string::npos) throw InputError(key, whole, kSaForms);
  std::string low = range.substr(0, dash), high = range.substr(dash + 1);
  const std::string unit = high.size() >= 2 ? high.substr(high.size() - 2) : "";
  if (read_building_period(unit, scaling)) {
    high.resize(high.size() - 2);
    if (low.size() > 2 && low.substr(low.size() - 2) == unit) low.resize(low.size() - 2);
  } else {
    if (!high.empty() && high.back() == 's') high.pop_back();
    scaling.period_s = 1.0;  // the range is in seconds
  }
  const std::optional<double> from = whole_number(low), to = whole_number(high);
  if (!from || !to) throw InputError(key, whole, kSaForms);
  if (!(*from > 0.0 && *to > *from && *to <= 100.0)) {
    throw InputError(key, whole, "the range must run from a positive period to a longer one");
  }
  scaling.from = *from, scaling.to = *to;
  if (scaling.building == 0 && !(*from >= kMinSaPeriod_s && *to <= kMaxSaPeriod_s)) {
    throw InputError(key, whole, fmt::format("the periods must lie in [{}, {}] s", kMinSaPeriod_s, kMaxSaPeriod_s));
  }
}

}  // namespace

SaScaling parse_sa_scaling(const std::string& text, const std::string& key) {
  const std::size_t at = text.find('@');
  if (at == std::string::npos || at == 0) throw InputError(key, text, kSaForms);
  SaScaling scaling;
  scaling.text = text;
  if (text.rfind("asce7(", 0) == 0) {
    scaling.design = parse_design(text.substr(0, at), key, text);
    parse_range(text.substr(at + 1), key, text, scaling);
    return scaling;
  }
  if (text[at - 1] != 'g') throw InputError(key, text, kSaForms);
  const std::optional<double> target = whole_number(text.substr(0, at - 1));
  if (!target) throw InputError(key, text, kSaForms);
  if (!(*target > 0.0 && *target <= kMaxPeakAccel_g)) {
    throw InputError(key, text, fmt::format("the target must lie in (0, {}] g", kMaxPeakAccel_g));
  }
  scaling.target_g = *target;
  std::string period = text.substr(at + 1);
  if (read_building_period(period, scaling)) return scaling;
  if (!period.empty() && period.back() == 's') period.pop_back();
  const std::optional<double> period_s = whole_number(period);
  if (!period_s) throw InputError(key, text, kSaForms);
  if (!(*period_s >= kMinSaPeriod_s && *period_s <= kMaxSaPeriod_s)) {
    throw InputError(key, text, fmt::format("the period must lie in [{}, {}] s", kMinSaPeriod_s, kMaxSaPeriod_s));
  }
  scaling.period_s = *period_s;
  return scaling;
}

NonFiniteTime::NonFiniteTime(double t_s)
    : std::domain_error(
          fmt::format("the ground motion was asked for at t = {} s: the solution is no longer finite", t_s)) {}

std::optional<AccelUnits> parse_accel_units(std::string_view name) {
  if (name == "g") return AccelUnits::g;
  if (name == "m/s2") return AccelUnits::m_per_s2;
  if (name == "cm/s2") return AccelUnits::cm_per_s2;
  if (name == "in/s2") return AccelUnits::in_per_s2;
  if (name == "ft/s2") return AccelUnits::ft_per_s2;
  return std::nullopt;
}

namespace {

// A component's keys sit under `prefix`: "excitation." or "excitation.second.".

void validate_spacing(const std::string& prefix, const RecordReadOptions& read, std::optional<double> dt_override_s) {
  // Below 1e-5 s a spacing is a typo (accelerographs sample at 50 Hz to 1 kHz); a denormal one
  // would make every sample time the same.
  const Range sample_spacing{kMinSampleSpacing_s, kMaxSampleSpacing_s, "s"};
  if (dt_override_s) require_range(prefix + "dt_s", *dt_override_s, sample_spacing);
  if (read.dt_s) require_range(prefix + "dt_s", *read.dt_s, sample_spacing);
}

void validate_layout(const std::string& prefix, const RecordReadOptions& read) {
  if (read.format == RecordFormat::single && !read.dt_s) {
    throw InputError(prefix + "dt_s", "missing", "format 'single' needs the time step");
  }
  if (read.time_column < 1) {
    throw InputError(prefix + "time_column", std::to_string(read.time_column), "columns are numbered from 1");
  }
  if (read.accel_column && *read.accel_column < 1) {
    throw InputError(prefix + "accel_column", std::to_string(*read.accel_column), "columns are numbered from 1");
  }
  if (read.format == RecordFormat::columns && read.accel_column == read.time_column) {
    throw InputError(
        prefix + "accel_column", std::to_string(*read.accel_column),
        fmt::format("is the time column ({}time_column): the acceleration must be another column", prefix));
  }
}

}  // namespace

// Physical ranges: beyond them a value is a typo or a unit mistake. (An array: GCC 12 fails with an
// internal error on a std::vector of these rows in this file.)
std::span<const ExcitationKeySpec> excitation_specs() {
  static const ExcitationKeySpec kSpecs[] = {
      {.key = "start_s",
       .member = &ExcitationSpec::start_s,
       .range = Range{0.0, kMaxRecordDuration_s, "s"},
       .description = "cut start; times are shifted back by it (s)"},
      {.key = "duration_s",
       .member = &ExcitationSpec::duration_s,
       .range = Range{0.0, kMaxRecordDuration_s, "s", true},
       .description = "cut length (s)",
       .details = "cut ends that fall between samples are interpolated; a cut that ends after the record is "
                  "refused (a_g would be zero there)",
       .default_note = "to the end"},
      {.key = "free_vibration_s",
       .member = &ExcitationSpec::free_vibration_s,
       .range = Range{0.0, kMaxFreeVibration_s, "s"},
       .description = "a quiet tail after the record (s)",
       .details = "zero samples at the record's spacing, as many as cover it, so that the buildings come to rest "
                  "before the run ends and `summary.json`'s `residual_drift` is the drift they keep (FEMA P-58's "
                  "residual drift). a_g falls linearly from the last sample to 0 over the first interval. Comes after "
                  "the cut and the scaling (it changes neither); the run, its history and the response spectra then "
                  "cover the tail too"},
      {.key = "scale_to_pga_g",
       .member = &ExcitationSpec::scale_to_pga_g,
       .range = Range{0.0, kMaxPeakAccel_g, "g", true},
       .description = "scale so that max \\|a_g\\| equals this many g (sign kept)",
       .default_note = "none"},
      {.key = "scale_factor",
       .member = &ExcitationSpec::scale_factor,
       .description = "plain multiplier; excludes `scale_to_pga_g`",
       .details = "the processed record may peak at most at 10 g (recorded peaks stay below 5 g); more is refused, "
                  "naming `scale_factor` (or `units` when the record's own values are too large)",
       .type_note = "number ≠ 0"},
      {.key = "g_mps2",
       .member = &ExcitationSpec::g_mps2,
       .range = Range{kGravityRange_mps2[0], kGravityRange_mps2[1], "m/s2"},
       .description = "gravity used to convert g (m/s²)"},
      {.key = "direction_deg",
       .member = &ExcitationSpec::direction_deg,
       .range = Range{-360.0, 360.0, "deg"},
       .description = "β: the shaking acts along (cos β, sin β) in plan; a pair's second component along β + 90°"},
  };
  return kSpecs;
}

void ExcitationSpec::validate() const {
  validate_spacing("excitation.", read, dt_override_s);
  validate_keys(*this, excitation_specs(), "excitation");
  if (!std::isfinite(scale_factor) || scale_factor == 0.0) {
    throw InputError("excitation.scale_factor", format_value(scale_factor), "must be finite and non-zero");
  }
  if (scale_to_pga_g && scale_factor != 1.0) {
    throw InputError("excitation.scale_factor", format_value(scale_factor),
                     "give either scale_factor or scale_to_pga_g, not both");
  }
  if (scale_to_sa && (scale_to_pga_g || scale_factor != 1.0)) {
    throw InputError("excitation.scale_to_sa", scale_to_sa->text,
                     "give one scaling: scale_to_sa, scale_to_pga_g or scale_factor");
  }
  validate_layout("excitation.", read);
  if (second) {
    validate_spacing("excitation.second.", second->read, second->dt_override_s);
    validate_layout("excitation.second.", second->read);
  }
}

GroundMotion::GroundMotion(std::vector<double> time_s, std::vector<double> accel_mps2, double direction_rad)
    : time_s_(std::move(time_s)), direction_rad_(direction_rad) {
  accel_mps2_.push_back(std::move(accel_mps2));
  find_peaks();
}

GroundMotion::GroundMotion(std::vector<double> time_s, std::vector<double> h1_mps2, std::vector<double> h2_mps2,
                           double direction_rad)
    : time_s_(std::move(time_s)), direction_rad_(direction_rad) {
  accel_mps2_.push_back(std::move(h1_mps2));
  accel_mps2_.push_back(std::move(h2_mps2));
  find_peaks();
}

void GroundMotion::find_peaks() {
  for (const std::vector<double>& accel : accel_mps2_) {
    std::size_t peak = 0;
    for (std::size_t i = 1; i < accel.size(); ++i) {
      if (std::abs(accel[i]) > std::abs(accel[peak])) peak = i;
    }
    peak_index_.push_back(peak);
  }
}

double GroundMotion::accel_at(double t_s, int component) const {
  // A NaN passes every range test below; it means the solution has already diverged.
  if (!std::isfinite(t_s)) throw NonFiniteTime(t_s);
  const std::vector<double>& accel = accel_mps2(component);
  if (t_s < time_s_.front() || t_s > time_s_.back()) return 0.0;
  if (t_s == time_s_.back()) return accel.back();
  return interpolate(time_s_, accel, t_s);
}

std::optional<double> GroundMotion::next_sample_after(double t_s) const {
  // "Clearly": a stop just reached (t_s equal to a sample up to round-off) is not set again.
  const auto next = std::upper_bound(time_s_.begin(), time_s_.end(), t_s + 1e-12 * std::max(1.0, std::abs(t_s)));
  if (next == time_s_.end()) return std::nullopt;
  return *next;
}

double GroundMotion::sample_spacing_s() const { return median_spacing_s(time_s_); }

double GroundMotion::peak_mps2(int component) const {
  return std::abs(accel_mps2(component)[peak_index_[static_cast<std::size_t>(component)]]);
}
double GroundMotion::peak_time_s(int component) const {
  return time_s_[peak_index_[static_cast<std::size_t>(component)]];
}

namespace {

/// Zero samples after the record at its sample spacing (the median interval), the last at or past
/// end + tail_s: every solution path takes them as it takes the record's own samples.
void append_quiet_tail(std::vector<RecordSamples>& components, double tail_s) {
  const std::vector<double>& times = components.front().time_s;
  const double spacing_s = median_spacing_s(times), end_s = times.back();
  const auto samples = static_cast<std::size_t>(std::ceil(tail_s / spacing_s * (1.0 - 1e-12)));
  for (RecordSamples& c : components) {
    for (std::size_t i = 1; i <= samples; ++i) {
      c.time_s.push_back(end_s + static_cast<double>(i) * spacing_s);
      c.accel.push_back(0.0);
    }
  }
}

}  // namespace

GroundMotion process_record(RecordSamples samples, const ExcitationSpec& spec, std::optional<RecordSamples> second) {
  spec.validate();
  const ComponentSource h1_source = first_source(spec);
  std::vector<RecordSamples> components{cut_and_convert(std::move(samples), spec, h1_source)};
  std::vector<ComponentSource> sources{h1_source};
  if (spec.second) {
    if (!second) throw std::logic_error("process_record: a pair's spec without H2's samples");
    sources.push_back(second_source(*spec.second));
    RecordSamples h2 = cut_and_convert(std::move(*second), spec, sources[1]);
    auto pair = on_common_span(components[0], h2, sources[1]);
    components = {std::move(pair[0]), std::move(pair[1])};
  }
  double applied_scale = unit_to_mps2(spec.units, spec.g_mps2) * spec.scale_factor;  // H1's, in m/s² per file unit
  if (spec.scale_to_pga_g) {
    // A pair keeps its components' ratio: one factor, from the larger component's peak.
    double peak = 0.0;
    for (const RecordSamples& c : components) peak = std::max(peak, peak_of(c.accel));
    if (peak == 0.0) {
      throw InputError("excitation.scale_to_pga_g", format_value(*spec.scale_to_pga_g),
                       "cannot scale a record that is zero throughout", spec.file.string());
    }
    const double scale = *spec.scale_to_pga_g * spec.g_mps2 / peak;
    for (RecordSamples& c : components) {
      for (double& a : c.accel) a *= scale;
    }
    applied_scale *= scale;
  }
  if (spec.scale_to_sa) {
    const double scale = sa_factor(components, spec);
    for (RecordSamples& c : components) {
      for (double& a : c.accel) a *= scale;
    }
    applied_scale *= scale;
  }
  for (std::size_t c = 0; c < components.size(); ++c) check_peak(components[c].accel, spec, sources[c]);
  if (spec.free_vibration_s > 0.0) append_quiet_tail(components, spec.free_vibration_s);
  const double direction_rad = spec.direction_deg * std::numbers::pi / 180.0;
  GroundMotion motion =
      spec.second ? GroundMotion(std::move(components[0].time_s), std::move(components[0].accel),
                                 std::move(components[1].accel), direction_rad)
                  : GroundMotion(std::move(components[0].time_s), std::move(components[0].accel), direction_rad);
  motion.set_record_scale(applied_scale / unit_to_mps2(spec.units, spec.g_mps2));
  return motion;
}

SecondComponentSpec second_like(const ExcitationSpec& first, std::filesystem::path file) {
  SecondComponentSpec second{
      .file = std::move(file), .read = first.read, .units = first.units, .dt_override_s = first.dt_override_s};
  second.read.accel_column.reset();
  return second;
}

GroundMotion load_ground_motion(const ExcitationSpec& spec) {
  spec.validate();
  std::optional<RecordSamples> second;
  try {
    if (spec.second) second = read_record(spec.second->file, spec.second->read);
  } catch (const InputError& error) {
    throw SecondComponentError(error);
  }
  return process_record(read_record(spec.file, spec.read), spec, std::move(second));
}

}  // namespace pounding::excitation
