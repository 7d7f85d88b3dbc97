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
// The four x-springs yield in the same instant (simultaneous branch changes). With P-Δ both
// branches lose k_g = m g / H, so without hardening the post-yield branch is unstable (hyperbolic).

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <numbers>

#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/event_driven.hpp"

namespace tt = boost::test_tools;
using namespace pounding;

namespace {

constexpr double kMass_t = 500.0, kE_kPa = 3e7, kSide_m = 0.5, kHeight_m = 3.0, kGravity_mps2 = 9.81;
// k of one column, 12 E I / H³ with I = b⁴/12, written out here (not model::column_stiffness).
const double kColumn_kN_per_m = 12.0 * kE_kPa * std::pow(kSide_m, 4) / 12.0 / std::pow(kHeight_m, 3);

model::Building column_building(const char* name, double x_centre, const model::HystereticLaw& law,
                                bool p_delta = false) {
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
  b.p_delta = p_delta;
  b.g_mps2 = kGravity_mps2;
  return model::make_building(b);
}

/// Building 1 yields; building 2 stays elastic 20 m away (no contact candidates).
dynamics::CoupledSystem system_of(const model::HystereticLaw& law, double duration_s, bool p_delta = false) {
  std::vector<model::Building> buildings{column_building("A", 0.0, law, p_delta), column_building("B", 40.0, {})};
  excitation::GroundMotion quiet({0.0, duration_s}, {0.0, 0.0}, 0.0);
  return dynamics::CoupledSystem(std::move(buildings), std::move(quiet), {}, {});
}

solvers::IntegratorFactory cvode(double rtol, double atol) {
  return [=](solvers::OdeFunctions& f, double t0, const Eigen::VectorXd& y0) -> std::unique_ptr<solvers::Integrator> {
    return std::make_unique<solvers::CvodeIntegrator>(
        f, solvers::CvodeSettings{.method = solvers::CvodeMethod::bdf, .rtol = rtol, .atol = atol}, t0, y0);
  };
}

/// The oscillator of the header comment, with P-Δ: the gravity load m g over the storey height
/// lowers both branches' stiffness by k_g = m g / H (k_g = 0 without P-Δ).
struct Bilinear {
  double k, k_g, m, d_y, alpha, v0;
  double k_elastic() const { return k - k_g; }
  double k_post() const { return alpha * k - k_g; }
  double plastic_force() const { return (1.0 - alpha) * k * d_y; }
  double omega() const { return std::sqrt(k_elastic() / m); }
  double t_yield() const { return std::asin(omega() * d_y / v0) / omega(); }
  double v_yield() const { return std::sqrt(v0 * v0 - omega() * omega() * d_y * d_y); }
  /// ½ k_post (x² − d_y²) + F₀ (x − d_y) = ½ m v₁²: the work to the peak; its smallest root past d_y.
  double x_max() const {
    const double kinetic = 0.5 * m * v_yield() * v_yield(), f0 = plastic_force();
    if (k_post() == 0.0) return d_y + kinetic / f0;
    const double c = 0.5 * k_post() * d_y * d_y + f0 * d_y + kinetic;
    const double root = std::sqrt(f0 * f0 + 2.0 * k_post() * c);
    return k_post() > 0.0                  ? (-f0 + root) / k_post()
           : (-f0 + root) / k_post() > d_y ? (-f0 + root) / k_post()
                                           : (-f0 - root) / k_post();
  }
  /// The time from yield to the peak on the post-yield branch m ẍ = −k_post x − F₀, which is
  /// harmonic (k_post > 0), uniformly decelerated (0) or hyperbolic (< 0, P-Δ beyond the hardening).
  double post_yield_time() const {
    if (k_post() == 0.0) return v_yield() / (plastic_force() / m);
    const double centre = -plastic_force() / k_post();
    if (k_post() > 0.0) {
      const double w = std::sqrt(k_post() / m);
      return std::atan2(v_yield(), w * (d_y - centre)) / w;  // ẋ = −w (d_y − x_c) sin wτ + v₁ cos wτ
    }
    const double lambda = std::sqrt(-k_post() / m);
    return std::atanh(v_yield() / (lambda * (centre - d_y))) / lambda;  // ẋ = λ (d_y − x_c) sinh + v₁ cosh
  }
  double slip() const { return x_max() - d_y; }
  /// Where the elastic swing after unloading is centred: k_el x = (1 − α) k s.
  double swing_centre() const { return (1.0 - alpha) * k * slip() / k_elastic(); }
};

}  // namespace

BOOST_AUTO_TEST_CASE(BilinearOscillatorReleasedWithAVelocityFollowsItsClosedForm) {
  for (bool p_delta : {false, true}) {
    for (double alpha : {0.0, 0.1}) {
      BOOST_TEST_CONTEXT("hardening ratio " << alpha << (p_delta ? ", P-Delta" : "")) {
        const double k_g = p_delta ? kMass_t * kGravity_mps2 / kHeight_m : 0.0;
        const Bilinear sdof{4.0 * kColumn_kN_per_m, k_g, kMass_t, 0.01, alpha, 0.5};
        const double t_peak = sdof.t_yield() + sdof.post_yield_time();
        // A quarter of an elastic period after the peak: the swing's centre, before its far side.
        const double t_end = t_peak + 0.25 * 2.0 * std::numbers::pi / sdof.omega();
        const auto system = system_of({.kind = model::HystereticLaw::Kind::bilinear,
                                       .yield_drift_ratio = {},
                                       .yield_drift_m = {sdof.d_y},
                                       .hardening_ratio = alpha},
                                      t_end, p_delta);
        BOOST_TEST_REQUIRE(system.springs().size() == 8u);  // 4 columns × (x, y)
        solvers::EventOptions options;
        options.initial_state = Eigen::VectorXd::Zero(system.state_size());
        options.initial_state[system.dof()] = sdof.v0;  // u̇ of building A's floor 1
        const solvers::RunResult run = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "cvode-bdf");
        BOOST_TEST(solvers::to_string(run.status) == "completed");
        BOOST_TEST_REQUIRE(run.springs.size() == 8u);
        // Two branch changes for each of the four x-springs: yield and unload.
        BOOST_TEST(run.statistics.yield_events == 8);
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
          BOOST_TEST(std::abs(r.final_drift_m - sdof.swing_centre()) < 1e-8);
          BOOST_TEST(r.hysteretic_kJ == (1.0 - alpha) * kColumn_kN_per_m * sdof.d_y * sdof.slip(), tt::tolerance(1e-8));
        }
        // Energy: the initial kinetic energy is what the springs (and gravity) store and what
        // they dissipated at the end.
        const double initial_kJ = 0.5 * kMass_t * sdof.v0 * sdof.v0;
        BOOST_TEST(run.energy.kinetic_kJ + run.energy.strain_kJ + run.energy.hysteretic_kJ == initial_kJ,
                   tt::tolerance(1e-8));
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(PDeltaBeyondTheHardeningStopsTheRunAsACollapse) {
  // Without hardening, P-Δ makes the post-yield branch m ẍ = k_g x − F₀ unstable: released fast
  // enough (v₁ ≥ λ (x_c − d_y), λ² = k_g/m, x_c = F₀/k_g) the drift never turns and the run ends
  // with status collapse once it passes 10 % of the storey; released slower it stops at x_max.
  const double k_g = kMass_t * kGravity_mps2 / kHeight_m;
  for (double v0 : {1.5, 4.0}) {
    BOOST_TEST_CONTEXT("v0 = " << v0) {
      const Bilinear sdof{4.0 * kColumn_kN_per_m, k_g, kMass_t, 0.01, 0.0, v0};
      const double lambda = std::sqrt(k_g / kMass_t), centre = sdof.plastic_force() / k_g;
      const bool runs_away = sdof.v_yield() >= lambda * (centre - sdof.d_y);
      BOOST_TEST(runs_away == (v0 > 3.0));  // the threshold is 3.06 m/s
      const auto system = system_of({.kind = model::HystereticLaw::Kind::bilinear,
                                     .yield_drift_ratio = {},
                                     .yield_drift_m = {sdof.d_y},
                                     .hardening_ratio = 0.0},
                                    2.0, true);
      solvers::EventOptions options;
      options.initial_state = Eigen::VectorXd::Zero(system.state_size());
      options.initial_state[system.dof()] = v0;
      const solvers::RunResult run = solvers::run_event_driven(system, options, cvode(1e-11, 1e-13), "cvode-bdf");
      BOOST_TEST(solvers::to_string(run.status) == (runs_away ? "collapse" : "completed"));
      if (!runs_away) BOOST_TEST(std::abs(run.springs[0].peak_drift_m - sdof.x_max()) < 1e-9);
      if (runs_away) BOOST_TEST(run.end_s < 2.0);
    }
  }
}

BOOST_AUTO_TEST_CASE(PDeltaSubtractsTheGravityLoadAboveEachStorey) {
  // Two storeys (4.0 m and 3.0 m), floors of 600 t and 400 t: K with P-Δ minus K without is the
  // assembly of G₁ = −(g/4)·diag(1000, 1000, J₁ + J₂) and G₂ = −(g/3)·diag(400, 400, J₂), written
  // out here. And a one-storey building's x period follows ω² = (k − m g/H)/m.
  model::BuildingDefinition b = column_building("A", 0.0, {}).definition;
  b.storeys = 2;
  b.storey_height_m = {4.0, 3.0};
  b.mass_t = {600.0, 400.0};
  b.polar_moment_tm2 = {model::uniform_polar_moment(b.slab, 600.0), model::uniform_polar_moment(b.slab, 400.0)};
  const model::Building elastic = model::make_building(b);
  b.p_delta = true;
  b.g_mps2 = kGravity_mps2;
  const model::Building with_p_delta = model::make_building(b);
  const double j1 = b.polar_moment_tm2[0], j2 = b.polar_moment_tm2[1];
  const Eigen::Matrix3d g1 =
      -(kGravity_mps2 / 4.0) * Eigen::Vector3d(1000.0, 1000.0, j1 + j2).asDiagonal().toDenseMatrix();
  const Eigen::Matrix3d g2 = -(kGravity_mps2 / 3.0) * Eigen::Vector3d(400.0, 400.0, j2).asDiagonal().toDenseMatrix();
  Eigen::MatrixXd expected(6, 6);
  expected << g1 + g2, -g2, -g2, g2;
  BOOST_TEST((with_p_delta.stiffness - elastic.stiffness - expected).cwiseAbs().maxCoeff() <= 1e-9);

  const auto system = system_of({}, 1.0, true);
  const double k_g = kMass_t * kGravity_mps2 / kHeight_m, k = 4.0 * kColumn_kN_per_m;
  bool found_x = false;
  for (const model::Mode& mode : system.building(0).modes) {
    if (std::abs(mode.shape[0]) < 0.5 * mode.shape.norm()) continue;  // the x mode
    found_x = true;
    BOOST_TEST(mode.omega_rad_s * mode.omega_rad_s == (k - k_g) / kMass_t, tt::tolerance(1e-10));
  }
  BOOST_TEST(found_x);
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

// Bouc–Wen with A = 1, β = γ = ½, n = 2: while the drift grows from rest, ż = ḋ (1 − z²)/d_y, so
// z = tanh(d/d_y) along the whole loading (whatever the time history), and the column's force is
// α k d + (1 − α) k d_y tanh(d/d_y). Released with v0 and undamped, the work gives the speed at
// every drift, ½ m v² = ½ m v0² − ½ α k d² − (1 − α) k d_y² ln cosh(d/d_y), so the time to reach a
// drift d is ∫ dd/v (Simpson below, far from the peak where v vanishes). Of the plastic part's work
// (1 − α) k d_y² ln cosh x (x = d/d_y) it stores ½ (1 − α) k d_y² tanh² x: the rest is dissipated.
namespace {

struct BoucWenLoading {
  double k, m, d_y, alpha, v0;
  double speed(double d) const {
    const double x = d / d_y;
    const double work = 0.5 * alpha * k * d * d + (1.0 - alpha) * k * d_y * d_y * std::log(std::cosh(x));
    return std::sqrt(v0 * v0 - 2.0 * work / m);
  }
  /// The time at which the drift reaches d (composite Simpson, 20 000 intervals).
  double time_to(double d) const {
    constexpr int kIntervals = 20000;
    const double h = d / kIntervals;
    double sum = 1.0 / speed(0.0) + 1.0 / speed(d);
    for (int i = 1; i < kIntervals; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) / speed(i * h);
    return sum * h / 3.0;
  }
  /// Per column (of k/4): what the plastic part dissipated by drift d (kJ).
  double dissipated_kJ(double d) const {
    const double x = d / d_y;
    return (1.0 - alpha) * (k / 4.0) * d_y * d_y * (std::log(std::cosh(x)) - 0.5 * std::tanh(x) * std::tanh(x));
  }
};

model::HystereticLaw bouc_wen(double d_y, double alpha, double n) {
  model::HystereticLaw law;
  law.kind = model::HystereticLaw::Kind::bouc_wen;
  law.yield_drift_m = {d_y};
  law.hardening_ratio = alpha;
  law.bouc_wen_n = n;
  return law;
}

solvers::RunResult released(const dynamics::CoupledSystem& system, double v0, double rtol = 1e-11) {
  solvers::EventOptions options;
  options.initial_state = Eigen::VectorXd::Zero(system.state_size());
  options.initial_state[system.dof()] = v0;  // u̇ of building A's floor 1
  return solvers::run_event_driven(system, options, cvode(rtol, rtol / 100), "cvode-bdf");
}

}  // namespace

BOOST_AUTO_TEST_CASE(BoucWenOscillatorLoadsAlongItsClosedFormBackbone) {
  const BoucWenLoading sdof{4.0 * kColumn_kN_per_m, kMass_t, 0.01, 0.1, 0.5};
  const double d_end = 0.02;  // well past d_y, well before the peak (speed there: 0.32 m/s)
  BOOST_TEST_REQUIRE(sdof.speed(d_end) > 0.3);
  const double t_end = sdof.time_to(d_end);
  const auto system = system_of(bouc_wen(sdof.d_y, sdof.alpha, 2.0), t_end);
  BOOST_TEST_REQUIRE(system.state_size() == 2 * system.dof() + 8);  // one z per column and direction
  const solvers::RunResult run = released(system, sdof.v0);
  BOOST_TEST(solvers::to_string(run.status) == "completed");
  BOOST_TEST_REQUIRE(run.springs.size() == 8u);
  for (std::size_t j = 0; j < run.springs.size(); ++j) {
    const solvers::SpringResult& r = run.springs[j];
    if (system.springs()[j].direction == 1) {
      BOOST_TEST(r.yield_count == 0);
      BOOST_TEST(r.hysteretic_kJ == 0.0);
      continue;
    }
    BOOST_TEST(std::abs(r.final_drift_m - d_end) < 1e-9);
    BOOST_TEST(std::abs(r.final_slip_m - (d_end - sdof.d_y * std::tanh(d_end / sdof.d_y))) < 1e-9);
    BOOST_TEST(std::abs(r.first_yield_t_s - sdof.time_to(sdof.d_y)) < 1e-9);  // |d| reaching d_y
    BOOST_TEST(r.hysteretic_kJ == sdof.dissipated_kJ(d_end), tt::tolerance(1e-6));
  }
  const double initial_kJ = 0.5 * kMass_t * sdof.v0 * sdof.v0;
  BOOST_TEST(run.energy.kinetic_kJ + run.energy.strain_kJ + run.energy.hysteretic_kJ == initial_kJ,
             tt::tolerance(1e-8));
}

BOOST_AUTO_TEST_CASE(BoucWenTendsToTheBilinearLawAsNGrows) {
  // The bilinear oscillator of the first test (α = 0.1, no P-Δ) against Bouc–Wen (A = 1,
  // β = γ = ½) of growing n, each run to a quarter period after the bilinear peak: the peak drift
  // and the slip approach the bilinear closed form, each n closer than the one before.
  const Bilinear sdof{4.0 * kColumn_kN_per_m, 0.0, kMass_t, 0.01, 0.1, 0.5};
  const double t_end = sdof.t_yield() + sdof.post_yield_time() + 0.25 * 2.0 * std::numbers::pi / sdof.omega();
  double previous_peak_error = 1.0, previous_slip_error = 1.0;
  for (double n : {2.0, 8.0, 32.0}) {
    BOOST_TEST_CONTEXT("n = " << n) {
      const auto system = system_of(bouc_wen(sdof.d_y, sdof.alpha, n), t_end);
      const solvers::RunResult run = released(system, sdof.v0, 1e-10);
      BOOST_TEST_REQUIRE(solvers::to_string(run.status) == "completed");
      const double peak_error = std::abs(run.springs[0].peak_drift_m - sdof.x_max());
      const double slip_error = std::abs(run.springs[0].final_slip_m - sdof.slip());
      BOOST_TEST_MESSAGE("n = " << n << ": peak drift " << run.springs[0].peak_drift_m << " m (bilinear "
                                << sdof.x_max() << "), slip " << run.springs[0].final_slip_m << " m (bilinear "
                                << sdof.slip() << ")");
      BOOST_TEST(peak_error < previous_peak_error);
      BOOST_TEST(slip_error < previous_slip_error);
      if (n == 32.0) {
        BOOST_TEST(peak_error < 1e-3 * sdof.x_max());  // 4.4e-4 here
        BOOST_TEST(slip_error < 2e-3 * sdof.slip());   // 7.2e-4
      }
      previous_peak_error = peak_error;
      previous_slip_error = slip_error;
      const double initial_kJ = 0.5 * kMass_t * sdof.v0 * sdof.v0;
      BOOST_TEST(run.energy.kinetic_kJ + run.energy.strain_kJ + run.energy.hysteretic_kJ == initial_kJ,
                 tt::tolerance(1e-6));
    }
  }
}

BOOST_AUTO_TEST_CASE(BoucWenJacobianIsTheDerivativeOfTheMotion) {
  // The full Jacobian (CoupledSystem::full_jacobian with the springs' tangent rows) against
  // central differences of rhs, at a state away from the kinks of sgn(ḋ z) (every drift rate and
  // z nonzero): the z columns (∂q̈/∂z), the z rows (∂ż/∂q̇, ∂ż/∂z) and the rest.
  const auto system = system_of(bouc_wen(0.01, 0.1, 3.0), 1.0);
  const int n = system.dof(), size = system.state_size();
  BOOST_TEST_REQUIRE(size == 2 * n + 8);
  const dynamics::SpringStates states(system.springs().size());
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size);
  y.segment(0, 3) << 0.008, -0.004, 3e-4;  // building A's floor: u, v (m), φ (rad)
  y.segment(n, 3) << 0.3, 0.2, -0.01;      // and its rates
  for (int k = 0; k < 8; ++k) y[2 * n + k] = (k % 2 == 0 ? 0.6 : -0.3) + 0.01 * k;
  Eigen::SparseMatrix<double> rows;
  system.constrained_acceleration_jacobian(y, {}, rows, &states);
  Eigen::MatrixXd analytic(size, size);
  system.full_jacobian(y, rows, analytic);
  Eigen::MatrixXd numeric(size, size);
  Eigen::VectorXd plus(size), minus(size);
  for (int j = 0; j < size; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(y[j]));
    Eigen::VectorXd up = y, down = y;
    up[j] += h;
    down[j] -= h;
    system.rhs(0.0, up, plus, &states);
    system.rhs(0.0, down, minus, &states);
    numeric.col(j) = (plus - minus) / (2.0 * h);
  }
  const double scale = analytic.cwiseAbs().maxCoeff();
  BOOST_TEST((analytic - numeric).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  BOOST_TEST(analytic.block(n, 2 * n, n, 8).cwiseAbs().maxCoeff() > 0.0);  // the z columns are there
}
