// Yielding columns (dynamics/yielding_springs.hpp, solvers/yield_states.hpp) against closed forms:
// a one-storey building on four equal columns placed symmetrically about its centre of mass is,
// in x, a single-degree-of-freedom bilinear oscillator of mass m and stiffness k = 4 k_c. Released
// at rest position with velocity v0 (no damping, no ground motion), it moves elastically to the
// yield drift d_y, then on the hardening branch α k to its peak, and unloads there:
//   elastic:   x = (v0/ω) sin ωt up to x = d_y, at t₁ = asin(ω d_y / v0)/ω, speed v₁² = v0² − ω² d_y²;
//   hardening: ½ m v₁² = ½ α k (x_max² − d_y²) + (1 − α) k d_y (x_max − d_y)  (work to the peak),
//              x(t) = x_c + (d_y − x_c) cos ω_α τ + (v₁/ω_α) sin ω_α τ, x_c = −(1 − α) d_y / α,
//              ω_α = √α ω (for α = 0: x = d_y + v₁ τ − ½ ω² d_y τ²);
//   then the slip is s = x_max − d_y, the dissipated energy (1 − α) k d_y s, and the building
//   swings elastically about x = (1 − α) s with amplitude x_max − (1 − α) s.
// The four x-springs yield in the same instant (simultaneous branch changes).

#define BOOST_TEST_MODULE yielding
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <numbers>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/event_driven.hpp"

namespace tt = boost::test_tools;
using namespace pounding;

namespace {

constexpr double kMass_t = 500.0, kE_kPa = 3e7, kSide_m = 0.5, kHeight_m = 3.0;
// k of one column, 12 E I / H³ with I = b⁴/12, written out here (not model::column_stiffness).
const double kColumn_kN_per_m = 12.0 * kE_kPa * std::pow(kSide_m, 4) / 12.0 / std::pow(kHeight_m, 3);

model::Building column_building(const char* name, double x_centre, const model::HystereticLaw& law) {
  model::BuildingDefinition b;
  b.name = name;
  b.storeys = 1;
  b.storey_height_m = {kHeight_m};
  const double x0 = x_centre - 6.0, x1 = x_centre + 6.0;
  b.slab = model::Polygon({{x0, -6.0}, {x1, -6.0}, {x1, 6.0}, {x0, 6.0}});
  b.centre_of_mass = {x_centre, 0.0};
  b.mass_t = {kMass_t};
  b.polar_moment_tm2 = {model::uniform_polar_moment(b.slab, kMass_t)};
  for (double dx : {-5.0, 5.0}) {
    for (double dy : {-5.0, 5.0})
      b.columns.push_back({.position_m = {x_centre + dx, dy}, .b_m = kSide_m, .h_m = kSide_m});
  }
  b.E_kPa = kE_kPa;
  b.frame_factor = 1.0;
  b.damping = {0.0, {1, 3}};
  b.hysteresis = law;
  return model::make_building(b);
}

/// Building 1 yields; building 2 stays elastic 20 m away (no contact candidates).
dynamics::CoupledSystem system_of(const model::HystereticLaw& law, double duration_s) {
  std::array<model::Building, 2> buildings{column_building("A", 0.0, law), column_building("B", 40.0, {})};
  excitation::GroundMotion quiet({0.0, duration_s}, {0.0, 0.0}, 0.0);
  return dynamics::CoupledSystem(std::move(buildings), std::move(quiet), {}, {});
}

solvers::IntegratorFactory cvode(double rtol, double atol) {
  return [=](solvers::OdeFunctions& f, double t0, const Eigen::VectorXd& y0) -> std::unique_ptr<solvers::Integrator> {
    return std::make_unique<solvers::CvodeIntegrator>(
        f, solvers::CvodeSettings{.method = solvers::CvodeMethod::bdf, .rtol = rtol, .atol = atol}, t0, y0);
  };
}

struct Bilinear {
  double k, m, d_y, alpha, v0;
  double omega() const { return std::sqrt(k / m); }
  double t_yield() const { return std::asin(omega() * d_y / v0) / omega(); }
  double v_yield() const { return std::sqrt(v0 * v0 - omega() * omega() * d_y * d_y); }
  double x_max() const {
    const double kinetic = 0.5 * m * v_yield() * v_yield();
    if (alpha == 0.0) return d_y + kinetic / (k * d_y);
    // ½ α k x² + (1 − α) k d_y x − [½ α k d_y² + (1 − α) k d_y² + kinetic] = 0
    const double a = 0.5 * alpha * k, b = (1.0 - alpha) * k * d_y;
    const double c = -(0.5 * alpha * k * d_y * d_y + (1.0 - alpha) * k * d_y * d_y + kinetic);
    return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  }
  /// The time from yield to the peak on the hardening branch.
  double hardening_time() const {
    if (alpha == 0.0) return v_yield() / (omega() * omega() * d_y);
    const double w = std::sqrt(alpha) * omega(), centre = -(1.0 - alpha) * d_y / alpha;
    // ẋ = −w (d_y − x_c) sin wτ + v₁ cos wτ = 0
    return std::atan2(v_yield(), w * (d_y - centre)) / w;
  }
  double slip() const { return x_max() - d_y; }
};

}  // namespace

BOOST_AUTO_TEST_CASE(BilinearOscillatorReleasedWithAVelocityFollowsItsClosedForm) {
  for (double alpha : {0.0, 0.1}) {
    BOOST_TEST_CONTEXT("hardening ratio " << alpha) {
      const Bilinear sdof{4.0 * kColumn_kN_per_m, kMass_t, 0.01, alpha, 0.5};
      const double t_peak = sdof.t_yield() + sdof.hardening_time();
      // A quarter of an elastic period after the peak: well before the far side of the swing.
      const double t_end = t_peak + 0.25 * 2.0 * std::numbers::pi / sdof.omega();
      const auto system = system_of(
          {.kind = model::HystereticLaw::Kind::bilinear, .yield_drift_m = sdof.d_y, .hardening_ratio = alpha}, t_end);
      BOOST_TEST_REQUIRE(system.springs().size() == 8u);  // 4 columns × (x, y)
      solvers::EventOptions options;
      options.initial_state = Eigen::VectorXd::Zero(system.state_size());
      options.initial_state[system.dof()] = sdof.v0;  // u̇ of building A's floor 1
      const solvers::RunResult run = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "cvode-bdf");
      BOOST_TEST(solvers::to_string(run.status) == "completed");
      BOOST_TEST_REQUIRE(run.springs.size() == 8u);
      // Two branch changes for each of the four x-springs: yield and unload.
      BOOST_TEST(run.statistics.yield_events == 8);
      const double x_end = (1.0 - alpha) * sdof.slip();  // the swing's centre, reached after a quarter period
      for (std::size_t j = 0; j < run.springs.size(); ++j) {
        const solvers::SpringResult& r = run.springs[j];
        if (system.springs()[j].direction == 1) {
          BOOST_TEST(r.yield_count == 0);
          continue;
        }
        BOOST_TEST(r.yield_count == 1);
        BOOST_TEST(std::abs(r.first_yield_t_s - sdof.t_yield()) < 1e-9);
        BOOST_TEST(std::abs(r.peak_drift_m - sdof.x_max()) < 1e-9);
        BOOST_TEST(std::abs(r.final_slip_m - sdof.slip()) < 1e-9);
        BOOST_TEST(std::abs(r.final_drift_m - x_end) < 1e-8);
        BOOST_TEST(r.hysteretic_kJ == (1.0 - alpha) * kColumn_kN_per_m * sdof.d_y * sdof.slip(), tt::tolerance(1e-8));
      }
      // Energy: the initial kinetic energy is what the springs store and dissipated at the end.
      const double initial_kJ = 0.5 * kMass_t * sdof.v0 * sdof.v0;
      BOOST_TEST(run.energy.kinetic_kJ + run.energy.strain_kJ + run.energy.hysteretic_kJ == initial_kJ,
                 tt::tolerance(1e-8));
    }
  }
}

BOOST_AUTO_TEST_CASE(ElasticColumnsAddNoWitnessesAndNoOutputs) {
  const auto system = system_of({}, 0.1);
  BOOST_TEST(system.springs().empty());
  solvers::EventOptions options;
  options.initial_state = Eigen::VectorXd::Zero(system.state_size());
  options.initial_state[system.dof()] = 0.5;
  const solvers::RunResult run = solvers::run_event_driven(system, options, cvode(1e-10, 1e-12), "cvode-bdf");
  BOOST_TEST(run.springs.empty());
  BOOST_TEST(run.statistics.yield_events == 0);
  BOOST_TEST(run.energy.hysteretic_kJ == 0.0);
}
