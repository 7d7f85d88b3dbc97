#include "pounding/solvers/gap_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "pounding/model/modal_basis.hpp"

namespace pounding::solvers {

GapClearance::GapClearance(const dynamics::CoupledSystem& system) : system_(system) {
  const std::vector<contact::Candidate>& candidates = system.candidates();
  const auto count = static_cast<std::size_t>(system.building_count());
  buildings_.resize(count);
  for (auto* scratch :
       {&amplitude_, &eta_, &eta_rate_, &rate_bound_, &rate_growth_, &displacement_bound_, &displacement_growth_})
    scratch->resize(count);
  for (int b = 0; b < system.building_count(); ++b) {
    BuildingModes& modes = buildings_[b];
    const int n = system.building(b).dof();
    modes.offset = system.floor_index(b, 1);
    const model::ModalBasis& basis = system.modal_basis(b);
    modes.projection = basis.projection;
    modes.omega_rad_s = basis.omega_rad_s;
    for (Eigen::Index k = 0; k < basis.omega_rad_s.size(); ++k) {
      const double zeta = basis.damping_ratio[k];
      if (zeta >= 1.0) continue;
      const double period_s = 2.0 * std::numbers::pi / (basis.omega_rad_s[k] * std::sqrt(1.0 - zeta * zeta));
      shortest_damped_period_s_ = std::min(shortest_damped_period_s_, period_s);
    }
    modes.participation = basis.participation.cwiseAbs();  // a column per ground-motion component
    for (const contact::Candidate& c : candidates) {
      if (c.pair[0] == b || c.pair[1] == b) modes.floors.push_back(c.floor_of(b));
    }
    std::sort(modes.floors.begin(), modes.floors.end());
    modes.floors.erase(std::unique(modes.floors.begin(), modes.floors.end()), modes.floors.end());
    const auto rows = static_cast<Eigen::Index>(3 * modes.floors.size());
    modes.rate_rows.resize(rows, n);
    for (std::size_t f = 0; f < modes.floors.size(); ++f) {
      const int first = 3 * (modes.floors[f] - 1);
      modes.rate_rows.middleRows(static_cast<Eigen::Index>(3 * f), 3) = basis.shapes.middleRows(first, 3).cwiseAbs();
    }
    modes.displacement_rows = modes.rate_rows * basis.omega_rad_s.cwiseInverse().asDiagonal();
    for (Eigen::Index c = 0; c < modes.participation.cols(); ++c) {
      modes.rate_growth.push_back(modes.rate_rows * modes.participation.col(c));
      modes.displacement_growth.push_back(modes.displacement_rows * modes.participation.col(c));
    }
    amplitude_[b].resize(n);
    eta_[b].resize(n);
    eta_rate_[b].resize(n);
    for (auto* bound : {&rate_bound_, &rate_growth_, &displacement_bound_, &displacement_growth_})
      (*bound)[b].resize(rows);
  }
  for (const contact::Candidate& c : candidates) {
    const auto row_of = [&](int b) {
      const std::vector<int>& floors = buildings_[b].floors;
      return 3 * static_cast<int>(std::lower_bound(floors.begin(), floors.end(), c.floor_of(b)) - floors.begin());
    };
    Pair pair;
    pair.striking = c.striking_building;
    pair.struck = c.struck_building;
    pair.striking_row = row_of(pair.striking);
    pair.struck_row = row_of(pair.struck);
    pair.arm_striking_m = (c.vertex_rest - system.building(c.striking_building).definition.centre_of_mass).norm();
    pair.arm_struck_m = (c.vertex_rest - system.building(c.struck_building).definition.centre_of_mass).norm();
    pairs_.push_back(pair);
  }
}

double GapClearance::open_time_s(const Eigen::Ref<const Eigen::VectorXd>& y, const std::vector<bool>& watched,
                                 double clearance_m, double horizon_s, const Eigen::Vector2d& peak_accel_mps2) const {
  const int dof = system_.dof();
  // Bounds on |q̇| and |q| of the contact floors over a window τ, affine in τ: the header's
  // Â = A(t) + |Γ| a τ through the rows, as rate_0 + rate_1 τ and shift_0 + shift_1 τ.
  for (std::size_t b = 0; b < buildings_.size(); ++b) {
    const BuildingModes& modes = buildings_[b];
    const auto n = modes.omega_rad_s.size();
    eta_[b].noalias() = modes.projection * y.segment(modes.offset, n);
    eta_rate_[b].noalias() = modes.projection * y.segment(dof + modes.offset, n);
    amplitude_[b] = (eta_rate_[b].cwiseAbs2() + eta_[b].cwiseProduct(modes.omega_rad_s).cwiseAbs2()).cwiseSqrt();
    rate_bound_[b].noalias() = modes.rate_rows * amplitude_[b];
    // Σ_c |a_c| rows·|Γ_c|: each component grows the amplitudes by at most its own peak.
    rate_growth_[b] = peak_accel_mps2[0] * modes.rate_growth[0];
    displacement_bound_[b].noalias() = modes.displacement_rows * amplitude_[b];
    displacement_growth_[b] = peak_accel_mps2[0] * modes.displacement_growth[0];
    for (std::size_t c = 1; c < modes.rate_growth.size(); ++c) {
      rate_growth_[b] += peak_accel_mps2[static_cast<Eigen::Index>(c)] * modes.rate_growth[c];
      displacement_growth_[b] += peak_accel_mps2[static_cast<Eigen::Index>(c)] * modes.displacement_growth[c];
    }
  }
  double open_s = horizon_s;
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    if (!watched[i]) continue;
    const double gap_m = system_.gap(y, i).gap_m;
    if (!(gap_m > clearance_m)) return 0.0;
    const Pair& pair = pairs_[i];
    const int a = pair.striking, b = pair.struck, row_a = pair.striking_row, row_b = pair.struck_row;
    // The bound L(τ) on |ġ| over a window τ (the header's), nondecreasing in τ.
    auto rate_bound_mps = [&](double tau_s) {
      const Eigen::Vector3d rate_a = rate_bound_[a].segment<3>(row_a) + tau_s * rate_growth_[a].segment<3>(row_a);
      const Eigen::Vector3d rate_b = rate_bound_[b].segment<3>(row_b) + tau_s * rate_growth_[b].segment<3>(row_b);
      const Eigen::Vector3d shift_a =
          displacement_bound_[a].segment<3>(row_a) + tau_s * displacement_growth_[a].segment<3>(row_a);
      const Eigen::Vector3d shift_b =
          displacement_bound_[b].segment<3>(row_b) + tau_s * displacement_growth_[b].segment<3>(row_b);
      // |P − C_B| ≤ r_AB + |(u, v)_A − (u, v)_B| + r_A |φ_A|.
      const double arm_struck_m = pair.arm_struck_m + std::hypot(shift_a[0] + shift_b[0], shift_a[1] + shift_b[1]) +
                                  pair.arm_striking_m * shift_a[2];
      return std::hypot(rate_a[0], rate_a[1]) + pair.arm_striking_m * rate_a[2] + std::hypot(rate_b[0], rate_b[1]) +
             arm_struck_m * rate_b[2];
    };
    // The gap stays above the clearance over any τ with τ L(τ) ≤ g − clearance; τ L(τ) grows
    // with τ, so the longest such τ below the current window is bracketed and bisected, keeping
    // the side where it holds.
    const double room_m = gap_m - clearance_m;
    if (open_s * rate_bound_mps(open_s) <= room_m) continue;
    double low_s = 0.0, high_s = open_s;
    for (int k = 0; k < 24; ++k) {
      const double mid_s = 0.5 * (low_s + high_s);
      (mid_s * rate_bound_mps(mid_s) <= room_m ? low_s : high_s) = mid_s;
    }
    open_s = low_s;
  }
  return open_s;
}

}  // namespace pounding::solvers
