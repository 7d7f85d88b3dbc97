#pragma once
// A building as the structural model sees it: rigid floor slabs (u, v, φ about the CM) joined by
// storeys of columns. Units: m, s, t, kN, rad (so forces in kN, moments in kN·m).

#include <Eigen/Core>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pounding/input_error.hpp"
#include "pounding/key_spec.hpp"
#include "pounding/model/mode.hpp"
#include "pounding/model/polygon.hpp"

namespace pounding::model {

/// The most storeys a building may have: the tallest buildings have 163; 200 storeys are 600
/// DOF, whose dense modal analysis still takes well under a second.
inline constexpr int kMaxStoreys = 200;

/// The most vertices a slab outline may have (an L or a rounded plan needs tens; contact
/// candidates grow with the product of two slabs' vertex counts), and the most columns a storey
/// may list (a 100 × 100 grid). Checked by the scene reader before it builds anything, so that a
/// short file cannot ask for hours of work or gigabytes of memory.
inline constexpr std::size_t kMaxSlabVertices = 1000;
inline constexpr std::size_t kMaxColumns = 10'000;

/// The storey heights a scene may give (m), each storey's alone or one for all: beyond them a
/// value is a typo or a unit mistake. Public so that the scene reader can refuse a single value
/// under the key the user typed.
inline constexpr Range kStoreyHeightRange{1.0, 20.0, "m"};
/// A floor's mass (above 1e6 t only to model a rigid wall) and a column's section sides, public
/// for the same reason: `top_floor_mass_t` and a `column_grid`'s `b_m`/`h_m` are refused under
/// their own keys, not under the `mass_t[i]` and `columns[i].b` they become.
inline constexpr Range kFloorMass{1.0, 1e10, "t"};
inline constexpr Range kColumnSize{0.0, 5.0, "m", true};

/// A column between two floors, fixed at both ends. b is its size along x, h along y (m).
struct Column {
  Point2 position_m = Point2::Zero();
  double b_m = 0.0;
  double h_m = 0.0;
  /// Where the scene gave it, for messages ("column_grid[1] x[5] y[2]"); empty: columns[i].
  std::string key = {};
  /// Its own yield force (kN), along x and along y alike, one a storey (storey 1 first; a column
  /// grid's or a listed column's `yield_force_kN`); empty: the building's strength (the section's,
  /// FlexuralStrengthFormula, or its storey's in [building.hysteresis]).
  std::vector<double> yield_force_kN = {};
  /// Its own shear capacity (kN), along x and along y alike, one a storey (`shear_capacity_kN` of
  /// its grid or its entry); empty: the building's (column_shear_capacity_kN or the section's).
  std::vector<double> shear_capacity_kN = {};
};

/// Rayleigh damping C = a0 M + a1 K fitted to one ratio at two modes (1-based, sorted by period
/// from the longest).
struct RayleighSpec {
  double ratio = 0.05;
  std::array<int, 2> modes{1, 3};
};

/// A reinforced-concrete column's shear capacity from its section by ASCE 41-17 Eq. 10-3
/// (docs/model.md §2a, "Column shear capacity"), in SI units:
///   V = k_nl [α A_v f_yt d/s + λ (0.5 √f'c / (M/Vd)) √(1 + N/(0.5 √f'c A_g)) 0.8 A_g]
/// for a sway along x (y) of a column b × h: the section's depth along the sway is b (h), d its
/// effective depth, A_g = b h, M/Vd = (H/2)/d in double curvature bounded to [2, 4], α = 1 for
/// s/d ≤ 0.75, 0 for s/d ≥ 1 and linear between, N the axial compression, λ = 1 (normal-weight
/// concrete). The same for every column of the building.
struct ShearCapacityFormula {
  double concrete_strength_MPa = 0.0;          // f'c (required)
  double transverse_yield_strength_MPa = 0.0;  // f_yt (required)
  double transverse_area_mm2 = 0.0;            // A_v: the legs of one set of ties across the shear plane (required)
  double transverse_spacing_mm = 0.0;          // s (required)
  std::optional<double> axial_load_kN;         // N per column, compression; unset: the gravity share
  double effective_depth_ratio = 0.8;          // d over the section's depth along the sway
  double ductility_factor = 1.0;               // k_nl: 1 at displacement ductility ≤ 2, 0.7 at ≥ 6
};

/// A reinforced-concrete column's flexural strength from its section (docs/model.md §2a, "Column
/// strength from the section"), SI units (N, mm, MPa): the nominal moment M_n of the section at
/// the concrete's ultimate strain ε_cu = 0.003 under its axial compression N, by strain
/// compatibility (ACI 318's assumptions: the stress block 0.85 f'c over β₁ c, E_s = 200 GPa, bars
/// elastic–perfectly plastic at ±f_y), with its bars as two layers of ρ_l D W / 2 each at
/// d' = cover_ratio · D from the faces across the sway: for a sway along x (y) of a column b × h,
/// D = b (h) the depth along the sway and W = h (b) the other side. The column's yield force is the
/// shear of its double curvature over the storey height, F_y = 2 M_n / H. A section whose tension
/// bars would not yield (N above the balanced load N_b, where the tension layer reaches f_y as the
/// concrete reaches ε_cu) is refused. The same keys for every column of the building but ρ_l, one a
/// storey.
struct FlexuralStrengthFormula {
  std::vector<double> longitudinal_ratio;  // ρ_l: all longitudinal bars over A_g, one a storey (required)
  double steel_yield_strength_MPa = 0.0;   // f_y of the longitudinal bars (required)
  double concrete_strength_MPa = 0.0;      // f'c (required)
  std::optional<double> axial_load_kN;     // N per column, compression; unset: the gravity share
  double cover_ratio = 0.1;                // d' / D: the bars' centroid from the face, over the depth
};

/// The force–drift law of every column of a building (docs/model.md, "Yielding columns"). Each
/// column has a spring in x and one in y, independent of each other (no interaction surface).
/// `elastic`: the linear spring of column_stiffness. `bilinear`: kinematic hardening; the initial
/// stiffness k up to the yield drift, then hardening_ratio · k, unloading at k; the same as a
/// linear spring α k in parallel with an elastic–perfectly-plastic one of stiffness (1 − α) k
/// that yields at the same drift. `bouc_wen`: the smooth law F = α k d + (1 − α) k d_y z with
/// the hysteretic variable z (dimensionless) obeying ż = (ḋ/d_y)(A − |z|ⁿ(β sgn(ḋ z) + γ));
/// with A = β + γ = 1 it saturates at the bilinear law's yield force and tends to it as n grows.
/// `imk_peak_oriented`: the Ibarra–Medina–Krawinkler peak-oriented law with cyclic strength and
/// stiffness deterioration, as OpenSees' IMKPeakOriented (dynamics/imk_law.hpp), with OpenSees'
/// parameter names: K_e is the column's k, F_y its k d_y on both sides. `imk_pinching`: the same
/// with OpenSees' IMKPinching's pinched reloading (κ_F, κ_D).
/// Storeys given as 3×3 matrices yield as storey springs (storey_springs()).
struct HystereticLaw {
  enum class Kind { elastic, bilinear, bouc_wen, imk_peak_oriented, imk_pinching };
  Kind kind = Kind::elastic;
  /// The strength, exactly one of three, each one value a storey, storey 1 first (the reader
  /// spreads a single number over every storey): the yield drift as a fraction of the storey
  /// height (d_y = ratio_j · H_j), the yield drift (m), or the storey's yield shear (kN), the
  /// shear at which the storey's columns all yield together in a translation along x or y:
  /// d_y = V_j / Σ k of its columns along that direction (column_yield_drift_m()).
  std::vector<double> yield_drift_ratio;
  std::vector<double> yield_drift_m;
  std::vector<double> yield_shear_kN;
  double hardening_ratio = 0.0;  // α ∈ [0, 1): post-yield over initial stiffness
  /// Bouc–Wen's shape parameters (only for Kind::bouc_wen): A = 1 (so that the initial stiffness
  /// is k, which K uses); β > 0 and −β < γ ≤ β, so that z stays within (A/(β + γ))^(1/n) and no
  /// loop returns energy; n ≥ 1, the sharpness.
  double bouc_wen_a = 1.0;
  double bouc_wen_beta = 0.5;
  double bouc_wen_gamma = 0.5;
  double bouc_wen_n = 2.0;
  /// IMK's backbone (only for Kind::imk_peak_oriented), one value a storey for the drifts (m):
  /// U_p (yield to the cap), U_pc (the cap to zero force), U_u (ultimate; empty: none); the
  /// negative side's lists empty: the positive side's. F_max/F_y ≥ 1 (required), F_res/F_y.
  std::vector<double> imk_up_pos_m, imk_upc_pos_m, imk_uu_pos_m, imk_up_neg_m, imk_upc_neg_m, imk_uu_neg_m;
  std::optional<double> imk_fmax_fy_pos, imk_fmax_fy_neg, imk_fres_fy_neg;
  double imk_fres_fy_pos = 0.0;
  /// IMK's cyclic deterioration: Λ (m; the reference energy Λ F_y⁺; 0: the mode is off) and the
  /// exponent c of strength (S), post-capping strength (C), accelerated reloading (A) and
  /// unloading stiffness (K); the rates D per side.
  double imk_lamda_s_m = 0.0, imk_lamda_c_m = 0.0, imk_lamda_a_m = 0.0, imk_lamda_k_m = 0.0;
  double imk_c_s = 1.0, imk_c_c = 1.0, imk_c_a = 1.0, imk_c_k = 1.0;
  double imk_d_pos = 1.0, imk_d_neg = 1.0;
  /// IMKPinching's κ_F and κ_D (required for Kind::imk_pinching).
  std::optional<double> imk_kappa_f, imk_kappa_d;

  bool yields() const { return kind != Kind::elastic; }
  /// True for the laws whose state is an ODE variable (Bouc–Wen's z) rather than branches.
  bool is_smooth() const { return kind == Kind::bouc_wen; }
  bool degrades() const { return kind == Kind::imk_peak_oriented || kind == Kind::imk_pinching; }
};

/// One side of an IMK law's backbone in one storey, as the scene gave it (both sides as positive
/// numbers; the negative side's keys left out are the positive side's).
struct ImkSideKeys {
  double plastic_drift_m = 0.0;                                       // U_p
  double post_cap_drift_m = 0.0;                                      // U_pc
  double ultimate_drift_m = std::numeric_limits<double>::infinity();  // U_u; infinite: not given
  double cap_ratio = 1.0;                                             // F_max / F_y
  double residual_ratio = 0.0;                                        // F_res / F_y
  double rate = 1.0;                                                  // D
};
/// Storey `storey` (1-based)'s positive or negative side. @pre law.degrades(), validated.
ImkSideKeys imk_side(const HystereticLaw& law, int storey, bool positive);

/// The scene's name of a law ("elastic", "bilinear", "bouc-wen", "imk-peak-oriented", "imk-pinching").
const char* to_string(HystereticLaw::Kind kind);
/// The laws' names in the order of HystereticLaw::Kind: what `hysteresis.law` accepts.
std::span<const std::string_view> hysteretic_law_names();

/// One key of [building.hysteresis] besides `law` (key_spec.hpp): the scene reader, the range
/// checks (validate()), `pounding settings` and the docs' table come from these rows; each names
/// the laws it applies to.
using HysteresisSpec = KeySpec<HystereticLaw>;
std::span<const HysteresisSpec> hysteresis_specs();

/// The range of slab_thickness_m (m).
inline constexpr Range kSlabThickness{0.0, 2.0, "m", true};

/// The range of column_shear_capacity_kN, public for the scene reader's messages (the
/// hysteresis parameters' ranges are their rows', hysteresis_specs()).
inline constexpr Range kColumnShearCapacity{0.0, 1e6, "kN", true};
/// The range of a column grid's yield_force_kN (Column::yield_force_kN), for the scene reader.
inline constexpr Range kColumnYieldForce{0.0, 1e6, "kN", true};

/// The peak transient storey drift ratios that mark a building's structural performance levels
/// ([building.limit_states], analysis/limit_states.hpp): immediate occupancy, life safety and
/// collapse prevention. An unset limit is its structural type's (FEMA 356 Table C1-3).
struct DriftLimits {
  std::string structural_type = "concrete-frame";
  std::optional<double> immediate_occupancy;
  std::optional<double> life_safety;
  std::optional<double> collapse_prevention;
};

/// Everything a scene says about one building. All floors share the slab outline and the CM.
struct BuildingDefinition {
  std::string name;
  int storeys = 0;
  std::vector<double> storey_height_m;     // one per storey, storey 1 (ground to floor 1) first
  Polygon slab;                            // global plan coordinates at rest, CCW
  Point2 centre_of_mass = Point2::Zero();  // global plan coordinates at rest (m)
  std::vector<double> mass_t;              // one per floor, floor 1 first
  std::vector<double> polar_moment_tm2;    // about the CM, one per floor

  // Storey stiffness, either from columns ...
  std::vector<Column> columns;
  double E_kPa = 0.0;                     // Young's modulus of the columns
  double frame_factor = 1.0;              // ignored when target_period_s is set
  std::optional<double> target_period_s;  // solve the frame factor for this T₁ (s)
  /// Each column's shear capacity (kN), along x and along y, one value a storey (the reader
  /// spreads a single number over every storey); empty: none given. Slab-to-column impacts report
  /// their shear demand against it (docs/model.md §6b), and yielding columns whose sway shear
  /// reaches it fail in shear (§2a).
  std::vector<double> column_shear_capacity_kN;
  /// ... or every column's from its section (excludes column_shear_capacity_kN). A column's own
  /// (Column::shear_capacity_kN) comes before either.
  std::optional<ShearCapacityFormula> shear_capacity;
  /// Every column's yield force from its section (excludes the storey strength keys of
  /// [building.hysteresis]); a column's own (Column::yield_force_kN) comes before it.
  std::optional<FlexuralStrengthFormula> flexural_strength;
  /// What a yielding column does when its sway shear reaches its capacity: "report" (the instant
  /// is reported, the column keeps its law) or "lose-stiffness" (bilinear columns only: it
  /// carries no force for the rest of the run).
  std::string column_shear_failure = "report";
  bool shear_failure_loses_stiffness() const { return column_shear_failure == "lose-stiffness"; }
  /// The floor slabs' thickness (m), for their axial stiffness E t w / L (slab_axial_stiffness_kN_per_m),
  /// which `check` sets beside the contact stiffness; unset: not shown. Only with columns (E_kPa).
  std::optional<double> slab_thickness_m;
  // ... or given directly: one 3×3 matrix per storey about the CM (kN/m, kN, kN·m/rad).
  std::vector<Eigen::Matrix3d> storey_stiffness;

  RayleighSpec damping;
  HystereticLaw hysteresis;  // of the columns; elastic unless the scene says otherwise
  /// P-Δ: each storey's stiffness lowered by the gravity load above it (geometric_stiffness), in
  /// K and so in the modes and the Rayleigh damping. The gravity g_mps2 is the scene's.
  bool p_delta = false;
  double g_mps2 = 9.81;
  /// The drift limits its run is assessed against; none: not assessed.
  std::optional<DriftLimits> drift_limits;

  bool uses_columns() const { return storey_stiffness.empty(); }
  /// @throws InputError naming the offending field (as the scene key, relative to the building),
  /// its value and, for a number outside its physical range, the range (docs/scene-format.md).
  void validate() const;
};

/// Polar moment about the CM of a slab of mass `mass_t` spread uniformly over `slab`:
/// J = m · (Ix + Iy)/A about the slab's centroid (t·m²). The offset of the CM from the centroid
/// is deliberately not added (it comes from non-uniform mass such as cores and cladding).
double uniform_polar_moment(const Polygon& slab, double mass_t);

/// Lateral stiffnesses (kN/m) of one column fixed at both ends: k_x = 12 E (h b³/12)/H³,
/// k_y = 12 E (b h³/12)/H³, times the frame factor.
Eigen::Vector2d column_stiffness(const Column& column, double elastic_modulus_kPa, double storey_height_m,
                                 double frame_factor);

/// Storey stiffness about `centre_of_mass`: Σ Tᵀ diag(k_x, k_y) T, T = [[1,0,−Δy],[0,1,Δx]],
/// for a storey of height `storey_height_m`.
Eigen::Matrix3d storey_stiffness_from_columns(const std::vector<Column>& columns, const Point2& centre_of_mass,
                                              double elastic_modulus_kPa, double storey_height_m, double frame_factor);

/// The geometric (P-Δ) stiffness of storey j about the CM: −(g/H_j) diag(M_j, M_j, J_j), M_j and
/// J_j the mass and polar moment of the floors it carries (j … N). A storey drift Δ tilts the load
/// above by Δ/H_j, whose horizontal share P Δ/H_j drives the drift on; a twist Δφ does so to each
/// mass element at radius r, g dm r² Δφ/H_j about the CM, which all floors share. (kN/m, kN·m/rad)
/// @pre definition valid.
std::vector<Eigen::Matrix3d> geometric_storey_matrices(const BuildingDefinition& definition);

/// Block-tridiagonal stiffness (3N×3N) from the storey matrices, storey 1 (to the ground) first.
Eigen::MatrixXd assemble_stiffness(const std::vector<Eigen::Matrix3d>& storeys);

/// The storey matrices of a column building, each storey with its own height H_j
/// (k = f · 12 E I / H_j³), so K stays linear in the frame factor f.
/// @pre definition valid and uses_columns().
std::vector<Eigen::Matrix3d> column_storey_matrices(const BuildingDefinition& definition, double frame_factor);

/// Elevation of each floor above the ground, z_j = H_1 + … + H_j (m), floor 1 first.
std::vector<double> floor_elevations(const BuildingDefinition& definition);

struct RayleighCoefficients {
  double a0_per_s = 0.0;  // mass-proportional
  double a1_s = 0.0;      // stiffness-proportional
};

/// a0, a1 such that the modal damping ratio equals `ratio` at ω_i and ω_j (rad/s).
/// @pre 0 < ω_i, 0 < ω_j, ω_i ≠ ω_j.
RayleighCoefficients fit_rayleigh(double omega_i, double omega_j, double ratio);

/// The assembled linear model of one building: M q̈ + C q̇ + K q = −M r a_g.
struct Building {
  BuildingDefinition definition;  // with frame_factor resolved
  Eigen::VectorXd mass_diagonal;  // (m₁, m₁, J₁, m₂, …), size 3N
  Eigen::MatrixXd stiffness;      // 3N×3N, symmetric positive definite
  Eigen::MatrixXd damping;        // 3N×3N
  RayleighCoefficients rayleigh;
  double frame_factor = 1.0;  // the one used (given, solved, or 1 for direct matrices)
  /// All 3N modes of mass_diagonal and stiffness (model::modal_analysis), longest period first,
  /// solved once by make_building: every user of a building's modes reads these. Stale if M or K
  /// is changed afterwards.
  std::vector<Mode> modes;

  int storeys() const { return definition.storeys; }
  int dof() const { return 3 * definition.storeys; }
};

/// Σ k (kN/m) of storey `storey`'s columns (1-based) along `direction` (0: x, 1: y), with the
/// building's frame factor; a storey given as a matrix: its storey spring's (storey_springs()).
double storey_column_stiffness(const Building& building, int storey, int direction);

/// A storey given as a 3×3 matrix K (about the CM) yields as two storey springs (docs/model.md
/// §2a, "Storey springs"): along x, k_x = K_uu acting at the storey's centre of rigidity along y,
/// e_y = −K_uφ/K_uu, on the drift Δu − e_y Δφ (row t_x = (1, 0, −e_y)); along y, k_y = K_vv at
/// e_x = K_vφ/K_vv on Δv + e_x Δφ (t_y = (0, 1, e_x)). K is k_x t_x t_xᵀ + k_y t_y t_yᵀ plus an
/// elastic torsional remainder, which needs K_uv = 0 (validate() refuses a coupled matrix).
struct StoreySprings {
  std::array<double, 2> stiffness_kN_per_m{};   // k_x, k_y
  std::array<std::array<double, 3>, 2> rows{};  // t_x, t_y over (Δu, Δv, Δφ)
};
/// @pre definition valid, !uses_columns(), 1 ≤ storey ≤ storeys.
StoreySprings storey_springs(const BuildingDefinition& definition, int storey);

/// The yield drift (m) of every column of storey `storey` (1-based) along `direction` (0: x,
/// 1: y), from the law's strength (HystereticLaw). @pre building.definition.hysteresis.yields().
double column_yield_drift_m(const Building& building, int storey, int direction);
/// Column `column` (0-based)'s yield drift (m) in storey `storey` along x (0) or y (1): its yield
/// force over its stiffness, F_y / k, where it has one (column_yield_force_kN()), else its storey's
/// (above). @pre as above.
double column_yield_drift_m(const Building& building, int storey, std::size_t column, int direction);
/// Column `column`'s own yield force (kN) in storey `storey` along x (0) or y (1): its
/// Column::yield_force_kN, else its section's 2 M_n / H (FlexuralStrengthFormula); none: the
/// storey's strength applies.
std::optional<double> column_yield_force_kN(const BuildingDefinition& definition, int storey, std::size_t column,
                                            int direction);

/// A column's section strength along one direction (FlexuralStrengthFormula).
struct SectionStrength {
  double axial_load_kN = 0.0;           // N
  double balanced_axial_load_kN = 0.0;  // N_b: the tension bars yield for N ≤ N_b
  double moment_kNm = 0.0;              // M_n at N
  double yield_force_kN = 0.0;          // 2 M_n / H
};
/// @pre definition.flexural_strength, its keys within their ranges.
SectionStrength column_section_strength(const BuildingDefinition& definition, int storey, std::size_t column,
                                        int direction);
/// A column's axial compression (kN) in storey `storey`: `given`, else the storey's gravity share
/// g Σ (floor masses from `storey` up) / its number of columns.
double column_axial_load_kN(const BuildingDefinition& definition, int storey, std::optional<double> given);
/// Column `column` (0-based)'s scene key, for messages and outputs: "columns[3]" or
/// "column_grid[1] x[2] y[1]" (Column::key, else its place in the list).
std::string column_key(const BuildingDefinition& definition, std::size_t column);
/// The row t over (u, v, φ) whose product with a storey's floor difference is column `column`'s
/// drift along x (0) or y (1): (1, 0, −Δy) or (0, 1, Δx), Δ its position from the CM (the rows of T).
std::array<double, 3> column_drift_row(const BuildingDefinition& definition, std::size_t column, int direction);
/// True when every column has its own yield force (Column::yield_force_kN), so neither the storey's
/// strength nor the section's is used; false for storeys given as matrices.
bool every_column_has_own_strength(const BuildingDefinition& definition);
/// Whether some column of `definition` has a shear capacity (its own, column_shear_capacity_kN or
/// [building.shear_capacity]).
bool has_shear_capacity(const BuildingDefinition& definition);
/// Column `column` (0-based)'s shear capacity (kN) in storey `storey` along x (0) or y (1): its
/// own (Column::shear_capacity_kN), else the given column_shear_capacity_kN, or ShearCapacityFormula's, whose axial
/// load defaults to the storey's gravity share g Σ (floor masses from `storey` up) / columns; 0 when none is given.
double column_shear_capacity_kN(const Building& building, int storey, std::size_t column, int direction);

/// A floor slab's axial stiffness along the plan direction `direction` (kN/m): E t w / L, E the
/// building's E_kPa, t its slab_thickness_m, w the slab's width across `direction` and L its length
/// along it (the extents of its outline). The contact spring that Anagnostopoulos (1988) and Maison
/// & Kasai (1992) derive from the colliding members is of this order (docs/model.md §6a).
/// @pre definition valid, uses_columns(), slab_thickness_m given, |direction| = 1.
double slab_axial_stiffness_kN_per_m(const BuildingDefinition& definition, const Point2& direction);

/// Validates `definition`, solves the frame factor if a target period is given (for the frame
/// without P-Δ), assembles M, K (with P-Δ if asked), C and solves the modes. @throws InputError (field relative to the
/// building) for invalid data or a stiffness that is not positive definite.
Building make_building(const BuildingDefinition& definition);

}  // namespace pounding::model
