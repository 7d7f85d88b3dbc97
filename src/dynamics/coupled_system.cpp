#include "pounding/dynamics/coupled_system.hpp"

#include "pounding/contact/corners.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <optional>

namespace pounding::dynamics {

CoupledSystem::CoupledSystem(std::vector<model::Building> buildings, excitation::GroundMotion ground_motion,
                             std::vector<contact::Level> levels, std::vector<contact::Candidate> candidates)
    : buildings_(std::move(buildings)),
      ground_motion_(std::move(ground_motion)),
      levels_(std::move(levels)),
      candidates_(std::move(candidates)) {
  for (const model::Building& building : buildings_) {
    offset_.push_back(dof_);
    dof_ += building.dof();
  }
  mass_.resize(dof_);
  stiffness_ = MatrixXd::Zero(dof_, dof_);
  damping_ = MatrixXd::Zero(dof_, dof_);
  for (std::size_t b = 0; b < buildings_.size(); ++b) {
    const int size = buildings_[b].dof();
    mass_.segment(offset_[b], size) = buildings_[b].mass_diagonal;
    stiffness_.block(offset_[b], offset_[b], size, size) = buildings_[b].stiffness;
    damping_.block(offset_[b], offset_[b], size, size) = buildings_[b].damping;
  }
  influence_ = MatrixXd::Zero(dof_, ground_motion_.component_count());
  const double beta = ground_motion_.direction_rad();
  for (int i = 0; i < dof_; i += 3) {
    influence_.col(0).segment<2>(i) << std::cos(beta), std::sin(beta);
    if (ground_motion_.is_pair()) influence_.col(1).segment<2>(i) << -std::sin(beta), std::cos(beta);
  }

  a_matrix_ = MatrixXd::Zero(2 * dof_, 2 * dof_);
  a_matrix_.topRightCorner(dof_, dof_).setIdentity();
  const VectorXd inverse_mass = mass_.cwiseInverse();
  a_matrix_.bottomLeftCorner(dof_, dof_) = -(inverse_mass.asDiagonal() * stiffness_);
  a_matrix_.bottomRightCorner(dof_, dof_) = -(inverse_mass.asDiagonal() * damping_);
  stiffness_sparse_ = stiffness_.sparseView();
  damping_sparse_ = damping_.sparseView();
  acceleration_rows_ = a_matrix_.bottomRows(dof_).sparseView();  // every nonzero, bit for bit
  springs_ = YieldingSprings(buildings_, offset_);
}

void CoupledSystem::rhs(double t, ConstVectorRef y, Eigen::Ref<VectorXd> y_dot, const SpringStates* springs) const {
  // q̈ = −M⁻¹(K q + C q̇ − slip forces) − r a_g; the accelerations first, in case y_dot aliases y.
  if (springs != nullptr && !springs_.empty()) {
    VectorXd restoring = stiffness_sparse_ * y.head(dof_) + damping_sparse_ * y.segment(dof_, dof_);
    VectorXd slip_force = VectorXd::Zero(dof_);
    springs_.add_slip_force(y, *springs, slip_force);
    restoring -= slip_force;
    y_dot.segment(dof_, dof_) = -(restoring.cwiseQuotient(mass_) + influence() * ground_motion_.accel_at(t));
  } else {
    y_dot.segment(dof_, dof_) =
        -((stiffness_sparse_ * y.head(dof_) + damping_sparse_ * y.segment(dof_, dof_)).cwiseQuotient(mass_) +
          influence() * ground_motion_.accel_at(t));
  }
  if (ground_motion_.is_pair()) y_dot.segment(dof_, dof_) -= influence(1) * ground_motion_.accel_at(t, 1);
  y_dot.head(dof_) = y.segment(dof_, dof_);
  if (springs_.smooth_count() > 0) springs_.hysteretic_rates(y, y_dot.tail(springs_.smooth_count()));
}

VectorXd CoupledSystem::ground_acceleration(double t) const {
  VectorXd accel = influence() * ground_motion_.accel_at(t);
  for (int c = 1; c < ground_motion_.component_count(); ++c) accel += influence(c) * ground_motion_.accel_at(t, c);
  return accel;
}

const model::ModalBasis& CoupledSystem::modal_basis(int b) const {
  std::call_once(modal_bases_->built[b], [&] {
    modal_bases_->basis[b] = model::modal_basis(buildings_[b], influence_.middleRows(offset_[b], buildings_[b].dof()));
  });
  return modal_bases_->basis[b];
}

void CoupledSystem::external_force(double t, Eigen::Ref<VectorXd> force) const {
  force = -ground_motion_.accel_at(t) * mass_.cwiseProduct(influence());
  for (int c = 1; c < ground_motion_.component_count(); ++c) {
    force -= ground_motion_.accel_at(t, c) * mass_.cwiseProduct(influence(c));
  }
}

contact::SlabMotion CoupledSystem::slab(ConstVectorRef y, int building, int floor) const {
  const int i = floor_index(building, floor);
  return {buildings_[building].definition.centre_of_mass, y.segment<3>(i), y.segment<3>(dof_ + i)};
}

contact::GapState CoupledSystem::gap(ConstVectorRef y, std::size_t index) const {
  const contact::Candidate& c = candidates_[index];
  if (c.column) {
    const std::optional<contact::SlabMotion> lower =
        c.lower_floor > 0 ? std::optional(slab(y, c.striking_building, c.lower_floor)) : std::nullopt;
    return contact::evaluate_column_gap(c, lower ? &*lower : nullptr,
                                        slab(y, c.striking_building, c.floor_of(c.striking_building)),
                                        slab(y, c.struck_building, c.floor_of(c.struck_building)));
  }
  return contact::evaluate_gap(c, slab(y, c.striking_building, c.floor_of(c.striking_building)),
                               slab(y, c.struck_building, c.floor_of(c.struck_building)));
}

double CoupledSystem::depth_inside_m(ConstVectorRef y, std::size_t index, const contact::GapState& s) const {
  const contact::Candidate& c = candidates_[index];
  const int b = c.struck_building;
  const contact::SlabMotion motion = slab(y, b, c.floor_of(b));
  const double cos_phi = std::cos(motion.q[2]), sin_phi = std::sin(motion.q[2]);
  std::vector<model::Point2> outline;
  for (const model::Point2& v : buildings_[b].definition.slab.vertices()) {
    const model::Point2 arm = v - motion.centre_rest;
    outline.emplace_back(motion.centre_rest + motion.q.head<2>() +
                         model::Point2(cos_phi * arm.x() - sin_phi * arm.y(), sin_phi * arm.x() + cos_phi * arm.y()));
  }
  return contact::depth_inside(outline, s.contact_point);
}

CoupledSystem::RowBlocks CoupledSystem::row_blocks(const contact::Candidate& c, const contact::GapState& s) const {
  const auto block = [&](int building, int floor, const Eigen::RowVector3d& row) {
    return RowBlock{building, floor, floor_index(building, floor), row};
  };
  RowBlocks blocks;
  blocks.blocks[0] = block(c.striking_building, c.floor_of(c.striking_building), s.striking_row);
  blocks.blocks[1] = block(c.struck_building, c.floor_of(c.struck_building), s.struck_row);
  if (c.column && c.lower_floor > 0) {
    blocks.blocks[2] = block(c.striking_building, c.lower_floor, s.striking_lower_row);
    blocks.count = 3;
  }
  return blocks;
}

double CoupledSystem::gap_acceleration(ConstVectorRef y, ConstVectorRef y_dot, std::size_t index) const {
  const contact::Candidate& c = candidates_[index];
  const contact::GapState s = gap(y, index);
  if (c.column) {
    double accel = s.curvature_mps2;
    for (const RowBlock& block : row_blocks(c, s)) accel += block.row.dot(y_dot.segment<3>(dof_ + block.first));
    return accel;
  }
  const auto accel_of = [&](int building) {
    return y_dot.segment<3>(dof_ + floor_index(building, c.floor_of(building)));
  };
  return s.striking_row.dot(accel_of(c.striking_building)) + s.struck_row.dot(accel_of(c.struck_building)) +
         s.curvature_mps2;
}

double CoupledSystem::gap_rate_round_off_mps(ConstVectorRef y, std::size_t index) const {
  double size = 0.0;
  for (const RowBlock& block : row_blocks(candidates_[index], gap(y, index)))
    size += block.row.cwiseAbs().dot(y.segment<3>(dof_ + block.first).cwiseAbs());
  return 1e-15 + 1e-9 * size;
}

VectorXd CoupledSystem::slab_velocities(ConstVectorRef y, const std::vector<Slab>& slabs) const {
  VectorXd v(3 * static_cast<Eigen::Index>(slabs.size()));
  for (std::size_t k = 0; k < slabs.size(); ++k)
    v.segment<3>(3 * static_cast<Eigen::Index>(k)) =
        y.segment<3>(dof_ + floor_index(slabs[k].building, slabs[k].floor));
  return v;
}

void CoupledSystem::add_slab_velocities(Eigen::Ref<VectorXd> y, const std::vector<Slab>& slabs,
                                        const VectorXd& change) const {
  for (std::size_t k = 0; k < slabs.size(); ++k)
    y.segment<3>(dof_ + floor_index(slabs[k].building, slabs[k].floor)) +=
        change.segment<3>(3 * static_cast<Eigen::Index>(k));
}

VectorXd CoupledSystem::slab_inverse_mass(const std::vector<Slab>& slabs) const {
  VectorXd inverse(3 * static_cast<Eigen::Index>(slabs.size()));
  for (std::size_t k = 0; k < slabs.size(); ++k) {
    const int i = floor_index(slabs[k].building, slabs[k].floor);
    inverse.segment<3>(3 * static_cast<Eigen::Index>(k)) << 1 / mass_[i], 1 / mass_[i + 1], 1 / mass_[i + 2];
  }
  return inverse;
}

Eigen::RowVectorXd CoupledSystem::slab_row(const contact::GapState& s, const contact::Candidate& c,
                                           const std::vector<Slab>& slabs) const {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(3 * static_cast<Eigen::Index>(slabs.size()));
  for (const RowBlock& block : row_blocks(c, s)) {
    const auto at = std::find(slabs.begin(), slabs.end(), Slab{block.building, block.floor});
    row.segment<3>(3 * (at - slabs.begin())) = block.row;
  }
  return row;
}

void CoupledSystem::constraint_rows(ConstVectorRef y, const std::vector<std::size_t>& held, MatrixXd& rows,
                                    VectorXd& bias, bool drift_correction) const {
  const Eigen::Index k = static_cast<Eigen::Index>(held.size());
  rows = MatrixXd::Zero(k, dof_);
  bias.resize(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    const contact::GapState s = gap(y, held[r]);
    for (const RowBlock& block : row_blocks(candidates_[held[r]], s)) rows.block<1, 3>(r, block.first) = block.row;
    // Drift correction g̈ = −3ġ/τ − 2g/τ²: roots −1/τ and −2/τ, distinct so that the linearised
    // held system stays diagonalisable (the exact path relies on it).
    constexpr double tau = hold_time_constant_s;
    bias[r] = s.curvature_mps2;
    if (drift_correction) bias[r] += 3.0 * s.gap_rate_mps / tau + 2.0 * s.gap_m / (tau * tau);
  }
}

void CoupledSystem::constrained_rhs(double t, ConstVectorRef y, const std::vector<std::size_t>& held,
                                    Eigen::Ref<VectorXd> y_dot, Eigen::Ref<VectorXd> forces_kN,
                                    const SpringStates* springs) const {
  rhs(t, y, y_dot, springs);
  if (held.empty()) return;
  MatrixXd rows;
  VectorXd bias;
  constraint_rows(y, held, rows, bias);
  const VectorXd inverse_mass = mass_.cwiseInverse();
  const MatrixXd w = rows * inverse_mass.asDiagonal() * rows.transpose();
  // W λ = −(G q̈_free + bias): the forces that make every held gap's (stabilised) g̈ vanish.
  const VectorXd needed = -(rows * y_dot.segment(dof_, dof_) + bias);
  forces_kN = w.completeOrthogonalDecomposition().solve(needed);
  y_dot.segment(dof_, dof_) += inverse_mass.asDiagonal() * (rows.transpose() * forces_kN);
}

contact::LcpSolution CoupledSystem::hold_complementarity(double t, ConstVectorRef y,
                                                         const std::vector<std::size_t>& held,
                                                         const SpringStates* springs) const {
  VectorXd y_dot(state_size());
  rhs(t, y, y_dot, springs);
  MatrixXd rows;
  VectorXd bias;
  constraint_rows(y, held, rows, bias);
  const MatrixXd w = rows * mass_.cwiseInverse().asDiagonal() * rows.transpose();
  return contact::solve_lcp(w, rows * y_dot.segment(dof_, dof_) + bias);
}

CoupledSystem::PhysicalHoldForces CoupledSystem::physical_hold_forces(double t, ConstVectorRef y,
                                                                      const std::vector<std::size_t>& held,
                                                                      const SpringStates* springs) const {
  VectorXd y_dot(state_size());
  rhs(t, y, y_dot, springs);
  MatrixXd rows;
  VectorXd bias;
  constraint_rows(y, held, rows, bias, false);
  const MatrixXd w = rows * mass_.cwiseInverse().asDiagonal() * rows.transpose();
  const auto free_accel = y_dot.segment(dof_, dof_);
  PhysicalHoldForces result;
  result.forces_kN = w.completeOrthogonalDecomposition().solve(-(rows * free_accel + bias));
  // The free gap accelerations are differences of terms of this size; below it a force is noise.
  const VectorXd term_size = rows.cwiseAbs() * free_accel.cwiseAbs();
  for (Eigen::Index k = 0; k < rows.rows(); ++k) {
    const double round_off_mps2 = 1e-9 * (1.0 + term_size[k] + std::abs(bias[k]));
    result.pressing.push_back(w(k, k) * result.forces_kN[k] > round_off_mps2);
  }
  return result;
}

void CoupledSystem::constrained_jacobian(ConstVectorRef y, const std::vector<std::size_t>& held,
                                         Eigen::Ref<MatrixXd> jacobian) const {
  Eigen::SparseMatrix<double> rows;
  constrained_acceleration_jacobian(y, held, rows);
  jacobian.topRows(dof_).setZero();
  jacobian.topRightCorner(dof_, dof_).setIdentity();
  jacobian.bottomRows(dof_) = rows;
}

void CoupledSystem::full_jacobian(ConstVectorRef y, const Eigen::SparseMatrix<double>& acceleration_rows,
                                  Eigen::Ref<MatrixXd> jacobian, const std::vector<std::size_t>& held) const {
  jacobian.setZero();
  jacobian.block(0, dof_, dof_, dof_).setIdentity();
  jacobian.block(dof_, 0, dof_, 2 * dof_) = acceleration_rows;
  const int m = springs_.smooth_count();
  if (m == 0) return;
  Eigen::SparseMatrix<double> accel_by_z, z_rate_by_velocity;
  VectorXd z_rate_by_z;
  smooth_jacobian(y, held, accel_by_z, z_rate_by_velocity, z_rate_by_z);
  jacobian.block(dof_, 2 * dof_, dof_, m) = accel_by_z;
  jacobian.block(2 * dof_, dof_, m, dof_) = z_rate_by_velocity;
  jacobian.bottomRightCorner(m, m).diagonal() = z_rate_by_z;
}

void CoupledSystem::smooth_jacobian(ConstVectorRef y, const std::vector<std::size_t>& held,
                                    Eigen::SparseMatrix<double>& accel_by_z,
                                    Eigen::SparseMatrix<double>& z_rate_by_velocity, VectorXd& z_rate_by_z) const {
  springs_.smooth_jacobian(y, mass_.cwiseInverse(), accel_by_z, z_rate_by_velocity, z_rate_by_z);
  if (held.empty()) return;
  MatrixXd rows;
  VectorXd bias;
  constraint_rows(y, held, rows, bias);
  const MatrixXd m_inv_gt = mass_.cwiseInverse().asDiagonal() * rows.transpose();
  const MatrixXd w = rows * m_inv_gt;
  // B − M⁻¹Gᵀ W⁺ G B: only the held floors' rows change (W⁺ as constrained_rhs' least squares).
  const MatrixXd correction = m_inv_gt * (w.completeOrthogonalDecomposition().pseudoInverse() * (rows * accel_by_z));
  accel_by_z = (MatrixXd(accel_by_z) - correction).sparseView();
}

void CoupledSystem::constrained_acceleration_jacobian(ConstVectorRef y, const std::vector<std::size_t>& held,
                                                      Eigen::SparseMatrix<double>& rows,
                                                      const SpringStates* springs) const {
  rows = acceleration_rows_;
  if (springs != nullptr) springs_.add_tangent_rows(*springs, mass_.cwiseInverse(), rows);
  if (held.empty()) return;
  const Eigen::SparseMatrix<double> free_rows = rows;
  MatrixXd dense_rows;
  VectorXd bias;
  constraint_rows(y, held, dense_rows, bias);
  const Eigen::SparseMatrix<double> g = dense_rows.sparseView();  // six entries a row
  const Eigen::SparseMatrix<double> m_inv_gt = mass_.cwiseInverse().asDiagonal() * g.transpose();
  const MatrixXd w = g * m_inv_gt;
  // The projection M⁻¹Gᵀ W⁻¹ G applied to A's lower half and to the Baumgarte terms, which
  // depend on y through g ≈ G q and ġ = G q̇ (rows frozen at y): M⁻¹Gᵀ W⁻¹ (G A₂ + [2/τ² G, 3/τ G])
  // with A₂ = acceleration_rows_, associated so that no n × n product is formed. W⁻¹ is the
  // pseudo-inverse, as constrained_rhs' least-squares forces: dependent contacts share.
  constexpr double tau = hold_time_constant_s;
  std::vector<Eigen::Triplet<double>> drift_terms;
  for (int r = 0; r < g.outerSize(); ++r) {
    for (Eigen::SparseMatrix<double>::InnerIterator entry(g, r); entry; ++entry) {
      drift_terms.emplace_back(entry.row(), entry.col(), entry.value() * (2.0 / (tau * tau)));
      drift_terms.emplace_back(entry.row(), dof_ + entry.col(), entry.value() * (3.0 / tau));
    }
  }
  Eigen::SparseMatrix<double> drift(g.rows(), 2 * dof_);
  drift.setFromTriplets(drift_terms.begin(), drift_terms.end());
  const Eigen::SparseMatrix<double> w_inverse = w.completeOrthogonalDecomposition().pseudoInverse().sparseView();
  rows -= m_inv_gt * (w_inverse * (g * free_rows + drift));
}

Eigen::RowVectorXd CoupledSystem::full_row(ConstVectorRef y, std::size_t index) const {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(dof_);
  for (const RowBlock& block : row_blocks(candidates_[index], gap(y, index))) row.segment<3>(block.first) = block.row;
  return row;
}

double CoupledSystem::normal_inverse_mass(ConstVectorRef y, std::size_t index) const {
  const Eigen::RowVectorXd row = full_row(y, index);
  return row.cwiseAbs2().dot(mass_.cwiseInverse().transpose());
}

void CoupledSystem::add_contact_force(ConstVectorRef y, std::size_t index, double force_kN,
                                      Eigen::Ref<VectorXd> y_dot) const {
  // Only the gap's floors feel it: O(1) per contact, not O(n) (a row has many contacts at once).
  for (const RowBlock& block : row_blocks(candidates_[index], gap(y, index))) {
    for (int k = 0; k < 3; ++k) y_dot[dof_ + block.first + k] += block.row[k] * force_kN / mass_[block.first + k];
  }
}

Eigen::SparseMatrix<double> CoupledSystem::contact_force_rows(ConstVectorRef y, std::size_t index,
                                                              double stiffness_kN_per_m,
                                                              double damping_kNs_per_m) const {
  std::vector<std::pair<int, double>> row;  // G's entries: (index in q, value)
  for (const RowBlock& block : row_blocks(candidates_[index], gap(y, index))) {
    for (int k = 0; k < 3; ++k) row.emplace_back(block.first + k, block.row[k]);
  }
  std::vector<Eigen::Triplet<double>> terms;
  for (const auto& [i, g_i] : row) {
    for (const auto& [j, g_j] : row) {
      const double coupling = g_i / mass_[i] * g_j;  // (M⁻¹GᵀG)ᵢⱼ
      terms.emplace_back(i, j, stiffness_kN_per_m * coupling);
      terms.emplace_back(i, dof_ + j, damping_kNs_per_m * coupling);
    }
  }
  Eigen::SparseMatrix<double> rows(dof_, 2 * dof_);
  rows.setFromTriplets(terms.begin(), terms.end());
  return rows;
}

void CoupledSystem::add_contact_force_jacobian(ConstVectorRef y, std::size_t index, double stiffness_kN_per_m,
                                               double damping_kNs_per_m, Eigen::SparseMatrix<double>& rows) const {
  rows -= contact_force_rows(y, index, stiffness_kN_per_m, damping_kNs_per_m);
}

double CoupledSystem::column_sway_shear_kN(ConstVectorRef y, int building, int storey, std::size_t column,
                                           int direction, const SpringStates* springs) const {
  if (springs != nullptr) {
    if (const std::optional<std::size_t> j = springs_.index_of(building, storey, column, direction))
      return springs_.force_kN(y, *springs, *j);
  }
  const model::Building& b = buildings_[building];
  const model::Column& c = b.definition.columns.at(column);
  const double height_m = b.definition.storey_height_m[static_cast<std::size_t>(storey - 1)];
  const double k_kN_per_m = model::column_stiffness(c, b.definition.E_kPa, height_m, b.frame_factor)[direction];
  const std::array<double, 3> t = model::column_drift_row(b.definition, column, direction);
  const Eigen::RowVector3d row(t[0], t[1], t[2]);
  double drift_m = row * y.segment<3>(floor_index(building, storey));
  if (storey > 1) drift_m -= row * y.segment<3>(floor_index(building, storey - 1));
  return k_kN_per_m * drift_m;
}

double CoupledSystem::kinetic_energy(ConstVectorRef y) const {
  return 0.5 * y.segment(dof_, dof_).cwiseAbs2().dot(mass_);
}

double CoupledSystem::strain_energy(ConstVectorRef y, const SpringStates* springs) const {
  const double elastic_kJ = 0.5 * y.head(dof_).dot(stiffness_sparse_ * y.head(dof_));
  if (springs == nullptr || springs_.empty()) return elastic_kJ;
  return elastic_kJ + springs_.stored_energy_change(y, *springs);
}

double CoupledSystem::damping_power(ConstVectorRef y) const {
  return y.segment(dof_, dof_).dot(damping_sparse_ * y.segment(dof_, dof_));
}

double CoupledSystem::input_power(double t, ConstVectorRef y) const {
  double power = -y.segment(dof_, dof_).dot(mass_.cwiseProduct(influence())) * ground_motion_.accel_at(t);
  for (int c = 1; c < ground_motion_.component_count(); ++c) {
    power -= y.segment(dof_, dof_).dot(mass_.cwiseProduct(influence(c))) * ground_motion_.accel_at(t, c);
  }
  return power;
}

}  // namespace pounding::dynamics
