#pragma once
// Slab-to-column contact (docs/model.md §6b): a slab of one building at an elevation between two
// floors of the other meets that building's facade columns. Each column is a fixed–fixed member
// between rigid floors: its deflected shape under the floors' motion is the cubic with zero end
// slopes, the contact force is shared between its floors by the same shape (virtual work), and
// its local flexibility under the point load acts in series with the contact law.
// Units: m, kN, kPa.

#include <array>
#include <vector>

#include "pounding/contact/candidates.hpp"
#include "pounding/model/building.hpp"

namespace pounding::contact {

/// The weights (N₁, N₂) of the column's lower and upper floor at height ratio ξ: the cubic with
/// zero end slopes, N₁ = 1 − 3ξ² + 2ξ³, N₂ = 3ξ² − 2ξ³ (N₁ + N₂ = 1). @pre 0 ≤ ξ ≤ 1.
std::array<double, 2> column_shape(double height_ratio);

/// The local flexibility (m/kN) of a column fixed at both ends, of length L, under a point load at
/// a = ξL along the unit plan direction `normal`: δ/P = a³b³/(3 E L³) (n_x²/I_x + n_y²/I_y),
/// b = L − a, I_x = h b_sec³/12 (bending along x), I_y = b_sec h³/12. Only the member's own section
/// and E count (a storey's frame factor describes its beams, not the struck column).
/// @pre E > 0, L > 0, 0 < ξ < 1, column sides > 0, |normal| = 1.
double column_flexibility(const model::Column& column, double elastic_modulus_kPa, double length_m, double height_ratio,
                          const model::Point2& normal);

/// What a point load P at ξ does to a fixed–fixed member of length L (signs dropped): the end
/// shears P b²(3a + b)/L³ and P a²(a + 3b)/L³, the end moments P a b²/L² and P a² b/L², and the
/// moment under the load 2 P a² b²/L³. Reports the larger shear and the largest moment.
struct ColumnDemand {
  double shear_kN = 0.0;
  double moment_kNm = 0.0;
};
/// @pre L > 0, 0 < ξ < 1.
ColumnDemand column_demand(double force_kN, double length_m, double height_ratio);

/// A floor of one building between two floors of the other (neither within `tolerance_m`), below
/// that building's roof: it faces the columns of `storey` (1-based; from floor storey − 1, or the
/// ground, to floor storey) at height ratio ξ.
struct ColumnLevel {
  int slab_building = 0;  // 0 or 1
  int slab_floor = 1;     // 1-based
  double elevation_m = 0.0;
  int storey = 1;  // of the other building
  double storey_height_m = 0.0;
  double height_ratio = 0.0;
};

/// Every such floor of either building, building 1's first, lowest first, given each building's
/// floor elevations (ascending, m). @pre 0 < tolerance_m < half of every storey height.
std::vector<ColumnLevel> column_levels(const std::array<std::vector<double>, 2>& elevations, double tolerance_m);

/// A column on a facade of its building that faces the other building: the column (0-based in
/// its list) and its contact point, its centre projected onto that slab edge (the column is taken
/// flush with the facade).
struct FacadeColumn {
  std::size_t column = 0;
  model::Point2 point;
};

/// The columns of `own` whose centre lies within half its larger section side of an edge of
/// `own`'s slab that faces `other`'s slab, projecting onto that edge: one point per such edge (a
/// column near a corner stands on both faces; a column centred on the corner gives it once).
std::vector<FacadeColumn> facade_columns(const model::BuildingDefinition& own, const model::Polygon& other);

/// The slab-to-column candidates: on each column level, every facade column point of the column
/// building within reach (within_reach) of an edge of the slab building's outline that faces it.
/// Candidate::level is 0 and `floors` holds the slab's floor and the column's upper floor.
/// @pre both buildings use columns wherever `levels` needs them (the scene refuses storeys given
///   as matrices there) and their outlines are counter-clockwise.
std::vector<Candidate> find_column_candidates(const std::array<const model::BuildingDefinition*, 2>& buildings,
                                              const std::vector<ColumnLevel>& levels, const CandidateOptions& options);

}  // namespace pounding::contact
