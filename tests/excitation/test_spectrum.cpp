#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pounding/excitation/spectrum.hpp"
#include "pounding/input_error.hpp"

namespace tt = boost::test_tools;
using namespace pounding::excitation;

namespace {

constexpr double kPi = std::numbers::pi;

/// a(t) = a0 on [0, duration], sampled every dt.
AccelerationHistory constant(double a0, double duration_s, double dt_s) {
  AccelerationHistory history;
  for (int i = 0; i * dt_s <= duration_s + 1e-12; ++i) {
    history.time_s.push_back(i * dt_s);
    history.accel_mps2.push_back(a0);
  }
  return history;
}

/// A deterministic, irregular record: two decaying sines of incommensurate periods.
AccelerationHistory wiggly(double dt_s, double duration_s, double phase) {
  AccelerationHistory history;
  for (int i = 0; i * dt_s <= duration_s + 1e-12; ++i) {
    const double t = i * dt_s;
    history.time_s.push_back(t);
    history.accel_mps2.push_back(std::exp(-0.3 * t) * (3.0 * std::sin(7.3 * t + phase) + 1.7 * std::cos(2.1 * t)));
  }
  return history;
}

}  // namespace

// A step of ground acceleration a0 from rest: x(t) = −(a0/ω²)(1 − e^{−ζωt}(cos ω_d t + ζ/√(1−ζ²)
// sin ω_d t)), whose largest |x| is at t = π/ω_d: (a0/ω²)(1 + exp(−ζπ/√(1−ζ²))). The samples are
// 0.37 T apart, so the peak lies between them.
BOOST_AUTO_TEST_CASE(StepFromRestPeaksAsTheClosedForm) {
  for (double zeta : {0.0, 0.02, 0.05, 0.2, 0.7}) {
    const double period = 0.8;
    const double omega = 2.0 * kPi / period;
    const AccelerationHistory step = constant(2.5, 1.3 * period, 0.37 * period);
    const auto spectrum = response_spectrum(step, {.periods_s = {period}, .damping_ratio = zeta});
    const double expected = 2.5 / (omega * omega) * (1.0 + std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta)));
    BOOST_TEST(spectrum[0].sd_m == expected, tt::tolerance(1e-12));
    BOOST_TEST(spectrum[0].peak_time_s == period / 2.0 / std::sqrt(1.0 - zeta * zeta), tt::tolerance(1e-9));
    BOOST_TEST(spectrum[0].psa_mps2 == omega * omega * expected, tt::tolerance(1e-12));
    BOOST_TEST(spectrum[0].psv_mps == omega * expected, tt::tolerance(1e-12));
  }
}

// A ramp a(t) = r t on [0, t1]: the particular solution −r t/ω² + 2ζr/ω³ and free vibration
// from x(0) = −2ζr/ω³, v(0) = r/ω²; here ζ = 0, so x(t) = (r/ω³)(sin ωt − ωt), monotone, and
// its largest |x| is at the record's end.
BOOST_AUTO_TEST_CASE(UndampedRampFollowsTheClosedForm) {
  const double r = 1.5, t1 = 2.0, period = 0.45;
  const double omega = 2.0 * kPi / period;
  AccelerationHistory ramp{{0.0, 0.7, t1}, {0.0, r * 0.7, r * t1}};
  const auto spectrum = response_spectrum(ramp, {.periods_s = {period}, .damping_ratio = 0.0});
  const double expected = r / (omega * omega * omega) * (omega * t1 - std::sin(omega * t1));
  BOOST_TEST(spectrum[0].sd_m == expected, tt::tolerance(1e-12));
  BOOST_TEST(spectrum[0].peak_time_s == t1);
}

BOOST_AUTO_TEST_CASE(RotDOfAPairWithAZeroSecondComponentIsTheFirstsSpectrum) {
  const AccelerationHistory first = wiggly(0.01, 6.0, 0.0);
  const AccelerationHistory zero{first.time_s, std::vector<double>(first.time_s.size(), 0.0)};
  const SpectrumOptions options{.periods_s = {0.05, 0.3, 1.0, 2.5}, .damping_ratio = 0.05};
  const auto single = response_spectrum(first, options);
  const auto rotd = rotd_spectrum(first, zero, options);
  for (std::size_t i = 0; i < single.size(); ++i) {
    BOOST_TEST(rotd[i].rotd100_sd_m == single[i].sd_m, tt::tolerance(1e-13));
    BOOST_TEST(rotd[i].rotd100_angle_deg == 0.0);
    // peak |x cos θ| = |cos θ| Sd. Over 0°, 1°, …, 179° the values |cos θ| come in equal pairs
    // (θ, 180° − θ) besides 1 (0°) and 0 (90°), so the two middle ones are |cos 45°| = |cos 135°|.
    BOOST_TEST(rotd[i].rotd50_sd_m == single[i].sd_m * std::cos(kPi / 4.0), tt::tolerance(1e-12));
  }
}

// RotD against the brute force: rotate the pair into each angle, take the one-component
// spectrum of the rotated record, then the median and the largest over the angles.
BOOST_AUTO_TEST_CASE(RotDMatchesABruteForceAngleLoop) {
  const AccelerationHistory first = wiggly(0.01, 5.0, 0.0);
  const AccelerationHistory second = wiggly(0.015, 4.0, 1.1);  // another grid: the common base is exercised
  const SpectrumOptions options{.periods_s = {0.1, 0.6, 1.7}, .damping_ratio = 0.05};
  const double step_deg = 5.0;
  const auto rotd = rotd_spectrum(first, second, options, step_deg);
  const auto [a, b] = on_common_time_base(first, second);
  for (std::size_t p = 0; p < options.periods_s.size(); ++p) {
    std::vector<double> peaks;
    for (double theta_deg = 0.0; theta_deg < 180.0; theta_deg += step_deg) {
      const double theta = theta_deg * kPi / 180.0;
      AccelerationHistory rotated{a.time_s, {}};
      for (std::size_t k = 0; k < a.time_s.size(); ++k) {
        rotated.accel_mps2.push_back(std::cos(theta) * a.accel_mps2[k] + std::sin(theta) * b.accel_mps2[k]);
      }
      const SpectrumOptions one{.periods_s = {options.periods_s[p]}, .damping_ratio = 0.05};
      peaks.push_back(response_spectrum(rotated, one)[0].sd_m);
    }
    std::sort(peaks.begin(), peaks.end());
    const double median = 0.5 * (peaks[peaks.size() / 2 - 1] + peaks[peaks.size() / 2]);
    BOOST_TEST(rotd[p].rotd100_sd_m == peaks.back(), tt::tolerance(1e-10));
    BOOST_TEST(rotd[p].rotd50_sd_m == median, tt::tolerance(1e-10));
  }
}

BOOST_AUTO_TEST_CASE(CommonTimeBaseKeepsEachRecordExactly) {
  const AccelerationHistory first{{0.0, 0.2, 0.4}, {0.0, 1.0, -1.0}};
  const AccelerationHistory second{{0.0, 0.3, 0.5}, {2.0, 0.5, 0.0}};
  const auto [a, b] = on_common_time_base(first, second);
  BOOST_TEST(a.time_s == (std::vector<double>{0.0, 0.2, 0.3, 0.4, 0.5}), tt::per_element());
  BOOST_TEST(a.accel_mps2[2] == 0.0, tt::tolerance(1e-15));  // halfway from 1 to −1
  BOOST_TEST(a.accel_mps2[4] == 0.0);                        // after its own end
  BOOST_TEST(b.accel_mps2[1] == 1.0, tt::tolerance(1e-15));  // 2 − 1.5·(0.2/0.3)
}

BOOST_AUTO_TEST_CASE(ScalingToAPseudoAccelerationHitsItToRoundOff) {
  AccelerationHistory record = wiggly(0.02, 8.0, 0.4);
  const double period = 0.73, target = 4.905;  // 0.5 g
  const double factor = scale_to_psa(record, period, 0.05, target);
  for (double& a : record.accel_mps2) a *= factor;
  const auto scaled = response_spectrum(record, {.periods_s = {period}, .damping_ratio = 0.05});
  BOOST_TEST(scaled[0].psa_mps2 == target, tt::tolerance(1e-13));
}

BOOST_AUTO_TEST_CASE(RefusesBadOptionsNamingTheField) {
  const AccelerationHistory record = wiggly(0.02, 1.0, 0.0);
  auto refuses = [&](const SpectrumOptions& options, const std::string& key) {
    try {
      response_spectrum(record, options);
    } catch (const pounding::InputError& error) {
      return error.key() == key;
    }
    return false;
  };
  BOOST_TEST(refuses({.periods_s = {1.0}, .damping_ratio = 1.0}, "damping_ratio"));
  BOOST_TEST(refuses({.periods_s = {1.0}, .damping_ratio = -0.1}, "damping_ratio"));
  BOOST_TEST(refuses({.periods_s = {1.0, 0.0}, .damping_ratio = 0.05}, "periods_s[2]"));
  BOOST_TEST(refuses({.periods_s = {std::nan("")}, .damping_ratio = 0.05}, "periods_s[1]"));
  BOOST_CHECK_THROW(scale_to_psa(record, 1.0, 0.05, -1.0), pounding::InputError);
  BOOST_CHECK_THROW(rotd_spectrum(record, record, {}, 0.0), pounding::InputError);
}
