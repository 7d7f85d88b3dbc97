#include "pounding/contact/impact.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <optional>

namespace pounding::contact {
namespace {

constexpr std::size_t kMaxEnumerated = 12;

struct Lcp {
  Eigen::MatrixXd w_matrix;  // W = G M⁻¹ Gᵀ
  Eigen::VectorXd offset;    // ġ⁻ − e: w = W I + offset
};

Lcp assemble(const std::vector<ContactRow>& contacts, const Eigen::VectorXd& inverse_mass) {
  const Eigen::Index m = static_cast<Eigen::Index>(contacts.size());
  Eigen::MatrixXd g(m, inverse_mass.size());
  Lcp lcp{Eigen::MatrixXd(m, m), Eigen::VectorXd(m)};
  for (Eigen::Index i = 0; i < m; ++i) {
    g.row(i) = contacts[i].jacobian;
    const double rate = contacts[i].gap_rate_mps;
    lcp.offset[i] = rate + contacts[i].restitution * std::min(rate, 0.0);
  }
  // A floor pair's W is formed with a fixed six-vector M⁻¹ (as two-building runs always were).
  if (inverse_mass.size() == 6) {
    lcp.w_matrix = g * Eigen::Map<const Vector6d>(inverse_mass.data()).asDiagonal() * g.transpose();
  } else {
    lcp.w_matrix = g * inverse_mass.asDiagonal() * g.transpose();
  }
  return lcp;
}

/// Tries the active set `mask`; returns the impulses if they satisfy the LCP to `tolerance`.
std::optional<Eigen::VectorXd> try_active_set(const Lcp& lcp, unsigned mask, double tolerance) {
  const Eigen::Index m = lcp.offset.size();
  std::vector<Eigen::Index> active;
  for (Eigen::Index i = 0; i < m; ++i) {
    if (mask & (1u << i)) active.push_back(i);
  }
  Eigen::VectorXd impulses = Eigen::VectorXd::Zero(m);
  if (!active.empty()) {
    const Eigen::Index a = static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd w_aa(a, a);
    Eigen::VectorXd rhs(a);
    for (Eigen::Index r = 0; r < a; ++r) {
      rhs[r] = -lcp.offset[active[r]];
      for (Eigen::Index c = 0; c < a; ++c) w_aa(r, c) = lcp.w_matrix(active[r], active[c]);
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(w_aa);
    if (lu.rank() < a) return std::nullopt;  // dependent contacts: a smaller set will do
    const Eigen::VectorXd solved = lu.solve(rhs);
    for (Eigen::Index r = 0; r < a; ++r) impulses[active[r]] = solved[r];
  }
  const Eigen::VectorXd w = lcp.w_matrix * impulses + lcp.offset;
  for (Eigen::Index i = 0; i < m; ++i) {
    if (impulses[i] < -tolerance || w[i] < -tolerance) return std::nullopt;
  }
  return impulses.cwiseMax(0.0);
}

Eigen::VectorXd enumerate(const Lcp& lcp, double tolerance) {
  const unsigned m = static_cast<unsigned>(lcp.offset.size());
  std::vector<unsigned> masks(1u << m);
  std::iota(masks.begin(), masks.end(), 0u);
  // Fewest active contacts first: the sparsest impulse set that satisfies the LCP.
  std::stable_sort(masks.begin(), masks.end(),
                   [](unsigned a, unsigned b) { return std::popcount(a) < std::popcount(b); });
  for (unsigned mask : masks) {
    if (auto impulses = try_active_set(lcp, mask, tolerance)) return *impulses;
  }
  return {};
}

/// max_i |min(W_ii x_i, w_i)| / max_i |offset_i|: zero exactly where x ≥ 0 solves the LCP (both
/// terms are in w's unit, a velocity for impacts and an acceleration for holds, so the ratio is
/// scale-free).
double complementarity_residual(const Lcp& lcp, const Eigen::VectorXd& x) {
  const Eigen::VectorXd w = lcp.w_matrix * x + lcp.offset;
  double largest = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    largest = std::max(largest, std::abs(std::min(lcp.w_matrix(i, i) * x[i], w[i])));
  const double scale = lcp.offset.cwiseAbs().maxCoeff();
  return scale > 0.0 ? largest / scale : largest;
}

/// Projected Gauss–Seidel until the residual is below kGaussSeidelResidual (checked every
/// kGaussSeidelCheck sweeps) or after kGaussSeidelSweeps sweeps. It converges for symmetric
/// positive semi-definite W, slowly where contacts depend on each other (rows of held slabs).
constexpr int kGaussSeidelSweeps = 20000;
constexpr int kGaussSeidelCheck = 25;
constexpr double kGaussSeidelResidual = 1e-12;

LcpSolution gauss_seidel(const Lcp& lcp) {
  const Eigen::Index m = lcp.offset.size();
  LcpSolution solution{Eigen::VectorXd::Zero(m), {}, false, 0.0};
  Eigen::VectorXd& impulses = solution.x;
  for (int sweep = 1; sweep <= kGaussSeidelSweeps; ++sweep) {
    for (Eigen::Index i = 0; i < m; ++i) {
      if (lcp.w_matrix(i, i) <= 0.0) continue;
      const double w = lcp.w_matrix.row(i).dot(impulses) + lcp.offset[i];
      impulses[i] = std::max(0.0, impulses[i] - w / lcp.w_matrix(i, i));
    }
    if (sweep % kGaussSeidelCheck == 0 && complementarity_residual(lcp, impulses) <= kGaussSeidelResidual) break;
  }
  solution.residual = complementarity_residual(lcp, impulses);
  return solution;
}

/// The contacts coupled to each other through W (sharing a slab), each group in ascending order.
std::vector<std::vector<Eigen::Index>> coupled_blocks(const Eigen::MatrixXd& w_matrix) {
  const Eigen::Index m = w_matrix.rows();
  std::vector<Eigen::Index> block(static_cast<std::size_t>(m), -1);
  std::vector<std::vector<Eigen::Index>> blocks;
  for (Eigen::Index start = 0; start < m; ++start) {
    if (block[static_cast<std::size_t>(start)] >= 0) continue;
    blocks.emplace_back();
    std::vector<Eigen::Index> todo{start};
    block[static_cast<std::size_t>(start)] = static_cast<Eigen::Index>(blocks.size() - 1);
    while (!todo.empty()) {
      const Eigen::Index i = todo.back();
      todo.pop_back();
      blocks.back().push_back(i);
      for (Eigen::Index j = 0; j < m; ++j) {
        if (block[static_cast<std::size_t>(j)] < 0 && w_matrix(i, j) != 0.0) {
          block[static_cast<std::size_t>(j)] = block[static_cast<std::size_t>(i)];
          todo.push_back(j);
        }
      }
    }
    std::sort(blocks.back().begin(), blocks.back().end());
  }
  return blocks;
}

/// A problem of more than kMaxEnumerated contacts, split into its independent blocks (contacts
/// that share no slab do not interact; the held contacts of every level form one problem): each
/// block of at most kMaxEnumerated is solved exactly, a larger one by Gauss–Seidel.
LcpSolution solve_by_blocks(const Lcp& lcp, double tolerance) {
  const Eigen::Index m = lcp.offset.size();
  LcpSolution solution{Eigen::VectorXd::Zero(m), {}, true, 0.0};
  for (const std::vector<Eigen::Index>& members : coupled_blocks(lcp.w_matrix)) {
    const Eigen::Index size = static_cast<Eigen::Index>(members.size());
    Lcp sub{Eigen::MatrixXd(size, size), Eigen::VectorXd(size)};
    for (Eigen::Index r = 0; r < size; ++r) {
      sub.offset[r] = lcp.offset[members[static_cast<std::size_t>(r)]];
      for (Eigen::Index c = 0; c < size; ++c)
        sub.w_matrix(r, c) = lcp.w_matrix(members[static_cast<std::size_t>(r)], members[static_cast<std::size_t>(c)]);
    }
    Eigen::VectorXd x;
    if (size <= static_cast<Eigen::Index>(kMaxEnumerated)) x = enumerate(sub, tolerance);
    if (x.size() == 0) {
      const LcpSolution iterated = gauss_seidel(sub);
      x = iterated.x;
      solution.exact = false;
    }
    for (Eigen::Index r = 0; r < size; ++r) solution.x[members[static_cast<std::size_t>(r)]] = x[r];
  }
  if (!solution.exact) solution.residual = complementarity_residual(lcp, solution.x);
  return solution;
}

}  // namespace

Vector6d inverse_mass(double mass1_t, double polar1_tm2, double mass2_t, double polar2_tm2) {
  Vector6d inv;
  inv << 1 / mass1_t, 1 / mass1_t, 1 / polar1_tm2, 1 / mass2_t, 1 / mass2_t, 1 / polar2_tm2;
  return inv;
}

double single_impulse(const ContactRow& contact, const Eigen::VectorXd& inverse_mass) {
  const double a = gap_rate(contact.jacobian.cwiseAbs2(), inverse_mass);
  return (1.0 + contact.restitution) * (-contact.gap_rate_mps) / a;
}

LcpSolution solve_lcp(const Eigen::MatrixXd& w_matrix, const Eigen::VectorXd& offset) {
  LcpSolution solution;
  if (offset.size() == 0) return solution;
  const Lcp lcp{w_matrix, offset};
  const double tolerance = 1e-12 * (offset.cwiseAbs().maxCoeff() + 1e-12) * (1.0 + w_matrix.diagonal().maxCoeff());
  if (offset.size() <= static_cast<Eigen::Index>(kMaxEnumerated)) {
    solution.x = enumerate(lcp, tolerance);
    if (solution.x.size() == 0) solution = gauss_seidel(lcp);
  } else {
    solution = solve_by_blocks(lcp, tolerance);
  }
  solution.w = w_matrix * solution.x + offset;
  return solution;
}

ImpulseSolution solve_impulses(const std::vector<ContactRow>& contacts, const Eigen::VectorXd& inverse_mass) {
  ImpulseSolution solution;
  solution.velocity_change = Eigen::VectorXd::Zero(inverse_mass.size());
  if (contacts.empty()) return solution;
  const Lcp lcp = assemble(contacts, inverse_mass);
  const LcpSolution lcp_solution = solve_lcp(lcp.w_matrix, lcp.offset);
  const Eigen::VectorXd& impulses = lcp_solution.x;
  solution.exact = lcp_solution.exact;
  solution.lcp_residual = lcp_solution.residual;
  solution.impulses_kNs.assign(impulses.data(), impulses.data() + impulses.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    solution.velocity_change += inverse_mass.cwiseProduct(contacts[i].jacobian.transpose()) * impulses[i];
  }
  return solution;
}

template <int N>
ImpulseSolution closing_impulses_of_size(const std::vector<Eigen::RowVectorXd>& rows,
                                         const Eigen::VectorXd& inverse_mass, const Eigen::VectorXd& velocities) {
  const Eigen::Map<const Eigen::Matrix<double, N, 1>> inv(inverse_mass.data(), inverse_mass.size());
  const Eigen::Map<const Eigen::Matrix<double, N, 1>> v(velocities.data(), velocities.size());
  Eigen::MatrixXd g(static_cast<Eigen::Index>(rows.size()), inverse_mass.size());
  for (std::size_t r = 0; r < rows.size(); ++r) g.row(static_cast<Eigen::Index>(r)) = rows[r];
  const Eigen::MatrixXd w = g * inv.asDiagonal() * g.transpose();
  const Eigen::VectorXd impulses = w.completeOrthogonalDecomposition().solve(-(g * v));
  ImpulseSolution solution;
  solution.impulses_kNs.assign(impulses.data(), impulses.data() + impulses.size());
  solution.velocity_change = inv.cwiseProduct(g.transpose() * impulses);
  return solution;
}

ImpulseSolution closing_impulses(const std::vector<Eigen::RowVectorXd>& rows, const Eigen::VectorXd& inverse_mass,
                                 const Eigen::VectorXd& velocities) {
  if (inverse_mass.size() == 6) return closing_impulses_of_size<6>(rows, inverse_mass, velocities);
  return closing_impulses_of_size<Eigen::Dynamic>(rows, inverse_mass, velocities);
}

namespace {

/// Whether every kept row's ġ at `velocities` is at least its minimum, to `tolerance`.
bool keeps_minimum(const std::vector<KeptRow>& kept, const Eigen::VectorXd& velocities, double tolerance) {
  for (const KeptRow& row : kept) {
    if (gap_rate(row.jacobian, velocities) < row.min_rate_mps - tolerance) return false;
  }
  return true;
}

}  // namespace

ImpulseSolution closing_impulses_keeping(const std::vector<Eigen::RowVectorXd>& held, const std::vector<KeptRow>& kept,
                                         const Eigen::VectorXd& inverse_mass, const Eigen::VectorXd& velocities) {
  ImpulseSolution plain = closing_impulses(held, inverse_mass, velocities);
  double scale = 1e-12;
  for (const Eigen::RowVectorXd& row : held) scale = std::max(scale, std::abs(gap_rate(row, velocities)));
  for (const KeptRow& row : kept) scale = std::max(scale, std::abs(gap_rate(row.jacobian, velocities)));
  const double tolerance = 1e-12 * scale;
  const Eigen::VectorXd after = velocities + plain.velocity_change;
  if (kept.size() > kMaxEnumerated || keeps_minimum(kept, after, tolerance)) {
    plain.impulses_kNs.resize(held.size() + kept.size(), 0.0);
    return plain;
  }
  // Rows: held, then kept. Unknown impulses x; w = G M⁻¹ Gᵀ x + (G q̇ − target).
  const Eigen::Index h = static_cast<Eigen::Index>(held.size()), m = h + static_cast<Eigen::Index>(kept.size());
  Eigen::MatrixXd g(m, inverse_mass.size());
  Eigen::VectorXd offset(m);
  for (Eigen::Index r = 0; r < h; ++r) {
    g.row(r) = held[static_cast<std::size_t>(r)];
    offset[r] = gap_rate(g.row(r), velocities);
  }
  for (Eigen::Index r = h; r < m; ++r) {
    const KeptRow& row = kept[static_cast<std::size_t>(r - h)];
    g.row(r) = row.jacobian;
    offset[r] = gap_rate(row.jacobian, velocities) - row.min_rate_mps;
  }
  const Eigen::MatrixXd w_matrix = g * inverse_mass.asDiagonal() * g.transpose();
  const unsigned free_count = static_cast<unsigned>(kept.size());
  std::vector<unsigned> masks(1u << free_count);
  std::iota(masks.begin(), masks.end(), 0u);
  std::stable_sort(masks.begin(), masks.end(),
                   [](unsigned a, unsigned b) { return std::popcount(a) < std::popcount(b); });
  for (unsigned mask : masks) {
    std::vector<Eigen::Index> active;
    for (Eigen::Index r = 0; r < h; ++r) active.push_back(r);
    for (unsigned k = 0; k < free_count; ++k) {
      if (mask & (1u << k)) active.push_back(h + static_cast<Eigen::Index>(k));
    }
    const Eigen::Index a = static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd w_aa(a, a);
    Eigen::VectorXd rhs(a);
    for (Eigen::Index r = 0; r < a; ++r) {
      rhs[r] = -offset[active[r]];
      for (Eigen::Index c = 0; c < a; ++c) w_aa(r, c) = w_matrix(active[r], active[c]);
    }
    const Eigen::VectorXd solved = w_aa.completeOrthogonalDecomposition().solve(rhs);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(m);
    for (Eigen::Index r = 0; r < a; ++r) x[active[r]] = solved[r];
    const Eigen::VectorXd w = w_matrix * x + offset;
    bool solves = true;
    for (Eigen::Index r = 0; r < m && solves; ++r) {
      solves = r < h ? std::abs(w[r]) <= tolerance : x[r] >= -tolerance && w[r] >= -tolerance;
    }
    if (!solves) continue;
    ImpulseSolution solution;
    solution.impulses_kNs.assign(x.data(), x.data() + m);
    solution.velocity_change = inverse_mass.cwiseProduct(g.transpose() * x);
    return solution;
  }
  plain.impulses_kNs.resize(held.size() + kept.size(), 0.0);  // no mixed solution: the held rows' own
  return plain;
}

double kinetic_energy(const Eigen::VectorXd& velocities, const Eigen::VectorXd& inverse_mass) {
  return 0.5 * gap_rate(velocities.cwiseAbs2().transpose(), inverse_mass.cwiseInverse());
}

double gap_rate(const Eigen::RowVectorXd& row, const Eigen::VectorXd& velocities) {
  if (row.size() == 6)
    return Eigen::Map<const RowVector6d>(row.data()).dot(Eigen::Map<const Vector6d>(velocities.data()));
  return row.dot(velocities);
}

}  // namespace pounding::contact
