#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/contact/kelvin.hpp"
#include "pounding/io/scene_reader.hpp"

// The quantities engineers design with (Recorder): absolute floor accelerations against closed
// forms, storey drift ratios against the history's own displacements, and contact forces
// against the Kelvin law evaluated on the sampled gap.

namespace tt = boost::test_tools;
using namespace pounding;
using namespace pounding::testing;

namespace {

constexpr double kPi = std::numbers::pi;

std::size_t column(const solvers::History& h, const std::string& name) {
  const auto found = std::find(h.columns.begin(), h.columns.end(), name);
  BOOST_REQUIRE_MESSAGE(found != h.columns.end(), "no column " << name);
  return static_cast<std::size_t>(found - h.columns.begin()) - 1;  // rows hold the columns after t_s
}

/// x'' + 2ζωx' + ω²x = −A from rest (a single storey under a ground step A): relative x and x'.
struct StepResponse {
  double A, omega, zeta;
  double wd() const { return omega * std::sqrt(1 - zeta * zeta); }
  double x(double t) const {
    return -A / (omega * omega) *
           (1 - std::exp(-zeta * omega * t) * (std::cos(wd() * t) + zeta * omega / wd() * std::sin(wd() * t)));
  }
  double rate(double t) const {
    return -A / (omega * omega) * std::exp(-zeta * omega * t) * omega * omega / wd() * std::sin(wd() * t);
  }
  /// Absolute acceleration x'' + A = −ω²x − 2ζωx'.
  double absolute_accel(double t) const { return -omega * omega * x(t) - 2 * zeta * omega * rate(t); }
};

// Two one-storey buildings of equal period (so they move as one and never touch) under a
// constant ground acceleration from rest: the x mode is uncoupled and damped at exactly ζ.
struct StepCase {
  static constexpr double A = 2.0, period = 0.5, zeta = 0.05, duration = 2.0;
  dynamics::CoupledSystem system =
      two_slabs({100.0, period, zeta}, box(0.5, 0, 10.5, 10), {100.0, period, zeta}, 0.5, duration, A);
  StepResponse exact{A, 2 * kPi / period, zeta};

  solvers::RunResult run() const {
    solvers::EventOptions options;
    options.history_interval_s = 0.01;
    return solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "test");
  }
};

}  // namespace

// The history's absolute acceleration is x'' + a_g from the model's rhs: −ω²x − 2ζωx' of the
// closed form at every sample (leaving out a_g would be off by A = 2 m/s²).
BOOST_AUTO_TEST_CASE(AbsoluteAccelerationMatchesTheStepResponse) {
  const StepCase c;
  const solvers::RunResult r = c.run();
  BOOST_TEST(solvers::to_string(r.status) == "completed");
  BOOST_TEST(r.impacts.empty());
  const std::size_t ax = column(r.history, "B1_f1_ax_abs_mps2"), ay = column(r.history, "B1_f1_ay_abs_mps2");
  double worst = 0.0;
  for (std::size_t k = 0; k < r.history.time_s.size(); ++k) {
    const double t = r.history.time_s[k];
    worst = std::max(worst, std::abs(r.history.rows[k][static_cast<Eigen::Index>(ax)] - c.exact.absolute_accel(t)));
    BOOST_TEST(std::abs(r.history.rows[k][static_cast<Eigen::Index>(ay)]) < 1e-12);  // shaking along x only
  }
  BOOST_TEST(worst < 1e-6 * c.A);  // tolerance of the run: rtol 1e-11 on x, times ω² = 158/s²
}

// The peak is the closed form's largest |a_abs| (its first turning point, at about half a period),
// located between samples: the 0.01 s samples alone miss it by up to 1 − cos(ω·0.005 s) = 0.2 %.
BOOST_AUTO_TEST_CASE(AccelerationPeakIsLocatedOnTheDenseOutput) {
  const StepCase c;
  const solvers::RunResult r = c.run();
  // Golden-section search of |a_abs| near its first maximum, t ∈ [0.3, 0.7] T.
  double a = 0.3 * c.period, b = 0.7 * c.period;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double p = b - g * (b - a), q = a + g * (b - a);
    (std::abs(c.exact.absolute_accel(p)) > std::abs(c.exact.absolute_accel(q)) ? b : a) =
        std::abs(c.exact.absolute_accel(p)) > std::abs(c.exact.absolute_accel(q)) ? q : p;
  }
  const double t_peak = 0.5 * (a + b), peak = c.exact.absolute_accel(t_peak);
  const solvers::Peak& got = r.peaks[0].floors[0].ax_abs_mps2;
  BOOST_TEST(got.value == peak, tt::tolerance(1e-7));
  BOOST_TEST(std::abs(got.t_s - t_peak) < 1e-4);  // a flat turning point: its time is less sharp
}

// Free vibration with the CM's drift: ẍ_abs = −ω² x − 2ζω ẋ also holds without excitation
// (the impulse law's smooth part is exactly this between impacts).
BOOST_AUTO_TEST_CASE(FreeVibrationAccelerationIsMinusOmegaSquaredXMinusDamping) {
  const double period = 0.5, zeta = 0.05, v0 = 0.2, omega = 2 * kPi / period;
  const dynamics::CoupledSystem system =
      two_slabs({100.0, period, zeta}, box(1.0, 0, 11, 10), {100.0, period, zeta}, 1.0, 1.0);
  solvers::EventOptions options;
  options.initial_state = pushed(system, v0);
  const solvers::RunResult r = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "test");
  const std::size_t u = column(r.history, "B1_f1_u_m"), ax = column(r.history, "B1_f1_ax_abs_mps2"),
                    drift = column(r.history, "B1_f1_drift_x");
  const double wd = omega * std::sqrt(1 - zeta * zeta);
  for (std::size_t k = 0; k < r.history.time_s.size(); k += 7) {
    const double t = r.history.time_s[k], decay = std::exp(-zeta * omega * t);
    const double x = v0 / wd * decay * std::sin(wd * t);
    const double rate = v0 * decay * (std::cos(wd * t) - zeta * omega / wd * std::sin(wd * t));
    BOOST_TEST(r.history.rows[k][static_cast<Eigen::Index>(ax)] == -omega * omega * x - 2 * zeta * omega * rate,
               tt::tolerance(1e-6 * v0 * omega));
    BOOST_TEST(
        r.history.rows[k][static_cast<Eigen::Index>(drift)] == r.history.rows[k][static_cast<Eigen::Index>(u)] / 3.0,
        tt::tolerance(1e-15));  // a one-storey building of height 3 m
  }
}

// Unequal storeys (building 2 on a 6 m ground storey) with torsion: every drift column is the
// displacement difference of the point over the storey height, computed here from the history's
// own u, v, φ with exact rotation; and no sample beats the summary's peaks.
BOOST_AUTO_TEST_CASE(DriftRatiosAreRelativeDisplacementOverStoreyHeight) {
  const analysis::RunReport report =
      analysis::run_scene(io::read_scene(POUNDING_EXAMPLES_DIR "/levels/unequal-storeys.toml"));
  const solvers::History& h = report.result.history;
  BOOST_REQUIRE(!h.rows.empty());
  // Levels j = B1 floor j + 1 and B2 floor j, so B2 floors 1-6 and B1 floors 2-7 are written.
  struct Case {
    int building, floor, below;  // below: 0 for the ground
    double height_m;
  };
  const Case cases[] = {{2, 1, 0, 6.0}, {2, 2, 1, 3.0}, {1, 3, 2, 3.0}};
  const analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/levels/unequal-storeys.toml");
  for (const Case& c : cases) {
    const model::Polygon& slab = scene.buildings[static_cast<std::size_t>(c.building - 1)].slab;
    const model::Point2 centre = scene.buildings[static_cast<std::size_t>(c.building - 1)].centre_of_mass;
    auto displacement = [&](const Eigen::VectorXd& row, int floor, const model::Point2& arm) -> model::Point2 {
      if (floor == 0) return model::Point2::Zero();
      const std::string prefix = "B" + std::to_string(c.building) + "_f" + std::to_string(floor) + "_";
      const double u = row[static_cast<Eigen::Index>(column(h, prefix + "u_m"))];
      const double v = row[static_cast<Eigen::Index>(column(h, prefix + "v_m"))];
      const double phi = row[static_cast<Eigen::Index>(column(h, prefix + "phi_rad"))];
      return {u + (std::cos(phi) - 1) * arm.x() - std::sin(phi) * arm.y(),
              v + std::sin(phi) * arm.x() + (std::cos(phi) - 1) * arm.y()};
    };
    const std::string prefix = "B" + std::to_string(c.building) + "_f" + std::to_string(c.floor) + "_";
    const solvers::FloorPeaks& peaks =
        report.result.peaks[static_cast<std::size_t>(c.building - 1)].floors[static_cast<std::size_t>(c.floor - 1)];
    double largest_x = 0.0, largest_corner = 0.0;
    for (std::size_t k = 0; k < h.rows.size(); ++k) {
      const Eigen::VectorXd& row = h.rows[k];
      for (std::size_t corner = 0; corner <= slab.size(); ++corner) {
        const model::Point2 arm = corner == 0 ? model::Point2::Zero() : model::Point2(slab.vertex(corner - 1) - centre);
        const model::Point2 drift = (displacement(row, c.floor, arm) - displacement(row, c.below, arm)) / c.height_m;
        const std::string name = corner == 0 ? prefix + "drift_" : prefix + "c" + std::to_string(corner) + "_drift_";
        BOOST_TEST(row[static_cast<Eigen::Index>(column(h, name + "x"))] == drift.x(), tt::tolerance(1e-12));
        BOOST_TEST(row[static_cast<Eigen::Index>(column(h, name + "y"))] == drift.y(), tt::tolerance(1e-12));
        if (corner == 0)
          largest_x = std::max(largest_x, std::abs(drift.x()));
        else
          largest_corner = std::max({largest_corner, std::abs(drift.x()), std::abs(drift.y())});
      }
    }
    BOOST_TEST(largest_x > 1e-3);  // the scene pounds: drifts of some per mille at least
    BOOST_TEST(std::abs(peaks.drift_x.value) >= largest_x * (1 - 1e-12));
    BOOST_TEST(std::abs(peaks.drift_x.value) <= largest_x * 1.05);  // located between 0.01 s samples
    BOOST_TEST(std::abs(solvers::worst_corner_drift(peaks).peak.value) >= largest_corner * (1 - 1e-12));
  }
}

// A lone head-on Kelvin contact sampled every 0.1 ms: each force sample is k δ + c δ̇ of the
// sampled gap and gap rate, c = 2ξ√(k m₁m₂/(m₁ + m₂)) written out here (head-on: no lever arm,
// so the effective masses are the slab masses), and samples exist only while the contact pushes.
BOOST_AUTO_TEST_CASE(ContactForceSamplesAreTheKelvinLawOfTheSampledGap) {
  constexpr double gap = 0.01, v0 = 0.5, m1 = 100.0, m2 = 200.0, k = 1e5, e = 0.5;
  const dynamics::CoupledSystem system = two_slabs({m1, 1e4, 0.0}, diamond(gap), {m2, 1e4, 0.0}, gap, 0.1);
  solvers::EventOptions options;
  options.restitution = e;
  options.law = contact::ContactLaw::kelvin;
  options.contact_stiffness = k;
  options.initial_state = pushed(system, v0);
  options.history_interval_s = 1e-4;
  const solvers::RunResult r = solvers::run_event_driven(system, options, cvode(1e-10, 1e-12), "test");
  BOOST_REQUIRE_EQUAL(r.impacts.size(), 1u);
  const solvers::ImpactRecord& impact = r.impacts.front();
  const double xi = -std::log(e) / std::sqrt(kPi * kPi + std::log(e) * std::log(e));
  const double c = 2 * xi * std::sqrt(k * m1 * m2 / (m1 + m2));
  const auto& samples = r.history.contact_forces;
  BOOST_TEST(samples.size() > 50u);  // π/ω ≈ 3.6 ms of contact at 0.1 ms
  double largest = 0.0;
  for (const solvers::ContactForceSample& s : samples) {
    BOOST_TEST(s.force_kN == -k * s.gap_m - c * s.gap_rate_mps, tt::tolerance(1e-9));
    BOOST_TEST(s.t_s >= impact.t_s);
    BOOST_TEST(s.t_s <= impact.t_s + impact.duration_s);
    BOOST_TEST(s.striking_building == impact.striking_building);
    BOOST_TEST(s.vertex == impact.vertex);
    largest = std::max(largest, s.force_kN);
  }
  // The impact's peak is the largest force at the quadrature nodes of each step (event_driven.cpp,
  // integrate_contacts), not located between them: a sample may exceed it by a hair.
  BOOST_TEST(largest <= impact.peak_force_kN * (1 + 1e-5));
  BOOST_TEST(largest >= 0.98 * impact.peak_force_kN);  // 0.1 ms of 3.6 ms: near the peak
  // The contact force is in the accelerations: slab 1 decelerates by F/m₁ at each sample.
  const std::size_t ax = column(r.history, "B1_f1_ax_abs_mps2");
  for (const solvers::ContactForceSample& s : samples) {
    const auto row = std::find(r.history.time_s.begin(), r.history.time_s.end(), s.t_s) - r.history.time_s.begin();
    // Storeys of period 10⁴ s add ~10⁻⁹ of the contact's acceleration.
    BOOST_TEST(r.history.rows[static_cast<std::size_t>(row)][static_cast<Eigen::Index>(ax)] == -s.force_kN / m1,
               tt::tolerance(1e-6));
  }
}

// The impulse law's analogue of a force history: the force λ holding a sustained contact. On the
// paper scene (six holds) every sample lies within a hold of its contact and the largest sample
// of each hold does not exceed the hold's own maximum, which the solver tracks on every step.
BOOST_AUTO_TEST_CASE(HoldForcesAreSampledWithinTheirSustainedContacts) {
  analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml");
  scene.output.history_interval_s = 1e-3;
  const analysis::RunReport report = analysis::run_scene(scene);
  const solvers::RunResult& r = report.result;
  BOOST_REQUIRE(!r.sustained_contacts.empty());
  BOOST_TEST(r.history.contact_forces.size() > 50u);
  for (const solvers::SustainedContactRecord& hold : r.sustained_contacts) {
    double largest = 0.0;
    std::size_t samples = 0;
    for (const solvers::ContactForceSample& s : r.history.contact_forces) {
      if (s.candidate != hold.candidate || s.t_s < hold.start_s || s.t_s > hold.release_s) continue;
      largest = std::max(largest, s.force_kN);
      ++samples;
    }
    BOOST_TEST_CONTEXT("hold from " << hold.start_s << " s") {
      BOOST_TEST(samples >= 1u);  // at least its start's event row
      BOOST_TEST(largest <= hold.max_force_kN * (1 + 1e-9));
      if (hold.release_s - hold.start_s > 0.02) BOOST_TEST(largest >= 0.9 * hold.max_force_kN);
    }
  }
  for (const solvers::ContactForceSample& s : r.history.contact_forces) {
    const auto hold = std::find_if(r.sustained_contacts.begin(), r.sustained_contacts.end(), [&](const auto& h) {
      return h.candidate == s.candidate && s.t_s >= h.start_s && s.t_s <= h.release_s;
    });
    BOOST_REQUIRE_MESSAGE(hold != r.sustained_contacts.end(),
                          "a force sample at " << s.t_s << " s outside every hold of candidate " << s.candidate);
    BOOST_TEST(s.force_kN >= -1e-6);  // compressive (a hold is released where λ turns tensile)
    BOOST_TEST(std::abs(s.gap_m) <= hold->max_gap_drift_m * (1 + 1e-9));  // held closed, up to its drift
  }
}
