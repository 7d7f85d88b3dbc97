#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "../support/two_slabs.hpp"
#include "pounding/analysis/contact_laws.hpp"
#include "pounding/analysis/run_scene.hpp"
#include "pounding/contact/kelvin.hpp"
#include "pounding/input_error.hpp"
#include "pounding/io/scene_reader.hpp"
#include "pounding/solvers/arkode_integrator.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using namespace pounding::testing;

namespace {

constexpr double kPi = std::numbers::pi;

solvers::IntegratorFactory arkode_dirk(double rtol, double atol) {
  return [=](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) {
    return solvers::make_arkode_integrator(
        functions, {.method = solvers::ArkodeMethod::dirk, .rtol = rtol, .atol = atol, .order = 4}, t0, y0);
  };
}

/// ξ of the Kelvin element, written out here (not the library's function): −ln e/√(π² + ln² e).
double damping_ratio(double e) {
  return e == 0.0 ? 1.0 : -std::log(e) / std::sqrt(kPi * kPi + std::log(e) * std::log(e));
}

/// The closed form of a lone Kelvin–Voigt contact (ω = 1, v₀ = 1), ξ < 1: δ = e^{−ξt} sin(ω_d t)/ω_d.
struct Oscillator {
  double xi, wd;
  explicit Oscillator(double x) : xi(x), wd(std::sqrt(1 - x * x)) {}
  double overlap(double t) const { return std::exp(-xi * t) * std::sin(wd * t) / wd; }
  double rate(double t) const { return std::exp(-xi * t) * (std::cos(wd * t) - xi / wd * std::sin(wd * t)); }
  double force(double t) const { return overlap(t) + 2 * xi * rate(t); }  // F / (μ ω v₀)
  /// The release: F = 0 past t = 0, bracketed in (π/2, π]/ω_d, found by bisection.
  double release() const {
    double a = kPi / (2 * wd), b = kPi / wd;
    for (int i = 0; i < 200; ++i) (force(0.5 * (a + b)) > 0 ? a : b) = 0.5 * (a + b);
    return 0.5 * (a + b);
  }
  /// The largest force on [0, release], by golden-section search (F rises, then falls).
  double peak_force() const {
    double a = 0.0, b = release();
    const double r = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 200; ++i) {
      const double c = b - r * (b - a), d = a + r * (b - a);
      (force(c) > force(d) ? b : a) = force(c) > force(d) ? d : c;
    }
    return force(0.5 * (a + b));
  }
};

// Two slabs head-on (the diamond's vertex in line with both CMs: no lever arm, so each slab's
// effective mass is its mass) on storeys so soft (T = 10⁴ s) that their forces are ~10⁻⁹ of the
// contact's: the relative normal motion is the closed form's oscillator exactly.
struct HeadOn {
  static constexpr double gap = 0.01, v0 = 0.5, m1 = 100.0, m2 = 200.0;
  dynamics::CoupledSystem system = two_slabs({m1, 1e4, 0.0}, diamond(gap), {m2, 1e4, 0.0}, gap, 0.4);
  static constexpr double mu = m1 * m2 / (m1 + m2);

  solvers::RunResult run(double e, double k, const solvers::IntegratorFactory& factory) const {
    solvers::EventOptions options;
    options.restitution = e;
    options.law = contact::ContactLaw::kelvin;
    options.contact_stiffness = k;
    options.initial_state = pushed(system, v0);
    return solvers::run_event_driven(system, options, factory, "test");
  }
};

void check_closed_form(double e, const solvers::IntegratorFactory& factory) {
  const HeadOn pair;
  const double k = 1e5, omega = std::sqrt(k / HeadOn::mu);
  const solvers::RunResult r = pair.run(e, k, factory);
  BOOST_TEST_CONTEXT("e = " << e) {
    BOOST_TEST(solvers::to_string(r.status) == "completed");
    BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
    BOOST_TEST(r.statistics.events == 3);  // onset, release, the gap opening: each a root
    const solvers::ImpactRecord& i = r.impacts.front();
    const Oscillator closed(damping_ratio(e));
    const double t_release = closed.release() / omega;  // after onset
    const double v_sep = -closed.rate(closed.release()) * HeadOn::v0;
    // Onset and release located to the solver's tolerance (rtol 1e-10: ~1e-9 of each time).
    BOOST_TEST(i.t_s == HeadOn::gap / HeadOn::v0, tt::tolerance(1e-8));
    BOOST_TEST(i.duration_s == t_release, tt::tolerance(1e-7));
    BOOST_TEST(i.approach_velocity_mps == HeadOn::v0, tt::tolerance(1e-8));
    BOOST_TEST(i.separation_velocity_mps == v_sep, tt::tolerance(1e-6));
    BOOST_TEST(i.impulse_kNs == HeadOn::mu * (HeadOn::v0 + v_sep), tt::tolerance(1e-6));
    BOOST_TEST(i.energy_lost_kJ == 0.5 * HeadOn::mu * (HeadOn::v0 * HeadOn::v0 - v_sep * v_sep), tt::tolerance(1e-5));
    // The peak is the largest of 17 interpolant samples a step: its error is second order in
    // the sample spacing, 1e-5 of the force here.
    BOOST_TEST(i.peak_force_kN == closed.peak_force() * HeadOn::mu * omega * HeadOn::v0, tt::tolerance(1e-4));
    // The library's closed form of the release agrees with this one.
    const contact::KelvinRelease release = contact::kelvin_release(contact::kelvin_damping_ratio(e));
    BOOST_TEST(release.omega_time == closed.release(), tt::tolerance(1e-12));
    BOOST_TEST(release.rebound == v_sep / HeadOn::v0, tt::tolerance(1e-12));
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(DampingRatioGivesTheRestitutionOfAFullHalfCycle) {
  // exp(−ξπ/√(1 − ξ²)) = e: the rebound of a Kelvin–Voigt element left to act until δ = 0.
  for (double e : {0.05, 0.3, 0.5, 0.8, 1.0}) {
    const double xi = contact::kelvin_damping_ratio(e);
    BOOST_TEST(std::exp(-xi * kPi / std::sqrt(1 - xi * xi)) == e, tt::tolerance(1e-13));
  }
  BOOST_TEST(contact::kelvin_damping_ratio(0.0) == 1.0);
}

BOOST_AUTO_TEST_CASE(ElasticKelvinContactLastsHalfAPeriodAndRebounds) {
  // e = 1: no dashpot, the force turns tensile exactly at δ = 0, after π/ω; the rebound is v₀.
  const HeadOn pair;
  const double k = 1e5, omega = std::sqrt(k / HeadOn::mu);
  const solvers::RunResult r = pair.run(1.0, k, cvode(1e-10, 1e-12));
  BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
  BOOST_TEST(r.impacts[0].duration_s == kPi / omega, tt::tolerance(1e-7));
  BOOST_TEST(r.impacts[0].separation_velocity_mps == HeadOn::v0, tt::tolerance(1e-7));
  BOOST_TEST(r.impacts[0].peak_force_kN == HeadOn::mu * omega * HeadOn::v0, tt::tolerance(1e-5));
}

BOOST_AUTO_TEST_CASE(KelvinContactMatchesClosedFormOnCvodeBdf) {
  for (double e : {0.9, 0.5, 0.1, 0.0}) {
    if (e == 0.0) continue;  // ξ = 1 has no ω_d; its own case below
    check_closed_form(e, cvode(1e-10, 1e-12));
  }
}

BOOST_AUTO_TEST_CASE(KelvinContactMatchesClosedFormOnArkodeDirk) { check_closed_form(0.5, arkode_dirk(1e-10, 1e-12)); }

BOOST_AUTO_TEST_CASE(CriticallyDampedContactForPlasticRestitution) {
  // e = 0 → ξ = 1: δ = v₀ t e^{−ωt}, F ∝ 2 − ωt, released at ωt = 2 rebounding at e⁻² v₀.
  const HeadOn pair;
  const double k = 1e5, omega = std::sqrt(k / HeadOn::mu);
  const solvers::RunResult r = pair.run(0.0, k, cvode(1e-10, 1e-12));
  BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
  BOOST_TEST(r.impacts[0].duration_s == 2.0 / omega, tt::tolerance(1e-7));
  BOOST_TEST(r.impacts[0].separation_velocity_mps == std::exp(-2.0) * HeadOn::v0, tt::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(StiffKelvinContactTendsToTheImpulseLaw) {
  // On storeys of T = 0.5 s the structure acts during a contact of finite length; as k grows the
  // contact shortens and the outcome tends to the impulse law's with the Kelvin element's
  // effective restitution (kelvin_release: the tension-free release rebounds above e).
  const double gap = 0.01, v0 = 0.5, e = 0.5;
  const dynamics::CoupledSystem system = two_slabs({100.0, 0.5, 0.05}, diamond(gap), {200.0, 0.3, 0.05}, gap, 0.1);
  solvers::EventOptions impulse;
  impulse.restitution = contact::kelvin_release(contact::kelvin_damping_ratio(e)).rebound;
  impulse.initial_state = pushed(system, v0);
  const solvers::RunResult reference = solvers::run_event_driven(system, impulse, cvode(1e-11, 1e-13), "impulse");
  BOOST_TEST_REQUIRE(reference.impacts.size() == 1u);
  std::vector<double> errors;
  for (double k : {1e5, 1e6, 1e7, 1e8}) {
    solvers::EventOptions options = impulse;
    options.restitution = e;
    options.law = contact::ContactLaw::kelvin;
    options.contact_stiffness = k;
    const solvers::RunResult r = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "kelvin");
    BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
    const double velocity_error =
        std::abs(r.impacts[0].separation_velocity_mps - reference.impacts[0].separation_velocity_mps);
    const double impulse_error = std::abs(r.impacts[0].impulse_kNs - reference.impacts[0].impulse_kNs) / 200.0;
    errors.push_back(std::max(velocity_error, impulse_error));
    BOOST_TEST_MESSAGE("k = " << k << " kN/m: post-impact velocity error " << errors.back() << " m/s");
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    // The contact lasts ∝ k^{-1/2}; the structure's impulse over it, so the error, falls as much.
    const double rate = std::log10(errors[i - 1] / errors[i]);
    BOOST_TEST_MESSAGE("observed order in k: " << rate);
    BOOST_TEST(rate > 0.4);
    BOOST_TEST(rate < 0.7);
  }
  BOOST_TEST(errors.back() < 0.01 * v0);  // 0.24 % at 1e8 kN/m (contact of 3 ms)
}

BOOST_AUTO_TEST_CASE(PaperSceneRunsWithKelvinOnEventDrivenMethods) {
  // Before the first contact both laws integrate the same free motion: the first onset is the
  // impulse law's first impact.
  const analysis::RunReport impulse = analysis::run_scene(io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml"));
  BOOST_TEST_REQUIRE(!impulse.result.impacts.empty());
  for (const char* method : {"cvode-bdf", "arkode-dirk"}) {
    analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml",
                                           {.contact = {{"--contact-law", std::string("kelvin")}}});
    scene.solver = analysis::with_method(scene.solver, method);
    const analysis::RunReport report = analysis::run_scene(scene);
    BOOST_TEST_CONTEXT(method) {
      BOOST_TEST(solvers::to_string(report.result.status) == "completed");
      BOOST_TEST(report.contact_law == "kelvin");
      BOOST_TEST(report.contact_stiffness == 93.5e3);
      BOOST_TEST(!report.result.impacts.empty());
      BOOST_TEST(report.result.impacts.front().t_s == impulse.result.impacts.front().t_s, tt::tolerance(1e-6));
      for (const solvers::ImpactRecord& i : report.result.impacts) {
        BOOST_TEST(i.duration_s > 0.0);
        BOOST_TEST(i.peak_force_kN > 0.0);
        BOOST_TEST(i.t_s + i.duration_s < report.result.end_s);  // every contact ended within the run
      }
      BOOST_TEST(report.result.sustained_contacts.empty());
      // The contacts' losses close the energy audit (as impulses' do, to 1e-6 of the input).
      const solvers::EnergyAudit& energy = report.result.energy;
      BOOST_TEST(energy.impact_loss_kJ > 0.0);
      BOOST_TEST(std::abs(energy.residual_kJ()) < 1e-6 * energy.input_kJ);
    }
  }
}

BOOST_AUTO_TEST_CASE(CompliantLawsAreRefusedWhereTheyCannotRun) {
  analysis::Scene scene = io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml",
                                         {.contact = {{"--contact-law", std::string("kelvin")}}});
  for (const char* method : {"hht", "exact"}) {
    scene.solver = analysis::with_method(scene.solver, method);
    try {
      analysis::run_scene(scene);
      BOOST_FAIL("kelvin ran on " << method);
    } catch (const InputError& error) {
      const std::string text = error.what();
      BOOST_TEST(text.find("kelvin") != std::string::npos);
      BOOST_TEST(text.find(method) != std::string::npos);
    }
  }
  // A law key given for the impulse law is refused like an inapplicable solver setting.
  BOOST_CHECK_THROW(
      io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml", {.contact = {{"--contact-stiffness", 1e6}}}),
      InputError);
  BOOST_CHECK_THROW(
      io::read_scene(POUNDING_EXAMPLES_DIR "/paper/paper.toml", {.contact = {{"--contact-law", std::string("hertz")}}}),
      InputError);
}

BOOST_AUTO_TEST_CASE(ImpulseLawImpactsCarryNoForceOrDuration) {
  const HeadOn pair;
  solvers::EventOptions options;
  options.initial_state = pushed(pair.system, HeadOn::v0);
  const solvers::RunResult r = solvers::run_event_driven(pair.system, options, cvode(1e-10, 1e-12), "impulse");
  BOOST_TEST_REQUIRE(r.impacts.size() == 1u);
  BOOST_TEST(r.impacts[0].duration_s == 0.0);
  BOOST_TEST(r.impacts[0].peak_force_kN == 0.0);
}

BOOST_AUTO_TEST_CASE(ContactJacobianMatchesFiniteDifferences) {
  // The analytic terms (G frozen) against central differences of the force's accelerations, at
  // an overlap with a rotated, moving pair: what G's turning adds is first order in the motion.
  const HeadOn pair;
  const dynamics::CoupledSystem& system = pair.system;
  const double k = 1e6, c = 2e3;
  const std::size_t index = 0;
  const int n = system.dof();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(system.state_size());
  y[system.floor_index(0, 1)] = 0.0102;    // building 1 overlaps building 2 by 0.2 mm
  y[system.floor_index(0, 1) + 2] = 1e-4;  // and both turn a little
  y[system.floor_index(1, 1) + 2] = -2e-4;
  y[n + system.floor_index(0, 1)] = 0.3;
  y[n + system.floor_index(1, 1) + 2] = 0.01;
  BOOST_TEST_REQUIRE(system.gap(y, index).gap_m < 0.0);
  auto contact_rhs = [&](const Eigen::VectorXd& state) {
    Eigen::VectorXd y_dot = Eigen::VectorXd::Zero(system.state_size());
    const contact::GapState s = system.gap(state, index);
    system.add_contact_force(state, index, -k * s.gap_m - c * s.gap_rate_mps, y_dot);
    return y_dot;
  };
  Eigen::SparseMatrix<double> rows(n, 2 * n);
  system.add_contact_force_jacobian(y, index, k, c, rows);
  Eigen::MatrixXd analytic = Eigen::MatrixXd::Zero(system.state_size(), system.state_size());
  analytic.bottomRows(n) = rows;  // the velocity rows carry no contact force
  Eigen::MatrixXd numeric(system.state_size(), system.state_size());
  for (int j = 0; j < system.state_size(); ++j) {
    const double h = 1e-7;
    Eigen::VectorXd plus = y, minus = y;
    plus[j] += h;
    minus[j] -= h;
    numeric.col(j) = (contact_rhs(plus) - contact_rhs(minus)) / (2 * h);
  }
  BOOST_TEST((analytic - numeric).norm() < 1e-3 * numeric.norm());
  // The translational columns carry no turning of G: there they agree to the differences' error.
  for (int j : {system.floor_index(0, 1), system.floor_index(1, 1)}) {
    BOOST_TEST((analytic.col(j) - numeric.col(j)).norm() < 1e-6 * numeric.norm());
  }
}
