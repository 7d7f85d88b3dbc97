#pragma once
// Two one-storey buildings with 10 × 10 m slabs side by side along x, for solver tests.
// Storey stiffness given directly as diag(k_x, 2 k_x, 3 k_x J/m) so the x, y and torsion modes
// are uncoupled and come in that order (x is mode 1, damped exactly at the given ratio).

#include <cmath>
#include <memory>
#include <numbers>

#include "pounding/contact/candidates.hpp"
#include "pounding/dynamics/coupled_system.hpp"
#include "pounding/solvers/cvode_integrator.hpp"
#include "pounding/solvers/event_driven.hpp"
#include "state_space_exact.hpp"
#include "pounding/solvers/modal_exact_integrator.hpp"

namespace pounding::testing {

struct SlabSpec {
  double mass_t = 100.0;
  double period_x_s = 0.5;
  double damping_ratio = 0.0;
};

inline model::Building slab_building(const char* name, const model::Polygon& slab, const SlabSpec& spec) {
  model::BuildingDefinition b;
  b.name = name;
  b.storeys = 1;
  b.storey_height_m = {3.0};
  b.slab = slab;
  b.centre_of_mass = slab.centroid();
  b.mass_t = {spec.mass_t};
  b.polar_moment_tm2 = {model::uniform_polar_moment(slab, spec.mass_t)};
  const double omega = 2.0 * std::numbers::pi / spec.period_x_s;
  const double kx = spec.mass_t * omega * omega;
  b.storey_stiffness = {Eigen::Vector3d(kx, 2 * kx, 3 * kx * b.polar_moment_tm2[0] / spec.mass_t).asDiagonal()};
  b.damping = {spec.damping_ratio, {1, 3}};
  return model::make_building(b);
}

inline model::Polygon box(double x0, double y0, double x1, double y1) {
  return model::Polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

/// A 10 × 10 diamond whose left vertex is at (x_left, 5): it meets building 1's face at one point,
/// head-on, in line with both centres of mass (the only candidate is that vertex against that face).
inline model::Polygon diamond(double x_left) {
  return model::Polygon({{x_left, 5}, {x_left + 5, 0}, {x_left + 10, 5}, {x_left + 5, 10}});
}

/// Building 1 on [−10, 0] × [0, 10]; building 2's slab as given; excitation a_g(t) constant
/// `ground_accel_mps2` along x over [0, duration].
inline dynamics::CoupledSystem two_slabs(const SlabSpec& left, const model::Polygon& right_slab, const SlabSpec& right,
                                         double gap_m, excitation::GroundMotion motion) {
  const model::Polygon left_slab = box(-10, 0, 0, 10);
  std::vector<model::Building> buildings{slab_building("A", left_slab, left), slab_building("B", right_slab, right)};
  contact::PairGeometry geometry{{left_slab, right_slab}, {left_slab.centroid(), right_slab.centroid()}};
  const std::vector<contact::Level> levels{{.index = 1, .floors = {1, 1}, .elevation_m = 3.0}};
  auto candidates = contact::find_candidates(geometry, levels, {.margin_m = 1.0, .gap_m = gap_m});
  return dynamics::CoupledSystem(std::move(buildings), std::move(motion), levels, std::move(candidates));
}

inline dynamics::CoupledSystem two_slabs(const SlabSpec& left, const model::Polygon& right_slab, const SlabSpec& right,
                                         double gap_m, double duration_s, double ground_accel_mps2 = 0.0) {
  return two_slabs(left, right_slab, right, gap_m,
                   excitation::GroundMotion({0.0, duration_s}, {ground_accel_mps2, ground_accel_mps2}, 0.0));
}

inline solvers::IntegratorFactory exact(solvers::ExactSettings settings = {}) {
  return [=](solvers::OdeFunctions& functions, double t0,
             const Eigen::VectorXd& y0) -> std::unique_ptr<solvers::Integrator> {
    return std::make_unique<testing::StateSpaceExactIntegrator>(functions, t0, y0, settings);
  };
}

/// The exact path in modal form on `system` (must outlive the factory's integrators).
inline solvers::IntegratorFactory modal_exact(const dynamics::CoupledSystem& system,
                                              solvers::ExactSettings settings = {}) {
  return [&system, settings](solvers::OdeFunctions& functions, double t0,
                             const Eigen::VectorXd& y0) -> std::unique_ptr<solvers::Integrator> {
    return std::make_unique<solvers::ModalExactIntegrator>(functions, system, t0, y0, settings);
  };
}

inline solvers::IntegratorFactory cvode(double rtol, double atol,
                                        solvers::CvodeMethod method = solvers::CvodeMethod::bdf) {
  return [=](solvers::OdeFunctions& functions, double t0, const Eigen::VectorXd& y0) {
    return std::make_unique<solvers::CvodeIntegrator>(functions, solvers::CvodeSettings{method, rtol, atol}, t0, y0);
  };
}

/// Initial state with building 1's slab moving along x at `velocity_mps`.
inline Eigen::VectorXd pushed(const dynamics::CoupledSystem& system, double velocity_mps) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(system.state_size());
  y[system.dof() + system.floor_index(0, 1)] = velocity_mps;
  return y;
}

}  // namespace pounding::testing
