#pragma once
// The Ibarra–Medina–Krawinkler peak-oriented law with cyclic deterioration (Ibarra, Medina &
// Krawinkler 2005), as OpenSees 3.8 implements it in IMKPeakOriented (its parameters, its branch
// numbers and its deterioration rules), for one column spring: a force–drift law F(d) that is
// linear on each branch, so that every branch change is a root an event-driven run locates:
//   0  elastic, F = K_e d, until d reaches ±U_y (U_y = F_y/K_e);
//   1  unloading at K_u from the last reversal, until F = 0 (a new excursion) or back at the
//      reversal point (reloading on to the global peak);
//   2  with pinching (OpenSees' IMKPinching, ImkPinching): reloading towards the pinching point;
//   3, 4  reloading towards the local peak, then the global one (peak-oriented);
//   5, 6, 7  the backbone: post-yield (slope K_p up to the cap), post-capping (K_pc < 0 down to the
//      residual), residual (F_res);
// and 12..17 their mirror images for negative drifts. The loading branches (2..7, 12..17) end
// also where the drift rate turns (a reversal). Deterioration, with E the work ∫F dd:
//   at a reversal (stiffness):  β_K = ((E_i − ½F²/K_u) / (E_t,K − E + ½F²/K_u))^c_K, K_u ← (1 − β_K) K_u,
//   at a new excursion (basic strength, post-capping strength, accelerated reloading):
//     β = (E_i / (E_t − E))^c with E_i the excursion's work, on the side it heads for:
//     F_y ← (1 − β_S D) F_y, K_p ← (1 − β_S D) K_p, the post-capping line's intercept
//     ← (1 − β_C D), the global peak drift ← (1 + β_A D) (the peak's force on the updated backbone);
// with E_t = Λ F_y⁺ per mode. The spring fails (carries no force from then on) where a β
// exceeds 1, a global peak falls to zero force, the drift reaches the ultimate drift U_u moving
// out, or the residual branch has no force. docs/model.md, "Degrading columns (IMK)", states
// the equations and this program's three choices beyond OpenSees: Λ = 0 turns a mode off, an
// exhausted energy (E_t ≤ E where a β is formed) fails the spring, and a reloading that would be
// stiffer than K_e (or point backwards) reloads at K_e to the backbone.
// Units: m, kN, kJ.

#include <array>
#include <limits>
#include <optional>

namespace pounding::dynamics {

/// One side's backbone (both sides as positive numbers).
struct ImkSide {
  double yield_force_kN = 0.0;                                        // F_y
  double plastic_drift_m = 0.0;                                       // U_p: yield to the cap
  double post_cap_drift_m = 0.0;                                      // U_pc: the cap to zero force
  double ultimate_drift_m = std::numeric_limits<double>::infinity();  // U_u
  double cap_ratio = 1.0;                                             // F_max / F_y ≥ 1
  double residual_ratio = 0.0;                                        // F_res / F_y ∈ [0, 1]
  double deterioration_rate = 1.0;                                    // D ∈ (0, 1]
};

/// The modes of cyclic deterioration, in the order of ImkParameters' arrays.
enum ImkMode { kStrength = 0, kPostCap = 1, kAccelerated = 2, kStiffness = 3 };

/// IMKPinching's pinching point: reloading heads first for (U_pinch, F_pinch), U_pinch =
/// (1 − κ_D) × the global peak's plastic drift, F_pinch = κ_F × the force of the line to the
/// global peak there.
struct ImkPinching {
  double kappa_f = 1.0;
  double kappa_d = 0.0;
};

struct ImkParameters {
  double stiffness_kN_per_m = 0.0;  // K_e
  ImkSide positive, negative;
  std::array<double, 4> lamda_m{};                     // Λ_S, Λ_C, Λ_A, Λ_K: E_t = Λ F_y⁺; 0: the mode is off
  std::array<double, 4> exponent{1.0, 1.0, 1.0, 1.0};  // c_S, c_C, c_A, c_K
  std::optional<ImkPinching> pinching;                 // empty: peak-oriented
};

/// The line a spring's force follows on its present branch: F = force_kN + slope (d − drift_m)
/// while lower_m ≤ d ≤ upper_m. A loading branch (reversal_sign ±1) ends also where
/// reversal_sign · ḋ falls to 0; 0: it does not. The unloading stiffness K_u gives the energy the
/// spring would return unloading to zero force, ½F²/K_u.
struct LineBranch {
  double force_kN = 0.0;
  double drift_m = 0.0;
  double slope_kN_per_m = 0.0;
  double lower_m = -std::numeric_limits<double>::infinity();
  double upper_m = std::numeric_limits<double>::infinity();
  int reversal_sign = 0;
  double unloading_stiffness_kN_per_m = 0.0;

  double force_at(double d) const { return force_kN + slope_kN_per_m * (d - drift_m); }
};

class ImkPeakOriented {
 public:
  /// @pre every side's F_y, U_p, U_pc and K_e positive, cap_ratio ≥ 1 (the scene validates them).
  explicit ImkPeakOriented(const ImkParameters& parameters);

  /// The present branch's line (on the elastic branch at the start).
  const LineBranch& line() const { return line_; }
  /// OpenSees' number of the present branch (see the header comment); −1 once failed.
  int branch() const { return failed_ ? -1 : branch_; }
  bool failed() const { return failed_; }
  double force_kN(double drift_m) const { return failed_ ? 0.0 : line_.force_at(drift_m); }

  /// At drift d (m), where the present branch ends (an end of [lower, upper] reached, or the
  /// loading branch's drift rate at zero), with the motion past the instant heading `direction`
  /// (+1 or −1: the drift rate's sign, or the acceleration's at zero rate): takes every branch
  /// change the motion makes there (several may fall on one drift). @return whether the branch
  /// changed (false where the motion turns back onto the present one).
  bool advance(double drift_m, int direction);

  /// Fails the spring at drift d (m) from outside its law (a shear failure that takes its
  /// stiffness): it carries no force from then on.
  void fail_at(double drift_m) { fail(drift_m); }

  /// The work ∫F dd (kJ) from the start to drift d on the present branch.
  double work_kJ(double drift_m) const;
  /// The work less what the spring would return unloading to zero force, ½F²/K_u (kJ); all of
  /// the work once failed.
  double dissipated_kJ(double drift_m) const;

 private:
  struct Backbone {  // one side's present backbone, signed (OpenSees' pos*/neg* members)
    double yield_drift_m, yield_force_kN, cap_drift_m, cap_force_kN, plastic_slope, post_cap_slope;
    double residual_force_kN, residual_drift_m;
    double local_drift_m, local_force_kN, global_drift_m, global_force_kN;
    double ultimate_drift_m, rate;
  };
  Backbone& side(int direction) { return direction > 0 ? positive_ : negative_; }
  /// F on side's backbone at d (elastic below the yield drift, at least the residual force).
  static double backbone_force(const Backbone& side, double drift_m, double stiffness);
  void reverse(double drift_m);
  /// The present branch's end reached at drift d heading `direction` (not the ultimate drift):
  /// the next branch (or a new excursion at zero force).
  void pass_end(double drift_m, int direction);
  void new_excursion(double drift_m, int direction);
  void deteriorate_backbone(Backbone& side, const std::array<double, 4>& beta);
  void reload(double drift_m, int direction);
  /// Back at a local peak before the global one: whether the pinching point lies between them,
  /// reached less steeply than the global peak (OpenSees' IMKPinching).
  bool pinches_before_global(const Backbone& side, int direction) const;
  void enter(int branch, double drift_m);
  /// β of `mode` for work `numerator` against the energy left, E_t − `spent`; sets failing_.
  double beta(ImkMode mode, double numerator, double spent_kJ);
  void fail(double drift_m);
  void close_segment(double drift_m);

  ImkParameters parameters_;
  Backbone positive_{}, negative_{};
  double unloading_stiffness_ = 0.0;  // K_u
  double pinch_drift_m_ = 0.0;        // the pinching point of the present excursion
  double pinch_force_kN_ = 0.0;
  double reload_slope_ = 0.0;        // K_reload on branches 2, 3, 4, 12, 13, 14
  double work_kJ_ = 0.0;             // ∫F dd up to the present branch's entry
  double excursion_start_kJ_ = 0.0;  // the work where the present excursion began (engDspt)
  double entry_drift_m_ = 0.0;       // where the present branch began
  int branch_ = 0;
  bool failed_ = false;
  bool failing_ = false;  // a β exceeded 1 (or the energy was spent) during this change
  LineBranch line_;
};

}  // namespace pounding::dynamics
