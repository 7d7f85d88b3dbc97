#pragma once
// The one list of history.csv's per-slab quantities, read by the recorder for both the header
// and every row (so a column and its value cannot drift apart), by `pounding outputs` and by the
// docs' column list (docs/guide/output-columns.md, generated from it).
//
// How a column is spelled: `B{b}_f{f}_` (building 1 or 2, its floor), then the quantity's name,
// then `_unit` when it has a unit. A quantity per contact vertex or per slab corner has `{n}` in
// its name, the vertex's or corner's 1-based number in the slab outline; consecutive quantities
// of the same kind are written vertex by vertex (c1_drift_x, c1_drift_y, c2_drift_x, ...).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/model/polygon.hpp"

namespace pounding::solvers {

/// Displacement (m) of a slab point given at rest, `arm` from the CM, with exact rotation, from
/// the slab's (u, v); c, s: cos φ and sin φ, which the caller takes once per slab.
inline model::Point2 point_displacement(const model::Point2& arm, double u, double v, double c, double s) {
  return {u + (c - 1.0) * arm.x() - s * arm.y(), v + s * arm.x() + (c - 1.0) * arm.y()};
}

/// One slab at one instant, as the history reads it.
struct SlabSample {
  const double* q = nullptr;      // u (m), v (m), φ (rad) of the slab's CM
  const double* accel = nullptr;  // its absolute accelerations ẍ, ÿ (m/s²), φ̈ (rad/s²)
  const double* drift = nullptr;  // drift ratios of the storey below: x, y at the CM, then x, y at each corner
  std::span<const model::Point2> contact_vertices;  // at rest (m), in outline-number order
  model::Point2 centre;                             // the CM at rest (m)
};

struct HistoryQuantity {
  enum class Per { slab, contact_vertex, corner };
  std::string_view name;  // e.g. "u", "vtx{n}_dx", "c{n}_drift_x"
  std::string_view unit;  // "m", "rad", "mps2", "radps2"; empty: a ratio
  Per per = Per::slab;
  std::string_view description;  // one line
  /// The value at `slab`; `k`: the 0-based index of the vertex or corner (0 for a slab quantity).
  double (*value)(const SlabSample& slab, std::size_t k) = nullptr;

  /// The column suffix after `B{b}_f{f}_` for vertex or corner number `n` (1-based; 0: `{n}`
  /// stays, the pattern the docs print).
  std::string column(int n = 0) const;
};

/// In column order: u, v, phi, vtx{n}_dx, ax_abs, ay_abs, phi_ddot, drift_x, drift_y,
/// c{n}_drift_x, c{n}_drift_y, vtx{n}_dy.
const std::vector<HistoryQuantity>& history_quantities();

/// Calls `visit(quantity, k)` for each column of one slab, in column order: `contact_vertices`
/// and `corners` are how many of each the slab has.
template <class Visit>
void for_each_slab_column(std::size_t contact_vertices, std::size_t corners, Visit&& visit) {
  const std::vector<HistoryQuantity>& quantities = history_quantities();
  for (std::size_t first = 0; first < quantities.size();) {
    std::size_t last = first + 1;  // [first, last): a run of quantities of one kind
    while (last < quantities.size() && quantities[last].per == quantities[first].per &&
           quantities[first].per != HistoryQuantity::Per::slab) {
      ++last;
    }
    const HistoryQuantity::Per per = quantities[first].per;
    const std::size_t count = per == HistoryQuantity::Per::slab             ? 1
                              : per == HistoryQuantity::Per::contact_vertex ? contact_vertices
                                                                            : corners;
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t j = first; j < last; ++j) visit(quantities[j], k);
    }
    first = last;
  }
}

}  // namespace pounding::solvers
