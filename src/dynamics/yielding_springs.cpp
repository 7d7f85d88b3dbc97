#include "pounding/dynamics/yielding_springs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace pounding::dynamics {

namespace {

std::optional<BoucWenShape> bouc_wen_shape(const model::HystereticLaw& law) {
  if (!law.is_smooth()) return std::nullopt;
  return BoucWenShape{.a = law.bouc_wen_a, .beta = law.bouc_wen_beta, .gamma = law.bouc_wen_gamma, .n = law.bouc_wen_n};
}

std::optional<ImkParameters> imk_parameters(const model::HystereticLaw& law, int storey, double stiffness_kN_per_m,
                                            double yield_drift_m) {
  if (!law.degrades()) return std::nullopt;
  const auto side = [&](bool positive) {  // F_y = k d_y on both sides
    const model::ImkSideKeys given = model::imk_side(law, storey, positive);
    return ImkSide{.yield_force_kN = stiffness_kN_per_m * yield_drift_m,
                   .plastic_drift_m = given.plastic_drift_m,
                   .post_cap_drift_m = given.post_cap_drift_m,
                   .ultimate_drift_m = given.ultimate_drift_m,
                   .cap_ratio = given.cap_ratio,
                   .residual_ratio = given.residual_ratio,
                   .deterioration_rate = given.rate};
  };
  return ImkParameters{.stiffness_kN_per_m = stiffness_kN_per_m,
                       .positive = side(true),
                       .negative = side(false),
                       .lamda_m = {law.imk_lamda_s_m, law.imk_lamda_c_m, law.imk_lamda_a_m, law.imk_lamda_k_m},
                       .exponent = {law.imk_c_s, law.imk_c_c, law.imk_c_a, law.imk_c_k},
                       .pinching = law.kind == model::HystereticLaw::Kind::imk_pinching
                                       ? std::optional<ImkPinching>({*law.imk_kappa_f, *law.imk_kappa_d})
                                       : std::nullopt};
}

/// Writes d = t·(q_storey − q_storey−1) into `spring` (its indices and coefficients), t the row
/// over (u, v, φ) of its direction; the ground's floor 0 does not move relative to the base.
void set_drift_row(YieldingSpring& spring, const std::array<double, 3>& row, int offset) {
  for (int floor : {spring.storey, spring.storey - 1}) {
    if (floor == 0) continue;
    const double sign = floor == spring.storey ? 1.0 : -1.0;
    for (int i = 0; i < 3; ++i) {
      if (row[i] == 0.0) continue;
      spring.indices.push_back(offset + 3 * (floor - 1) + i);
      spring.coefficients.push_back(sign * row[i]);
    }
  }
}

/// A spring of building b's storey along `direction` (0: x, 1: y) of stiffness k and its law's
/// parameters, named `name`, its drift row still to set.
YieldingSpring make_spring(const model::Building& building, int b, int storey, int direction, std::string name,
                           double stiffness_kN_per_m, double yield_drift_m) {
  const model::BuildingDefinition& d = building.definition;
  return YieldingSpring{.building = b,
                        .storey = storey,
                        .direction = direction,
                        .column = std::move(name),
                        .column_index = 0,
                        .stiffness_kN_per_m = stiffness_kN_per_m,
                        .hardening_ratio = d.hysteresis.degrades() ? 0.0 : d.hysteresis.hardening_ratio,
                        .yield_drift_m = yield_drift_m,
                        .storey_height_m = d.storey_height_m[storey - 1],
                        .indices = {},
                        .coefficients = {},
                        .bouc_wen = bouc_wen_shape(d.hysteresis),
                        .z_index = -1,
                        .imk = imk_parameters(d.hysteresis, storey, stiffness_kN_per_m, yield_drift_m),
                        .shear_capacity_kN = 0.0,
                        .loses_stiffness = false};
}

/// The springs of one building (empty if it stays elastic): a column's in x and in y, or, for a
/// storey given as a matrix, its storey springs (model::storey_springs).
void add_building_springs(const model::Building& building, int b, int offset, std::vector<YieldingSpring>& springs) {
  const model::BuildingDefinition& d = building.definition;
  if (!d.hysteresis.yields()) return;
  for (int storey = 1; storey <= d.storeys; ++storey) {
    if (!d.uses_columns()) {
      const model::StoreySprings storey_springs = model::storey_springs(d, storey);
      for (int direction = 0; direction < 2; ++direction) {
        YieldingSpring spring = make_spring(building, b, storey, direction, fmt::format("storey_stiffness[{}]", storey),
                                            storey_springs.stiffness_kN_per_m[direction],
                                            model::column_yield_drift_m(building, storey, direction));
        set_drift_row(spring, storey_springs.rows[direction], offset);
        springs.push_back(std::move(spring));
      }
      continue;
    }
    const double height_m = d.storey_height_m[storey - 1];
    for (std::size_t c = 0; c < d.columns.size(); ++c) {
      const Eigen::Vector2d k = model::column_stiffness(d.columns[c], d.E_kPa, height_m, building.frame_factor);
      for (int direction = 0; direction < 2; ++direction) {
        YieldingSpring spring = make_spring(building, b, storey, direction, model::column_key(d, c), k[direction],
                                            model::column_yield_drift_m(building, storey, c, direction));
        spring.column_index = c;
        spring.shear_capacity_kN = model::column_shear_capacity_kN(building, storey, c, direction);
        spring.loses_stiffness = d.shear_failure_loses_stiffness();
        set_drift_row(spring, model::column_drift_row(d, c, direction), offset);
        springs.push_back(std::move(spring));
      }
    }
  }
}

double sign_of(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

/// The factor of ż = (ḋ/d_y) Φ: Φ = A − |z|ⁿ (β sgn(ḋ z) + γ).
double bouc_wen_factor(const BoucWenShape& shape, double z, double drift_rate) {
  return shape.a - std::pow(std::abs(z), shape.n) * (shape.beta * sign_of(drift_rate * z) + shape.gamma);
}

}  // namespace

YieldingSprings::YieldingSprings(const std::vector<model::Building>& buildings, const std::vector<int>& offsets)
    : dof_(offsets.back() + buildings.back().dof()) {
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    const std::size_t first = springs_.size();
    add_building_springs(buildings[b], static_cast<int>(b), offsets[b], springs_);
    first_spring_.push_back(springs_.size() > first ? std::optional<std::size_t>(first) : std::nullopt);
    column_count_.push_back(buildings[b].definition.columns.size());
  }
  for (YieldingSpring& spring : springs_) {
    if (spring.bouc_wen) spring.z_index = 2 * dof_ + smooth_count_++;
  }
}

std::optional<std::size_t> YieldingSprings::index_of(int building, int storey, std::size_t column,
                                                     int direction) const {
  const std::size_t b = static_cast<std::size_t>(building);
  if (b >= first_spring_.size() || !first_spring_[b]) return std::nullopt;
  const std::size_t columns = std::max<std::size_t>(column_count_[b], 1);  // a storey matrix: its 2 springs
  if (column >= columns) return std::nullopt;
  return *first_spring_[b] + 2 * (static_cast<std::size_t>(storey - 1) * columns + column) +
         static_cast<std::size_t>(direction);
}

double YieldingSprings::drift(const Eigen::Ref<const Eigen::VectorXd>& q, std::size_t j) const {
  const YieldingSpring& s = springs_[j];
  double d = 0.0;
  for (std::size_t i = 0; i < s.indices.size(); ++i) d += s.coefficients[i] * q[s.indices[i]];
  return d;
}

double YieldingSprings::slip(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states,
                             std::size_t j) const {
  const YieldingSpring& spring = springs_[j];
  if (spring.bouc_wen) return drift(y.head(dof_), j) - spring.yield_drift_m * y[spring.z_index];
  switch (states[j].branch) {
    case SpringBranch::elastic: return states[j].slip_m;
    case SpringBranch::yielding_up: return drift(y.head(dof_), j) - spring.yield_drift_m;
    case SpringBranch::yielding_down: return drift(y.head(dof_), j) + spring.yield_drift_m;
    case SpringBranch::failed: return drift(y.head(dof_), j) / (1.0 - spring.hardening_ratio);
    case SpringBranch::line: {  // α = 0: s = d − F/k
      const double d = drift(y.head(dof_), j);
      return d - states[j].line.force_at(d) / spring.stiffness_kN_per_m;
    }
  }
  return 0.0;
}

double YieldingSprings::force_kN(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states,
                                 std::size_t j) const {
  return springs_[j].force_kN(drift(y.head(dof_), j), slip(y, states, j));
}

void YieldingSprings::add_slip_force(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states,
                                     Eigen::Ref<Eigen::VectorXd> force) const {
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const double s = slip(y, states, j);
    if (s == 0.0) continue;
    const YieldingSpring& spring = springs_[j];
    const double magnitude = spring.plastic_stiffness() * s;
    for (std::size_t i = 0; i < spring.indices.size(); ++i)
      force[spring.indices[i]] += magnitude * spring.coefficients[i];
  }
}

void YieldingSprings::hysteretic_rates(const Eigen::Ref<const Eigen::VectorXd>& y,
                                       Eigen::Ref<Eigen::VectorXd> z_dot) const {
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const YieldingSpring& spring = springs_[j];
    if (!spring.bouc_wen) continue;
    const double rate_mps = drift(y.segment(dof_, dof_), j);
    z_dot[spring.z_index - 2 * dof_] =
        rate_mps / spring.yield_drift_m * bouc_wen_factor(*spring.bouc_wen, y[spring.z_index], rate_mps);
  }
}

void YieldingSprings::add_tangent_rows(const SpringStates& states, const Eigen::VectorXd& inverse_mass,
                                       Eigen::SparseMatrix<double>& rows) const {
  std::vector<Eigen::Triplet<double>> terms;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const YieldingSpring& spring = springs_[j];
    if (!spring.bouc_wen && states[j].branch == SpringBranch::elastic) continue;
    // s_j = d_j ∓ d_y (or d_j − d_y z_j): the slip force (1 − α) k t tᵀ q adds to q̈ through M⁻¹;
    // failed, s_j = d_j/(1 − α): k t tᵀ q, the whole spring.
    // On a degrading spring's line, F = F_0 + K_b (d − d_0): the slip force k d − F, slope k − K_b.
    const double slope_kN_per_m = states[j].branch == SpringBranch::failed ? spring.stiffness_kN_per_m
                                  : states[j].branch == SpringBranch::line
                                      ? spring.stiffness_kN_per_m - states[j].line.slope_kN_per_m
                                      : spring.plastic_stiffness();
    if (slope_kN_per_m == 0.0) continue;
    for (std::size_t a = 0; a < spring.indices.size(); ++a) {
      for (std::size_t c = 0; c < spring.indices.size(); ++c) {
        terms.emplace_back(
            spring.indices[a], spring.indices[c],
            inverse_mass[spring.indices[a]] * slope_kN_per_m * spring.coefficients[a] * spring.coefficients[c]);
      }
    }
  }
  if (terms.empty()) return;
  Eigen::SparseMatrix<double> tangent(rows.rows(), rows.cols());
  tangent.setFromTriplets(terms.begin(), terms.end());
  rows += tangent;
}

void YieldingSprings::smooth_jacobian(const Eigen::Ref<const Eigen::VectorXd>& y, const Eigen::VectorXd& inverse_mass,
                                      Eigen::SparseMatrix<double>& accel_by_z,
                                      Eigen::SparseMatrix<double>& z_rate_by_velocity,
                                      Eigen::VectorXd& z_rate_by_z) const {
  std::vector<Eigen::Triplet<double>> accel_terms, rate_terms;
  z_rate_by_z.resize(smooth_count_);
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const YieldingSpring& spring = springs_[j];
    if (!spring.bouc_wen) continue;
    const BoucWenShape& shape = *spring.bouc_wen;
    const int k = spring.z_index - 2 * dof_;
    const double z = y[spring.z_index], rate_mps = drift(y.segment(dof_, dof_), j), d_y = spring.yield_drift_m;
    const double factor_slope = -shape.n * std::pow(std::abs(z), shape.n - 1.0) * sign_of(z) *
                                (shape.beta * sign_of(rate_mps * z) + shape.gamma);
    z_rate_by_z[k] = rate_mps / d_y * factor_slope;
    const double factor = bouc_wen_factor(shape, z, rate_mps);
    for (std::size_t i = 0; i < spring.indices.size(); ++i) {
      const int q = spring.indices[i];
      rate_terms.emplace_back(k, q, factor / d_y * spring.coefficients[i]);
      accel_terms.emplace_back(q, k, -inverse_mass[q] * spring.plastic_stiffness() * d_y * spring.coefficients[i]);
    }
  }
  accel_by_z.resize(dof_, smooth_count_);
  accel_by_z.setFromTriplets(accel_terms.begin(), accel_terms.end());
  z_rate_by_velocity.resize(smooth_count_, dof_);
  z_rate_by_velocity.setFromTriplets(rate_terms.begin(), rate_terms.end());
}

double YieldingSprings::witness(const Eigen::Ref<const Eigen::VectorXd>& y, const SpringStates& states,
                                std::size_t j) const {
  if (springs_[j].bouc_wen) return 1.0;
  switch (states[j].branch) {
    case SpringBranch::elastic: return springs_[j].yield_drift_m - std::abs(drift(y.head(dof_), j) - states[j].slip_m);
    case SpringBranch::yielding_up: return drift(y.segment(dof_, dof_), j);
    case SpringBranch::yielding_down: return -drift(y.segment(dof_, dof_), j);
    case SpringBranch::failed: return 1.0;
    case SpringBranch::line: {
      const LineBranch& line = states[j].line;
      const double d = drift(y.head(dof_), j);
      const double end_m = std::min(d - line.lower_m, line.upper_m - d);
      if (line.reversal_sign == 0) return std::isfinite(end_m) ? end_m : 1.0;
      return std::min(end_m, line.reversal_sign * drift(y.segment(dof_, dof_), j));
    }
  }
  return 1.0;
}

double YieldingSprings::stored_energy_change(const Eigen::Ref<const Eigen::VectorXd>& y,
                                             const SpringStates& states) const {
  double change_kJ = 0.0;
  for (std::size_t j = 0; j < springs_.size(); ++j) {
    const YieldingSpring& spring = springs_[j];
    if (spring.bouc_wen) {
      // ½ k d² (in ½ qᵀ K q) becomes ½ α k d² + ½ (1 − α) k d_y² z²/A.
      const double d = drift(y.head(dof_), j), z = y[spring.z_index], d_y = spring.yield_drift_m;
      change_kJ += 0.5 * spring.plastic_stiffness() * (d_y * d_y * z * z / spring.bouc_wen->a - d * d);
      continue;
    }
    const double d = drift(y.head(dof_), j);
    if (states[j].branch == SpringBranch::line) {  // ½ k d² becomes ½F²/K_u
      const double force_kN = states[j].line.force_at(d);
      change_kJ +=
          0.5 * (force_kN * force_kN / states[j].line.unloading_stiffness_kN_per_m - spring.stiffness_kN_per_m * d * d);
      continue;
    }
    if (states[j].branch == SpringBranch::failed) {  // its ½ k d² leaves ½ qᵀ K q: it stores nothing
      change_kJ -= 0.5 * spring.stiffness_kN_per_m * d * d;
      continue;
    }
    const double s = slip(y, states, j);
    change_kJ += spring.plastic_stiffness() * s * (0.5 * s - d);
  }
  return change_kJ;
}

double YieldingSprings::dissipation_power(const Eigen::Ref<const Eigen::VectorXd>& y, std::size_t j) const {
  const YieldingSpring& spring = springs_[j];
  if (!spring.bouc_wen) return 0.0;
  const BoucWenShape& shape = *spring.bouc_wen;
  const double z = y[spring.z_index], rate_mps = drift(y.segment(dof_, dof_), j);
  // ḋ z |z|ⁿ (β sgn(ḋ z) + γ) = ḋ z (A − Φ): the part of the work ż does not store.
  return spring.plastic_stiffness() * spring.yield_drift_m * rate_mps * z *
         (shape.a - bouc_wen_factor(shape, z, rate_mps)) / shape.a;
}

}  // namespace pounding::dynamics
