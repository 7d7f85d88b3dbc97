#include "pounding/solvers/gap_mode_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "pounding/model/mode.hpp"

namespace pounding::solvers {

namespace {

/// The gap rows of every candidate at rest (those of every small motion): per candidate, each
/// floor its gap reads as (building, floor index in q_b, row over that floor's (u, v, φ)).
struct RestBlock {
  int building = 0;
  int first = 0;
  Eigen::RowVector3d row;
};
using RestRows = std::vector<std::vector<RestBlock>>;

RestRows rest_rows(const dynamics::CoupledSystem& system) {
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(system.state_size());
  RestRows result;
  for (std::size_t i = 0; i < system.candidates().size(); ++i) {
    std::vector<RestBlock>& blocks = result.emplace_back();
    for (const auto& block : system.row_blocks(system.candidates()[i], system.gap(rest, i)))
      blocks.push_back({block.building, 3 * (block.floor - 1), block.row});
  }
  return result;
}

/// The largest |∂g/∂η| of mode `shape` of building b over the candidates (m per unit η).
double gap_per_unit(const RestRows& rest, int b, const Eigen::VectorXd& shape) {
  double largest = 0.0;
  for (const std::vector<RestBlock>& blocks : rest) {
    double per_unit = 0.0;
    for (const RestBlock& block : blocks) {
      if (block.building == b) per_unit += block.row.dot(shape.segment<3>(block.first));
    }
    largest = std::max(largest, std::abs(per_unit));
  }
  return largest;
}

/// The largest |∂d/∂η| of mode `shape` of building b (whose first index in q is `offset`) over
/// the yielding springs' drifts d (m per unit η): a yield or an unloading is a root as a contact is.
double drift_per_unit(const dynamics::YieldingSprings& springs, int b, int offset, const Eigen::VectorXd& shape) {
  double largest = 0.0;
  for (const dynamics::YieldingSpring& spring : springs.all()) {
    if (spring.building != b) continue;
    double drift = 0.0;
    for (std::size_t i = 0; i < spring.indices.size(); ++i)
      drift += spring.coefficients[i] * shape[spring.indices[i] - offset];
    largest = std::max(largest, std::abs(drift));
  }
  return largest;
}

}  // namespace

GapModeBound::GapModeBound(const dynamics::CoupledSystem& system, double resolution_m, double steps_per_period,
                           double modes_cutoff_hz)
    : dof_(system.dof()), resolution_m_(resolution_m), steps_per_period_(steps_per_period) {
  const excitation::GroundMotion& motion = system.ground_motion();
  const RestRows rest = rest_rows(system);
  double longest_period_s = 0.0;
  for (int b = 0; b < system.building_count(); ++b) {
    const model::Building& building = system.building(b);
    const int offset = system.floor_index(b, 1);
    const Eigen::VectorXd& mass = building.mass_diagonal;
    for (const model::Mode& mode : building.modes) {
      longest_period_s = std::max(longest_period_s, mode.period_s);
      const double omega = mode.omega_rad_s;
      // A mode left out follows a_g quasi-statically, linear within a step: it cannot hide a minimum.
      if (modes_cutoff_hz > 0.0 && omega / (2.0 * std::numbers::pi) >= modes_cutoff_hz) continue;
      const double zeta = mode.shape.dot(building.damping * mode.shape) / (2.0 * omega);
      if (zeta >= 1.0) continue;  // overdamped: its free response has at most one extremum
      OscillatingMode m;
      m.offset = offset;
      m.omega_rad_s = omega;
      m.damped_period_s = 2.0 * std::numbers::pi / (omega * std::sqrt(1.0 - zeta * zeta));
      longest_period_s = std::max(longest_period_s, m.damped_period_s);
      m.mass_shape = mass.cwiseProduct(mode.shape);
      m.gap_per_unit_m =
          std::max(gap_per_unit(rest, b, mode.shape), drift_per_unit(system.springs(), b, offset, mode.shape));
      // Σ_c |Γ_c| peak_c: each component drives the mode by at most its own peak.
      double load_mps2 =
          std::abs(m.mass_shape.dot(system.influence().segment(offset, building.dof()))) * motion.peak_mps2();
      for (int c = 1; c < motion.component_count(); ++c) {
        load_mps2 +=
            std::abs(m.mass_shape.dot(system.influence(c).segment(offset, building.dof()))) * motion.peak_mps2(c);
      }
      m.forced_amplitude = 2.0 * load_mps2 / (omega * omega);
      if (m.gap_per_unit_m > 0.0) modes_.push_back(std::move(m));
    }
  }
  longest_period_s_ = longest_period_s;
  std::sort(modes_.begin(), modes_.end(),
            [](const OscillatingMode& a, const OscillatingMode& b) { return a.damped_period_s < b.damped_period_s; });
  // A mode whose forced amplitude alone moves a gap by more than the resolution sets the bound
  // in every state: max_step_s never looks past the first such mode, so the rest need not be kept.
  const auto always = std::find_if(modes_.begin(), modes_.end(), [&](const OscillatingMode& m) {
    return m.gap_per_unit_m * m.forced_amplitude > resolution_m_;
  });
  if (always != modes_.end()) modes_.erase(always + 1, modes_.end());
}

double GapModeBound::max_step_s(const Eigen::Ref<const Eigen::VectorXd>& y) const {
  for (const OscillatingMode& m : modes_) {
    const Eigen::Index n = m.mass_shape.size();
    const double eta = m.mass_shape.dot(y.segment(m.offset, n));
    const double eta_rate = m.mass_shape.dot(y.segment(dof_ + m.offset, n));
    const double amplitude = std::hypot(eta, eta_rate / m.omega_rad_s) + m.forced_amplitude;
    if (m.gap_per_unit_m * amplitude > resolution_m_) {
      governing_period_s_ = m.damped_period_s;
      return std::min(m.damped_period_s, longest_period_s_) / steps_per_period_;
    }
  }
  governing_period_s_ = 0.0;
  return longest_period_s_ / steps_per_period_;
}

}  // namespace pounding::solvers
