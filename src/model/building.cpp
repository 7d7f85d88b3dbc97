#include "pounding/model/building.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <utility>
#include <fmt/format.h>

#include "pounding/input_error.hpp"
#include "pounding/model/modal.hpp"

namespace pounding::model {
namespace {

// The ranges of HystereticLaw's parameters (hysteresis_specs()' rows).
constexpr Range kYieldDriftRatio{0.0, 0.05, "", true};
constexpr Range kYieldDrift{0.0, 1.0, "m", true};
constexpr Range kYieldShear{0.0, 1e9, "kN", true};
constexpr Range kHardeningRatio{0.0, 1.0, "", false, "[0, 1)"};
constexpr Range kBoucWenA{0.0, 10.0, "", true};
constexpr Range kBoucWenBeta{0.0, 10.0, "", true};
constexpr Range kBoucWenGamma{-10.0, 10.0};
constexpr Range kBoucWenN{1.0, 50.0};
constexpr Range kImkDrift{0.0, 10.0, "m", true};
constexpr Range kImkCapRatio{1.0, 10.0};
constexpr Range kImkResidualRatio{0.0, 1.0};
constexpr Range kImkLamda{0.0, 1e6, "m"};
constexpr Range kImkExponent{0.0, 10.0, "", true};
constexpr Range kImkRate{0.0, 1.0, "", true};
constexpr Range kImkKappa{0.0, 1.0};

std::string indexed(const char* key, std::size_t index) { return fmt::format("{}[{}]", key, index + 1); }

// Physical ranges (docs/scene-format.md lists each next to its key). Beyond them a value is a
// typo or a unit mistake, and the modal analysis or the time step it implies is meaningless.
constexpr double kMaxPlanCoordinate_m = 10'000.0;
constexpr Range kPolarMoment{0.1, 1e14, "t·m²"};
constexpr Range kYoungsModulus{1e6, 1e9, "kPa"};
constexpr Range kFrameFactor{1e-4, 10.0, "", true};
constexpr Range kTargetPeriod{0.02, 20.0, "s"};
constexpr double kMaxStoreyStiffness = 1e16;        // torsional entries reach k·r², 1e12 kN/m · (100 m)²
constexpr double kMinCentreOfMassInset_m = 1e-3;    // a CM on the slab's edge is a typo
constexpr double kColumnOutsideTolerance_m = 1e-6;  // columns on the slab's edge are usual
constexpr double kRepeatedColumnDistance_m = 1e-6;  // closer columns are one column given twice

double distance_to_boundary(const Polygon& slab, const Point2& p) {
  double distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < slab.size(); ++i) {
    const Point2& a = slab.vertex(i);
    const Point2 edge = slab.edge_end(i) - a;
    const double s = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    distance = std::min(distance, (a + s * edge - p).norm());
  }
  return distance;
}

std::string point_text(const Point2& p) { return fmt::format("[{}, {}]", p.x(), p.y()); }

void validate_slab(const BuildingDefinition& b) {
  if (b.slab.size() < 3) {
    throw InputError("slab", fmt::format("{} vertices", b.slab.size()), "a slab needs at least 3 vertices");
  }
  if (b.slab.size() > kMaxSlabVertices) {
    throw InputError("slab", fmt::format("{} vertices", b.slab.size()),
                     fmt::format("a slab may have at most {} vertices", kMaxSlabVertices));
  }
  for (std::size_t i = 0; i < b.slab.size(); ++i) {
    if (!(b.slab.vertex(i).cwiseAbs().maxCoeff() <= kMaxPlanCoordinate_m)) {  // NaN fails too
      throw InputError(indexed("slab", i), point_text(b.slab.vertex(i)),
                       fmt::format("coordinates must lie in [-{0}, {0}] m", kMaxPlanCoordinate_m));
    }
  }
  if (!b.slab.is_simple()) {
    throw InputError("slab", "", "the polygon is not simple (edges cross, touch or repeat a vertex)");
  }
  if (b.slab.signed_area() <= 0.0) {
    throw InputError("slab", "", "vertices must be listed counter-clockwise (the signed area is negative)");
  }
  if (!b.slab.contains(b.centre_of_mass)) {
    throw InputError("centre_of_mass", point_text(b.centre_of_mass), "lies outside the slab");
  }
  if (!b.slab.contains_strictly(b.centre_of_mass) ||
      distance_to_boundary(b.slab, b.centre_of_mass) < kMinCentreOfMassInset_m) {
    throw InputError("centre_of_mass", point_text(b.centre_of_mass),
                     fmt::format("lies on the slab's edge; it must be at least {} m inside", kMinCentreOfMassInset_m));
  }
}

void validate_per_floor(const std::vector<double>& values, const char* key, int storeys, const Range& range,
                        const char* unit = "floor") {
  if (values.size() != static_cast<std::size_t>(storeys)) {
    throw InputError(key, fmt::format("{} values", values.size()),
                     fmt::format("needs one value per {} ({})", unit, storeys));
  }
  for (std::size_t i = 0; i < values.size(); ++i) require_range(indexed(key, i), values[i], range);
}

/// Two columns at one position (a grid line or a list entry repeated) would count one column's
/// stiffness twice without a word: refused, naming both. Sorted by x, each column is compared with
/// the ones after it whose x lies within the tolerance.
void refuse_repeated_columns(const std::vector<Column>& columns) {
  std::vector<std::size_t> order(columns.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&columns](std::size_t a, std::size_t b) {
    return std::make_pair(columns[a].position_m.x(), a) < std::make_pair(columns[b].position_m.x(), b);
  });
  const auto name = [&columns](std::size_t i) {
    return columns[i].key.empty() ? indexed("columns", i) : columns[i].key;
  };
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Point2& p = columns[order[k]].position_m;
    for (std::size_t j = k + 1; j < order.size(); ++j) {
      const Point2& q = columns[order[j]].position_m;
      if (q.x() - p.x() > kRepeatedColumnDistance_m) break;
      if ((q - p).norm() > kRepeatedColumnDistance_m) continue;
      const auto [first, second] = std::minmax(order[k], order[j]);  // the later one is the repeat
      throw InputError(
          name(second), point_text(columns[second].position_m),
          fmt::format("stands where {} stands: a column given twice counts its stiffness twice", name(first)));
    }
  }
}

void validate_shear_failure(const BuildingDefinition& b) {
  const std::string& choice = b.column_shear_failure;
  if (choice != "report" && choice != "lose-stiffness") {
    throw InputError("column_shear_failure", fmt::format("\"{}\"", choice),
                     "expected \"report\" or \"lose-stiffness\"");
  }
  if (choice == "report") return;
  if (b.hysteresis.kind != HystereticLaw::Kind::bilinear && !b.hysteresis.degrades()) {
    throw InputError(
        "column_shear_failure", "\"lose-stiffness\"",
        "needs bilinear, imk-peak-oriented or imk-pinching columns ([building.hysteresis] law): the columns' sway "
        "shear is checked where they yield");
  }
  if (!has_shear_capacity(b)) {
    throw InputError("column_shear_failure", "\"lose-stiffness\"",
                     "needs a shear capacity: column_shear_capacity_kN, [building.shear_capacity] or a column's "
                     "shear_capacity_kN");
  }
}

/// A column's own key as the scene gave it: its grid's, `column_grid[g].<key>`, or its entry's,
/// `columns[i].<key>`.
std::string own_key(const Column& c, const char* key) { return c.key.substr(0, c.key.find(' ')) + "." + key; }
std::string own_strength_key(const Column& c) { return own_key(c, "yield_force_kN"); }

void validate_columns(const BuildingDefinition& b) {
  if (b.columns.empty()) {
    throw InputError("columns", "none", "give columns (or column_grid), or storey_stiffness");
  }
  if (b.columns.size() > kMaxColumns) {
    throw InputError("columns", fmt::format("{} columns", b.columns.size()),
                     fmt::format("a storey may have at most {} columns", kMaxColumns));
  }
  for (std::size_t i = 0; i < b.columns.size(); ++i) {
    const Column& c = b.columns[i];
    const std::string key = c.key.empty() ? indexed("columns", i) : c.key;
    if (!c.position_m.allFinite()) throw InputError(key, point_text(c.position_m), "position must be finite");
    if (!b.slab.contains(c.position_m, kColumnOutsideTolerance_m)) {
      throw InputError(key, point_text(c.position_m), "the column stands outside its slab");
    }
    require_range(key + ".b", c.b_m, kColumnSize);
    require_range(key + ".h", c.h_m, kColumnSize);
  }
  refuse_repeated_columns(b.columns);
  for (const Column& c : b.columns) {  // a grid's own yield forces (each of its columns holds them)
    if (!c.yield_force_kN.empty())
      validate_per_floor(c.yield_force_kN, own_strength_key(c).c_str(), b.storeys, kColumnYieldForce, "storey");
    if (!c.shear_capacity_kN.empty()) {
      validate_per_floor(c.shear_capacity_kN, own_key(c, "shear_capacity_kN").c_str(), b.storeys, kColumnShearCapacity,
                         "storey");
    }
  }
  require_range("E_kPa", b.E_kPa, kYoungsModulus);
  if (b.slab_thickness_m) require_range("slab_thickness_m", *b.slab_thickness_m, kSlabThickness);
  if (!b.column_shear_capacity_kN.empty()) {
    validate_per_floor(b.column_shear_capacity_kN, "column_shear_capacity_kN", b.storeys, kColumnShearCapacity,
                       "storey");
  }
  validate_shear_failure(b);
  if (!b.column_shear_capacity_kN.empty() && b.shear_capacity) {
    throw InputError("shear_capacity", "given with column_shear_capacity_kN",
                     "give the columns' shear capacity one way: column_shear_capacity_kN or [building.shear_capacity]");
  }
  if (b.target_period_s) {
    require_range("target_period_s", *b.target_period_s, kTargetPeriod);
  } else {
    require_range("frame_factor", b.frame_factor, kFrameFactor);
  }
}

void validate_storey_matrices(const BuildingDefinition& b) {
  if (b.storey_stiffness.size() != static_cast<std::size_t>(b.storeys)) {
    throw InputError("storey_stiffness", fmt::format("{} matrices", b.storey_stiffness.size()),
                     fmt::format("needs one 3x3 matrix per storey ({})", b.storeys));
  }
  for (std::size_t i = 0; i < b.storey_stiffness.size(); ++i) {
    const Eigen::Matrix3d& k = b.storey_stiffness[i];
    const std::string key = indexed("storey_stiffness", i);
    if (!(k.cwiseAbs().maxCoeff() <= kMaxStoreyStiffness)) {  // NaN fails too
      throw InputError(key, format_value(k.cwiseAbs().maxCoeff()),
                       fmt::format("entries must lie in [-{0}, {0}] (kN/m, kN, kN·m/rad)", kMaxStoreyStiffness));
    }
    if (!k.isApprox(k.transpose(), 1e-12)) throw InputError(key, "", "must be symmetric");
    if (Eigen::LLT<Eigen::Matrix3d>(k).info() != Eigen::Success) {
      throw InputError(key, "", "must be positive definite");
    }
  }
}

/// Bouc–Wen's shape (each within its row's range, hysteresis_specs()): −β < γ ≤ β keeps every
/// loop dissipative and z bounded; A = 1 keeps the initial stiffness the k that K, the modes, the
/// damping and the step bounds use.
void validate_bouc_wen(const HystereticLaw& law) {
  if (law.bouc_wen_a != 1.0) {
    throw InputError("hysteresis.a", format_value(law.bouc_wen_a),
                     "must be 1: the columns' initial stiffness would become alpha k + (1 - alpha) k A, while K, "
                     "the modes, the Rayleigh damping and the step bounds use k (scale the yield drift instead)");
  }
  if (!(law.bouc_wen_gamma > -law.bouc_wen_beta && law.bouc_wen_gamma <= law.bouc_wen_beta)) {
    throw InputError("hysteresis.gamma", format_value(law.bouc_wen_gamma),
                     fmt::format("must lie in (-beta, beta] = ({0:g}, {1:g}]: with |gamma| > beta a loop returns "
                                 "energy, and at gamma = -beta z grows without bound (the column never yields)",
                                 -law.bouc_wen_beta, law.bouc_wen_beta));
  }
}

/// A drift of 10 % of a storey ends a run as a collapse (solvers::kCollapseDriftRatio): a column
/// must yield well before, at most at 5 % of its storey. One value for every storey is named
/// without an index and measured against the lowest storey.
void refuse_collapse_before_yield(const std::vector<double>& yield_drift_m, const std::vector<double>& heights_m) {
  const bool uniform =
      std::adjacent_find(yield_drift_m.begin(), yield_drift_m.end(), std::not_equal_to<>()) == yield_drift_m.end();
  if (uniform) {
    const double lowest_m = *std::min_element(heights_m.begin(), heights_m.end());
    if (yield_drift_m.front() <= 0.05 * lowest_m) return;
    throw InputError("hysteresis.yield_drift_m", format_value(yield_drift_m.front()),
                     fmt::format("must be at most 5 % of the lowest storey ({:g} m): a drift of 10 % of a storey "
                                 "ends a run as a collapse",
                                 lowest_m));
  }
  for (std::size_t j = 0; j < yield_drift_m.size(); ++j) {
    if (yield_drift_m[j] <= 0.05 * heights_m[j]) continue;
    throw InputError(indexed("hysteresis.yield_drift_m", j), format_value(yield_drift_m[j]),
                     fmt::format("must be at most 5 % of storey {}'s height ({:g} m): a drift of 10 % of a storey "
                                 "ends a run as a collapse",
                                 j + 1, heights_m[j]));
  }
}

/// IMK's required keys (their ranges are their rows', hysteresis_specs()).
void validate_imk(const BuildingDefinition& b) {
  const HystereticLaw& law = b.hysteresis;
  const auto require = [&law](bool given, const char* key) {
    if (!given) throw InputError(key, "missing", fmt::format("law \"{}\" needs it", to_string(law.kind)));
  };
  require(!law.imk_up_pos_m.empty(), "hysteresis.Up_pos");
  require(!law.imk_upc_pos_m.empty(), "hysteresis.Upc_pos");
  require(law.imk_fmax_fy_pos.has_value(), "hysteresis.FmaxFy_pos");
  if (law.kind != HystereticLaw::Kind::imk_pinching) return;
  require(law.imk_kappa_f.has_value(), "hysteresis.kappaF");
  require(law.imk_kappa_d.has_value(), "hysteresis.kappaD");
}

/// Storeys given as matrices yield as springs along x and y (storey_springs()), which K must split
/// into without a coupling K_uv between them.
void refuse_coupled_storey_springs(const BuildingDefinition& b) {
  for (std::size_t j = 0; j < b.storey_stiffness.size(); ++j) {
    const Eigen::Matrix3d& k = b.storey_stiffness[j];
    if (std::abs(k(0, 1)) <= 1e-12 * std::sqrt(k(0, 0) * k(1, 1))) continue;
    throw InputError(indexed("storey_stiffness", j), fmt::format("K_uv = {:g} kN/m", k(0, 1)),
                     "a storey that yields (hysteresis.law) is a storey spring along x and one along y, so its "
                     "matrix must not couple u and v (K_uv = 0; docs/model.md §2a, \"Storey springs\")");
  }
}

/// The first column with a yield force of its own, if any.
const Column* column_with_own_strength(const BuildingDefinition& b) {
  for (const Column& c : b.columns)
    if (!c.yield_force_kN.empty()) return &c;
  return nullptr;
}

void validate_hysteresis(const BuildingDefinition& b) {
  const HystereticLaw& law = b.hysteresis;
  const Column* own = column_with_own_strength(b);
  if (!law.yields() && b.flexural_strength) {
    throw InputError("flexural_strength", "given", "needs yielding columns ([building.hysteresis] law)");
  }
  if (!law.yields() && own != nullptr) {
    throw InputError(own_strength_key(*own), format_value(own->yield_force_kN.front()),
                     "needs yielding columns ([building.hysteresis] law)");
  }
  if (!law.yields()) return;
  if (!b.uses_columns()) refuse_coupled_storey_springs(b);
  std::vector<std::string> strengths;
  if (!law.yield_drift_ratio.empty()) strengths.push_back("yield_drift_ratio");
  if (!law.yield_drift_m.empty()) strengths.push_back("yield_drift_m");
  if (!law.yield_shear_kN.empty()) strengths.push_back("yield_shear_kN");
  const bool every_column_own = every_column_has_own_strength(b);
  if (b.flexural_strength && !strengths.empty()) {
    throw InputError("hysteresis." + strengths[0], "given with [building.flexural_strength]",
                     "give the columns' strength one way: the section's ([building.flexural_strength]) or the "
                     "storey's (yield_drift_ratio, yield_drift_m or yield_shear_kN)");
  }
  if (strengths.size() != 1 && !(strengths.empty() && (every_column_own || b.flexural_strength))) {
    throw InputError(
        "hysteresis." + (strengths.empty() ? std::string("yield_drift_ratio") : strengths[0]),
        strengths.empty() ? "missing" : "given with " + strengths[1],
        "give one of yield_drift_ratio, yield_drift_m and yield_shear_kN (or [building.flexural_strength], "
        "or every column its yield_force_kN)");
  }
  for (const HysteresisSpec& spec : hysteresis_specs()) {
    if (!is_per_storey(spec)) continue;
    const auto& values = law.*std::get<std::vector<double> HystereticLaw::*>(spec.member);
    if (!values.empty() && values.size() != static_cast<std::size_t>(b.storeys)) {
      throw InputError(fmt::format("hysteresis.{}", spec.key), fmt::format("{} values", values.size()),
                       fmt::format("needs one value per storey ({})", b.storeys));
    }
  }
  validate_keys(law, hysteresis_specs(), "hysteresis");
  if (!law.yield_drift_m.empty()) refuse_collapse_before_yield(law.yield_drift_m, b.storey_height_m);
  if (law.is_smooth()) validate_bouc_wen(law);
  if (law.degrades()) validate_imk(b);
}

void validate_damping(const BuildingDefinition& b) {
  const double ratio = b.damping.ratio;
  if (!(ratio >= 0.0 && ratio < 1.0)) {
    throw InputError("damping.ratio", format_value(ratio), "must lie in [0, 1)");
  }
  const auto [i, j] = b.damping.modes;
  const int modes = 3 * b.storeys;
  for (int mode : {i, j}) {
    if (mode < 1 || mode > modes) {
      throw InputError("damping.modes", fmt::format("[{}, {}]", i, j),
                       fmt::format("modes are numbered 1..{} (3 per floor)", modes));
    }
  }
  if (i == j) {
    throw InputError("damping.modes", fmt::format("[{}, {}]", i, j), "the two modes must differ");
  }
}

Eigen::VectorXd assemble_mass(const BuildingDefinition& b) {
  Eigen::VectorXd diagonal(3 * b.storeys);
  for (int floor = 0; floor < b.storeys; ++floor) {
    diagonal.segment<3>(3 * floor) << b.mass_t[floor], b.mass_t[floor], b.polar_moment_tm2[floor];
  }
  return diagonal;
}

Eigen::MatrixXd column_building_stiffness(const BuildingDefinition& b, double frame_factor) {
  return assemble_stiffness(column_storey_matrices(b, frame_factor));
}

void require_positive_definite(const Eigen::MatrixXd& stiffness, const BuildingDefinition& b) {
  if (Eigen::LLT<Eigen::MatrixXd>(stiffness).info() == Eigen::Success) return;
  if (b.p_delta) {
    throw InputError("p_delta", "true",
                     "the gravity load makes the building unstable: its P-Δ stiffness exceeds the storeys' own");
  }
  if (b.uses_columns()) {
    throw InputError("columns", fmt::format("{} columns", b.columns.size()),
                     "the storey stiffness is singular: columns that all stand at one point "
                     "cannot resist torsion");
  }
  throw InputError("storey_stiffness", "", "the assembled stiffness is not positive definite");
}

}  // namespace

void BuildingDefinition::validate() const {
  if (name.empty()) throw InputError("name", "\"\"", "must not be empty");
  if (storeys < 1 || storeys > kMaxStoreys) {
    throw InputError("storeys", std::to_string(storeys), fmt::format("must lie in [1, {}]", kMaxStoreys));
  }
  // Heights are needed even with storey matrices given directly: they place the floors, and
  // only floors at a common elevation can touch.
  validate_per_floor(storey_height_m, "storey_height_m", storeys, kStoreyHeightRange, "storey");
  validate_slab(*this);
  validate_per_floor(mass_t, "mass_t", storeys, kFloorMass);
  validate_per_floor(polar_moment_tm2, "polar_moment_tm2", storeys, kPolarMoment);
  if (uses_columns()) {
    validate_columns(*this);
  } else {
    validate_storey_matrices(*this);
  }
  validate_damping(*this);
  validate_hysteresis(*this);
}

std::span<const std::string_view> hysteretic_law_names() {
  static constexpr std::array<std::string_view, 5> kNames{"elastic", "bilinear", "bouc-wen", "imk-peak-oriented",
                                                          "imk-pinching"};
  return kNames;
}

/// A row of IMK's (OpenSees' name as the key), for both IMK laws, or for `laws`.
template <typename Member>
HysteresisSpec imk_row(std::string_view key, Member member, const Range& range, std::string_view description,
                       std::string_view default_note = {}, std::string_view details = {},
                       std::vector<std::string_view> laws = {"imk-peak-oriented", "imk-pinching"}) {
  return {.key = key,
          .member = member,
          .range = range,
          .description = description,
          .details = details,
          .default_note = default_note,
          .applies_to = std::move(laws)};
}

std::span<const HysteresisSpec> hysteresis_specs() {
  static const std::vector<std::string_view> yielding{"bilinear", "bouc-wen", "imk-peak-oriented", "imk-pinching"};
  static const std::vector<std::string_view> hardening{"bilinear", "bouc-wen"};
  static const std::vector<std::string_view> smooth{"bouc-wen"};
  static const std::vector<HysteresisSpec> kSpecs{
      {.key = "yield_drift_ratio",
       .member = &HystereticLaw::yield_drift_ratio,
       .range = kYieldDriftRatio,
       .description = "yield drift as a fraction of the storey height (0.005 = 0.5 %)",
       .details = "a list gives each storey its own, storey 1 first",
       .default_note = "one of these three",
       .applies_to = yielding},
      {.key = "yield_drift_m",
       .member = &HystereticLaw::yield_drift_m,
       .range = kYieldDrift,
       .description = "yield drift (m), at most 5 % of its storey",
       .details = "one number holds for every storey (a drift of 10 % of a storey ends a run as a collapse)",
       .default_note = "one of these three",
       .applies_to = yielding},
      {.key = "yield_shear_kN",
       .member = &HystereticLaw::yield_shear_kN,
       .range = kYieldShear,
       .description = "the storey yield shear V (kN)",
       .details = "every column of the storey yields at d_y = V / Σ k of the storey's columns along x (and along "
                  "y), so that the columns yield together in a translation, each at its share k d_y "
                  "([model.md](model.md) §2a). A V that puts d_y above 5 % of the storey is refused",
       .default_note = "one of these three",
       .applies_to = yielding},
      {.key = "hardening_ratio",
       .member = &HystereticLaw::hardening_ratio,
       .range = kHardeningRatio,
       .description = "α: post-yield over initial stiffness (0: elastic–perfectly plastic)",
       .applies_to = hardening},
      {.key = "a",
       .member = &HystereticLaw::bouc_wen_a,
       .range = kBoucWenA,
       .description = "A, the hysteretic part's initial stiffness over (1 − α) k",
       .details = "only 1 is accepted, since K, the modes, the damping and the step bounds use the columns' "
                  "initial stiffness k (scale the yield drift instead)",
       .applies_to = smooth},
      {.key = "beta",
       .member = &HystereticLaw::bouc_wen_beta,
       .range = kBoucWenBeta,
       .description = "β",
       .applies_to = smooth},
      {.key = "gamma",
       .member = &HystereticLaw::bouc_wen_gamma,
       .range = kBoucWenGamma,
       .description = "γ, in (−β, β]",
       .details = "with β + γ = 1 the force saturates at the bilinear law's; \\|γ\\| ≤ β keeps every loop "
                  "dissipative and γ > −β keeps z bounded (refused otherwise)",
       .applies_to = smooth},
      {.key = "n",
       .member = &HystereticLaw::bouc_wen_n,
       .range = kBoucWenN,
       .description = "n, the sharpness of the transition (n → ∞: the bilinear law)",
       .applies_to = smooth},
      imk_row("Up_pos", &HystereticLaw::imk_up_pos_m, kImkDrift,
              "U_p: the drift (m) from yield to the cap, where F reaches F_max", "required",
              "a list gives each storey its own, storey 1 first"),
      imk_row("Upc_pos", &HystereticLaw::imk_upc_pos_m, kImkDrift,
              "U_pc: the drift (m) from the cap to zero force along the post-capping slope", "required"),
      imk_row("Uu_pos", &HystereticLaw::imk_uu_pos_m, kImkDrift,
              "U_u: the ultimate drift (m); reached moving out, the column fails", "none"),
      imk_row("FmaxFy_pos", &HystereticLaw::imk_fmax_fy_pos, kImkCapRatio, "F_max / F_y, the cap's force", "required",
              "U_p must exceed (F_max/F_y − 1) d_y, so that the post-yield slope is below k"),
      imk_row("FresFy_pos", &HystereticLaw::imk_fres_fy_pos, kImkResidualRatio, "F_res / F_y, the residual strength",
              {}, "0: the column fails at the end of the post-capping branch"),
      imk_row("Up_neg", &HystereticLaw::imk_up_neg_m, kImkDrift, "U_p of the negative side (m, positive)", "Up_pos"),
      imk_row("Upc_neg", &HystereticLaw::imk_upc_neg_m, kImkDrift, "U_pc of the negative side (m, positive)",
              "Upc_pos"),
      imk_row("Uu_neg", &HystereticLaw::imk_uu_neg_m, kImkDrift, "U_u of the negative side (m, positive)", "Uu_pos"),
      imk_row("FmaxFy_neg", &HystereticLaw::imk_fmax_fy_neg, kImkCapRatio, "F_max / F_y of the negative side",
              "FmaxFy_pos"),
      imk_row("FresFy_neg", &HystereticLaw::imk_fres_fy_neg, kImkResidualRatio, "F_res / F_y of the negative side",
              "FresFy_pos"),
      imk_row("Lamda_S", &HystereticLaw::imk_lamda_s_m, kImkLamda,
              "Λ_S (m): basic strength deterioration, reference energy E_t = Λ_S F_y", {},
              "0 turns the mode off (as every Lamda_*)"),
      imk_row("Lamda_C", &HystereticLaw::imk_lamda_c_m, kImkLamda, "Λ_C (m): post-capping strength deterioration"),
      imk_row("Lamda_A", &HystereticLaw::imk_lamda_a_m, kImkLamda,
              "Λ_A (m): accelerated reloading stiffness deterioration"),
      imk_row("Lamda_K", &HystereticLaw::imk_lamda_k_m, kImkLamda, "Λ_K (m): unloading stiffness deterioration"),
      imk_row("c_S", &HystereticLaw::imk_c_s, kImkExponent, "c_S, the exponent of β_S"),
      imk_row("c_C", &HystereticLaw::imk_c_c, kImkExponent, "c_C, the exponent of β_C"),
      imk_row("c_A", &HystereticLaw::imk_c_a, kImkExponent, "c_A, the exponent of β_A"),
      imk_row("c_K", &HystereticLaw::imk_c_k, kImkExponent, "c_K, the exponent of β_K"),
      imk_row("D_pos", &HystereticLaw::imk_d_pos, kImkRate,
              "D⁺, the rate of cyclic deterioration on the positive side"),
      imk_row("D_neg", &HystereticLaw::imk_d_neg, kImkRate,
              "D⁻, the rate of cyclic deterioration on the negative side"),
      imk_row("kappaF", &HystereticLaw::imk_kappa_f, kImkKappa,
              "κ_F: the pinching point's force over that of the line to the global peak", "required",
              "1 with kappaD = 0: the pinching point on the line to the global peak", {"imk-pinching"}),
      imk_row("kappaD", &HystereticLaw::imk_kappa_d, kImkKappa,
              "κ_D: the pinching point's drift, (1 − κ_D) × the global peak's plastic drift", "required", {},
              {"imk-pinching"}),
  };
  return kSpecs;
}

ImkSideKeys imk_side(const HystereticLaw& law, int storey, bool positive) {
  const auto at = [storey](const std::vector<double>& own, const std::vector<double>& fallback, double none) {
    const std::vector<double>& values = own.empty() ? fallback : own;
    return values.empty() ? none : values.at(static_cast<std::size_t>(storey - 1));
  };
  const double none = std::numeric_limits<double>::infinity();
  if (positive) {
    return {.plastic_drift_m = at(law.imk_up_pos_m, {}, none),
            .post_cap_drift_m = at(law.imk_upc_pos_m, {}, none),
            .ultimate_drift_m = at(law.imk_uu_pos_m, {}, none),
            .cap_ratio = *law.imk_fmax_fy_pos,
            .residual_ratio = law.imk_fres_fy_pos,
            .rate = law.imk_d_pos};
  }
  return {.plastic_drift_m = at(law.imk_up_neg_m, law.imk_up_pos_m, none),
          .post_cap_drift_m = at(law.imk_upc_neg_m, law.imk_upc_pos_m, none),
          .ultimate_drift_m = at(law.imk_uu_neg_m, law.imk_uu_pos_m, none),
          .cap_ratio = law.imk_fmax_fy_neg.value_or(*law.imk_fmax_fy_pos),
          .residual_ratio = law.imk_fres_fy_neg.value_or(law.imk_fres_fy_pos),
          .rate = law.imk_d_neg};
}

const char* to_string(HystereticLaw::Kind kind) {
  return hysteretic_law_names()[static_cast<std::size_t>(kind)].data();  // literals: NUL-terminated
}

double uniform_polar_moment(const Polygon& slab, double mass_t) {
  return mass_t * slab.polar_area_moment_about_centroid() / slab.signed_area();
}

Eigen::Vector2d column_stiffness(const Column& column, double elastic_modulus_kPa, double storey_height_m,
                                 double frame_factor) {
  const double b = column.b_m, h = column.h_m;
  const double bending = 12.0 * elastic_modulus_kPa / std::pow(storey_height_m, 3);
  return frame_factor * bending * Eigen::Vector2d(h * b * b * b / 12.0, b * h * h * h / 12.0);
}

Eigen::Matrix3d storey_stiffness_from_columns(const std::vector<Column>& columns, const Point2& centre_of_mass,
                                              double elastic_modulus_kPa, double storey_height_m, double frame_factor) {
  Eigen::Matrix3d storey = Eigen::Matrix3d::Zero();
  for (const Column& column : columns) {
    const Point2 arm = column.position_m - centre_of_mass;
    Eigen::Matrix<double, 2, 3> t;
    t << 1.0, 0.0, -arm.y(), 0.0, 1.0, arm.x();
    const Eigen::Vector2d k = column_stiffness(column, elastic_modulus_kPa, storey_height_m, frame_factor);
    storey += t.transpose() * k.asDiagonal() * t;
  }
  return storey;
}

std::vector<Eigen::Matrix3d> geometric_storey_matrices(const BuildingDefinition& b) {
  std::vector<Eigen::Matrix3d> storeys(static_cast<std::size_t>(b.storeys));
  double mass_above_t = 0.0, polar_above_tm2 = 0.0;
  for (int j = b.storeys; j >= 1; --j) {
    mass_above_t += b.mass_t[j - 1];
    polar_above_tm2 += b.polar_moment_tm2[j - 1];
    const double factor = -b.g_mps2 / b.storey_height_m[j - 1];
    storeys[j - 1] = (factor * Eigen::Vector3d(mass_above_t, mass_above_t, polar_above_tm2)).asDiagonal();
  }
  return storeys;
}

Eigen::MatrixXd assemble_stiffness(const std::vector<Eigen::Matrix3d>& storeys) {
  const int n = static_cast<int>(storeys.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int s = 0; s < n; ++s) {
    // Storey s + 1 joins floor s (the ground when s = 0) and floor s + 1.
    k.block<3, 3>(3 * s, 3 * s) += storeys[s];
    if (s == 0) continue;
    k.block<3, 3>(3 * (s - 1), 3 * (s - 1)) += storeys[s];
    k.block<3, 3>(3 * s, 3 * (s - 1)) -= storeys[s];
    k.block<3, 3>(3 * (s - 1), 3 * s) -= storeys[s];
  }
  return k;
}

std::vector<Eigen::Matrix3d> column_storey_matrices(const BuildingDefinition& b, double frame_factor) {
  std::vector<Eigen::Matrix3d> storeys;
  for (double height : b.storey_height_m) {
    storeys.push_back(storey_stiffness_from_columns(b.columns, b.centre_of_mass, b.E_kPa, height, frame_factor));
  }
  return storeys;
}

std::vector<double> floor_elevations(const BuildingDefinition& b) {
  std::vector<double> elevations;
  double z = 0.0;
  for (double height : b.storey_height_m) elevations.push_back(z += height);
  return elevations;
}

RayleighCoefficients fit_rayleigh(double omega_i, double omega_j, double ratio) {
  // ζ(ω) = a0/(2ω) + a1 ω/2 equal to `ratio` at both frequencies.
  const double sum = omega_i + omega_j;
  return {2.0 * ratio * omega_i * omega_j / sum, 2.0 * ratio / sum};
}

StoreySprings storey_springs(const BuildingDefinition& definition, int storey) {
  const Eigen::Matrix3d& k = definition.storey_stiffness.at(static_cast<std::size_t>(storey - 1));
  const double e_y = -k(0, 2) / k(0, 0), e_x = k(1, 2) / k(1, 1);
  return {.stiffness_kN_per_m = {k(0, 0), k(1, 1)}, .rows = {{{1.0, 0.0, -e_y}, {0.0, 1.0, e_x}}}};
}

double storey_column_stiffness(const Building& building, int storey, int direction) {
  const BuildingDefinition& d = building.definition;
  if (!d.uses_columns()) return storey_springs(d, storey).stiffness_kN_per_m[static_cast<std::size_t>(direction)];
  double sum_kN_per_m = 0.0;
  for (const Column& column : d.columns)
    sum_kN_per_m += column_stiffness(column, d.E_kPa, d.storey_height_m[storey - 1], building.frame_factor)[direction];
  return sum_kN_per_m;
}

double column_yield_drift_m(const Building& building, int storey, std::size_t column, int direction) {
  const BuildingDefinition& d = building.definition;
  const std::optional<double> force_kN = column_yield_force_kN(d, storey, column, direction);
  if (!force_kN) return column_yield_drift_m(building, storey, direction);
  const Column& c = d.columns.at(column);
  return *force_kN / column_stiffness(c, d.E_kPa, d.storey_height_m[storey - 1], building.frame_factor)[direction];
}

std::optional<double> column_yield_force_kN(const BuildingDefinition& definition, int storey, std::size_t column,
                                            int direction) {
  const Column& c = definition.columns.at(column);
  if (!c.yield_force_kN.empty()) return c.yield_force_kN.at(static_cast<std::size_t>(storey - 1));
  if (!definition.flexural_strength) return std::nullopt;
  return column_section_strength(definition, storey, column, direction).yield_force_kN;
}

double column_axial_load_kN(const BuildingDefinition& definition, int storey, std::optional<double> given) {
  if (given) return *given;
  double carried_t = 0.0;
  for (std::size_t floor = static_cast<std::size_t>(storey - 1); floor < definition.mass_t.size(); ++floor)
    carried_t += definition.mass_t[floor];
  return carried_t * (definition.g_mps2 / static_cast<double>(definition.columns.size()));
}

double slab_axial_stiffness_kN_per_m(const BuildingDefinition& definition, const Point2& direction) {
  const Point2 across(-direction.y(), direction.x());
  const auto extent_m = [&](const Point2& axis) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Point2& vertex : definition.slab.vertices()) {
      low = std::min(low, vertex.dot(axis));
      high = std::max(high, vertex.dot(axis));
    }
    return high - low;
  };
  return definition.E_kPa * definition.slab_thickness_m.value() * extent_m(across) / extent_m(direction);
}

namespace {

/// ACI 318-19 Table 22.2.2.4.3: the stress block's depth over the neutral axis' depth.
double stress_block_factor(double concrete_strength_MPa) {
  return std::clamp(0.85 - 0.05 * (concrete_strength_MPa - 28.0) / 7.0, 0.65, 0.85);
}

/// A rectangular section of two bar layers at its ultimate strain (N, mm, MPa): the stress block
/// 0.85 f'c over β₁ c and each layer's stress from the strain ε_cu (c − y)/c at its depth y,
/// bounded by ±f_y (compression positive).
struct TwoLayerSection {
  double depth_mm, width_mm, cover_mm, layer_area_mm2, steel_yield_MPa, concrete_MPa;
  static constexpr double kUltimateStrain = 0.003, kSteelModulus_MPa = 200'000.0;

  double block_mm(double axis_mm) const { return std::min(stress_block_factor(concrete_MPa) * axis_mm, depth_mm); }
  double layer_stress_MPa(double axis_mm, double layer_depth_mm) const {
    const double strain = kUltimateStrain * (axis_mm - layer_depth_mm) / axis_mm;
    return std::clamp(kSteelModulus_MPa * strain, -steel_yield_MPa, steel_yield_MPa);
  }
  /// The axial force the section carries (N, compression positive) with its neutral axis at c.
  double axial_N(double axis_mm) const {
    return 0.85 * concrete_MPa * block_mm(axis_mm) * width_mm +
           layer_area_mm2 * (layer_stress_MPa(axis_mm, cover_mm) + layer_stress_MPa(axis_mm, depth_mm - cover_mm));
  }
  /// The moment about the section's centre (N·mm) with its neutral axis at c.
  double moment_Nmm(double axis_mm) const {
    const double half_mm = depth_mm / 2.0, block = block_mm(axis_mm);
    return 0.85 * concrete_MPa * block * width_mm * (half_mm - block / 2.0) +
           layer_area_mm2 * (layer_stress_MPa(axis_mm, cover_mm) - layer_stress_MPa(axis_mm, depth_mm - cover_mm)) *
               (half_mm - cover_mm);
  }
  /// The neutral axis' depth at which the section carries `axial_N`: axial_N() rises with c, so
  /// bisection. @pre axial_N below the section's squash load.
  double axis_for_mm(double target_N) const {
    double low = 1e-9 * depth_mm, high = depth_mm;
    while (axial_N(high) < target_N && high < 1e6 * depth_mm) high *= 2.0;
    for (int i = 0; i < 200 && high - low > 1e-13 * high; ++i) {
      const double mid = 0.5 * (low + high);
      (axial_N(mid) < target_N ? low : high) = mid;
    }
    return 0.5 * (low + high);
  }
};

}  // namespace

SectionStrength column_section_strength(const BuildingDefinition& definition, int storey, std::size_t column,
                                        int direction) {
  const FlexuralStrengthFormula& f = definition.flexural_strength.value();
  const Column& c = definition.columns.at(column);
  // N, mm, MPa throughout; D along the sway, W across it.
  const double depth_mm = 1000.0 * (direction == 0 ? c.b_m : c.h_m);
  const double width_mm = 1000.0 * (direction == 0 ? c.h_m : c.b_m);
  const TwoLayerSection section{
      .depth_mm = depth_mm,
      .width_mm = width_mm,
      .cover_mm = f.cover_ratio * depth_mm,
      .layer_area_mm2 = 0.5 * f.longitudinal_ratio.at(static_cast<std::size_t>(storey - 1)) * depth_mm * width_mm,
      .steel_yield_MPa = f.steel_yield_strength_MPa,
      .concrete_MPa = f.concrete_strength_MPa};
  // Balanced: the tension layer just yields as the concrete reaches ε_cu.
  const double tension_depth_mm = depth_mm - section.cover_mm;
  const double balanced_axis_mm =
      TwoLayerSection::kUltimateStrain * tension_depth_mm /
      (TwoLayerSection::kUltimateStrain + f.steel_yield_strength_MPa / TwoLayerSection::kSteelModulus_MPa);
  SectionStrength strength;
  strength.axial_load_kN = column_axial_load_kN(definition, storey, f.axial_load_kN);
  strength.balanced_axial_load_kN = section.axial_N(balanced_axis_mm) / 1000.0;
  const double axis_mm = section.axis_for_mm(1000.0 * strength.axial_load_kN);
  strength.moment_kNm = section.moment_Nmm(axis_mm) / 1e6;
  strength.yield_force_kN =
      2.0 * strength.moment_kNm / definition.storey_height_m.at(static_cast<std::size_t>(storey - 1));
  return strength;
}

double column_yield_drift_m(const Building& building, int storey, int direction) {
  const HystereticLaw& law = building.definition.hysteresis;
  const std::size_t j = storey - 1;
  if (!law.yield_drift_m.empty()) return law.yield_drift_m[j];
  if (!law.yield_drift_ratio.empty()) return law.yield_drift_ratio[j] * building.definition.storey_height_m[j];
  return law.yield_shear_kN.at(j) / storey_column_stiffness(building, storey, direction);
}

std::string column_key(const BuildingDefinition& definition, std::size_t column) {
  const std::string& key = definition.columns.at(column).key;
  return key.empty() ? fmt::format("columns[{}]", column + 1) : key;
}

std::array<double, 3> column_drift_row(const BuildingDefinition& definition, std::size_t column, int direction) {
  const Point2 arm = definition.columns.at(column).position_m - definition.centre_of_mass;
  return direction == 0 ? std::array<double, 3>{1.0, 0.0, -arm.y()} : std::array<double, 3>{0.0, 1.0, arm.x()};
}

bool every_column_has_own_strength(const BuildingDefinition& definition) {
  return definition.uses_columns() && std::all_of(definition.columns.begin(), definition.columns.end(),
                                                  [](const Column& c) { return !c.yield_force_kN.empty(); });
}

bool has_shear_capacity(const BuildingDefinition& definition) {
  return !definition.column_shear_capacity_kN.empty() || definition.shear_capacity ||
         std::any_of(definition.columns.begin(), definition.columns.end(),
                     [](const Column& c) { return !c.shear_capacity_kN.empty(); });
}

double column_shear_capacity_kN(const Building& building, int storey, std::size_t column, int direction) {
  const BuildingDefinition& d = building.definition;
  const std::size_t j = static_cast<std::size_t>(storey - 1);
  if (column < d.columns.size() && !d.columns[column].shear_capacity_kN.empty())
    return d.columns[column].shear_capacity_kN.at(j);
  if (!d.column_shear_capacity_kN.empty()) return d.column_shear_capacity_kN.at(j);
  if (!d.shear_capacity) return 0.0;
  const ShearCapacityFormula& f = *d.shear_capacity;
  const Column& c = d.columns.at(column);
  const double depth_mm = 1000.0 * (direction == 0 ? c.b_m : c.h_m);
  const double gross_area_mm2 = 1e6 * c.b_m * c.h_m;
  const double d_mm = f.effective_depth_ratio * depth_mm;
  const double moment_ratio =
      std::clamp(1000.0 * d.storey_height_m.at(static_cast<std::size_t>(storey - 1)) / 2.0 / d_mm, 2.0, 4.0);
  const double spacing_ratio = f.transverse_spacing_mm / d_mm;
  const double steel_share = std::clamp((1.0 - spacing_ratio) / 0.25, 0.0, 1.0);
  const double axial_kN = column_axial_load_kN(d, storey, f.axial_load_kN);
  const double root_fc = std::sqrt(f.concrete_strength_MPa);
  const double steel_N =
      steel_share * f.transverse_area_mm2 * f.transverse_yield_strength_MPa * d_mm / f.transverse_spacing_mm;
  const double concrete_N = 0.5 * root_fc / moment_ratio *
                            std::sqrt(1.0 + 1000.0 * axial_kN / (0.5 * root_fc * gross_area_mm2)) * 0.8 *
                            gross_area_mm2;
  return f.ductility_factor * (steel_N + concrete_N) / 1000.0;
}

namespace {

/// A storey yield shear sets the yield drift through the columns' stiffness, known only once the
/// frame factor is: refused here, as refuse_collapse_before_yield() refuses a yield drift.
void refuse_collapse_before_yield_shear(const Building& building) {
  const BuildingDefinition& d = building.definition;
  for (std::size_t c = 0; c < d.columns.size(); ++c) {
    const Column& column = d.columns[c];
    for (int storey = 1; storey <= d.storeys; ++storey) {
      const std::size_t j = static_cast<std::size_t>(storey - 1);
      for (int direction = 0; direction < 2; ++direction) {
        const std::optional<double> force_kN = column_yield_force_kN(d, storey, c, direction);
        if (!force_kN) continue;
        const double drift_m = column_yield_drift_m(building, storey, c, direction);
        if (drift_m <= 0.05 * d.storey_height_m[j]) continue;
        throw InputError(
            column.yield_force_kN.empty() ? std::string("flexural_strength")
                                          : fmt::format("{}[{}]", own_strength_key(column), j + 1),
            format_value(*force_kN),
            fmt::format("gives {} a yield drift of {:.4g} m along {}{}, over 5 % of storey {}'s height "
                        "({:g} m): a drift of 10 % of a storey ends a run as a collapse",
                        column_key(d, c), drift_m, direction == 0 ? "x" : "y",
                        column.yield_force_kN.empty() ? " (its section's yield force 2 M_n / H over k)" : "", storey,
                        d.storey_height_m[j]));
      }
    }
  }
  const std::vector<double>& shears_kN = building.definition.hysteresis.yield_shear_kN;
  for (std::size_t j = 0; j < shears_kN.size(); ++j) {
    const double height_m = building.definition.storey_height_m[j];
    for (int direction = 0; direction < 2; ++direction) {
      const double drift_m = column_yield_drift_m(building, static_cast<int>(j) + 1, direction);
      if (drift_m <= 0.05 * height_m) continue;
      throw InputError(indexed("hysteresis.yield_shear_kN", j), format_value(shears_kN[j]),
                       fmt::format("gives storey {}'s columns a yield drift of {:.4g} m along {}, over 5 % of its "
                                   "height ({:g} m): a drift of 10 % of a storey ends a run as a collapse",
                                   j + 1, drift_m, direction == 0 ? "x" : "y", height_m));
    }
  }
}

/// IMK's post-yield slope (F_max/F_y − 1) F_y / U_p must stay below k, i.e. U_p > (F_max/F_y − 1) d_y,
/// on each side of every storey along x and y (d_y known only once the frame factor is).
void refuse_steep_imk_hardening(const Building& building) {
  const HystereticLaw& law = building.definition.hysteresis;
  for (const bool positive : {true, false}) {
    const char* key = !positive && !law.imk_up_neg_m.empty() ? "hysteresis.Up_neg" : "hysteresis.Up_pos";
    const char* cap_key = !positive && law.imk_fmax_fy_neg ? "FmaxFy_neg" : "FmaxFy_pos";
    for (int storey = 1; storey <= building.definition.storeys; ++storey) {
      const ImkSideKeys side = imk_side(law, storey, positive);
      const std::size_t j = static_cast<std::size_t>(storey - 1);
      // A storey given as a matrix: its storey springs', which yield at the storey's d_y.
      const std::size_t springs = std::max<std::size_t>(building.definition.columns.size(), 1);
      for (std::size_t c = 0; c < springs; ++c) {
        for (int direction = 0; direction < 2; ++direction) {
          const double yield_m = building.definition.uses_columns()
                                     ? column_yield_drift_m(building, storey, c, direction)
                                     : column_yield_drift_m(building, storey, direction);
          const double least_m = (side.cap_ratio - 1.0) * yield_m;
          if (side.plastic_drift_m > least_m) continue;
          throw InputError(
              indexed(key, j), format_value(side.plastic_drift_m),
              fmt::format("must exceed ({} - 1) d_y = {:.4g} m on the {} side (storey {} along {}): the "
                          "post-yield slope would reach the elastic stiffness",
                          cap_key, least_m, positive ? "positive" : "negative", j + 1, direction == 0 ? "x" : "y"));
        }
      }
    }
  }
}

}  // namespace

Building make_building(const BuildingDefinition& definition) {
  definition.validate();
  Building building;
  building.definition = definition;
  building.mass_diagonal = assemble_mass(definition);

  if (definition.uses_columns()) {
    // K is linear in the frame factor, so ω² ∝ f and T₁(f) = T₁(1)/√f: the factor that gives
    // the target period follows in closed form from one eigen-analysis at f = 1.
    double f = definition.frame_factor;
    if (definition.target_period_s) {
      const Eigen::MatrixXd k_unit = column_building_stiffness(definition, 1.0);
      require_positive_definite(k_unit, definition);
      const double period_unit = modal_analysis(building.mass_diagonal, k_unit).front().period_s;
      f = std::pow(period_unit / *definition.target_period_s, 2);
    }
    building.frame_factor = f;
    building.definition.frame_factor = f;
    building.stiffness = column_building_stiffness(definition, f);
  } else {
    building.frame_factor = 1.0;
    building.stiffness = assemble_stiffness(definition.storey_stiffness);
  }
  if (definition.hysteresis.yields()) refuse_collapse_before_yield_shear(building);
  if (definition.hysteresis.degrades()) refuse_steep_imk_hardening(building);
  if (definition.p_delta) building.stiffness += assemble_stiffness(geometric_storey_matrices(definition));
  require_positive_definite(building.stiffness, definition);

  building.modes = modal_analysis(building.mass_diagonal, building.stiffness);
  const auto [i, j] = definition.damping.modes;
  building.rayleigh =
      fit_rayleigh(building.modes[i - 1].omega_rad_s, building.modes[j - 1].omega_rad_s, definition.damping.ratio);
  building.damping = building.rayleigh.a0_per_s * Eigen::MatrixXd(building.mass_diagonal.asDiagonal()) +
                     building.rayleigh.a1_s * building.stiffness;
  return building;
}

}  // namespace pounding::model
