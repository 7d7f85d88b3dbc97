#pragma once
// The compliant contact laws: a force along the struck edge's normal while the
// slabs overlap, a function of the overlap δ = −g > 0 (m) and its rate δ̇ (m/s)
// alone. Each law is given by its force, the force's slopes (for the Jacobian)
// and one switch function whose falling zero is where the law changes its form,
// so the event loop (solvers/event_driven.cpp) treats every law alike.
// docs/model.md §6a states the laws, their sources and which to use for what.

#include <string_view>

namespace pounding::contact {

/// How contacts are resolved (analysis/contact_laws.hpp lists them for users).
enum class ContactLaw { impulse, kelvin, hertzdamp, hertzdamp_ye, jankowski };

std::string_view to_string(ContactLaw law);

/// Hertzdamp's damping ξ = 3k_h(1 − e²)/(4δ̇₀) (Muthukumar & DesRoches 2006) as
/// ξδ̇₀/k_h = 3(1 − e²)/4 (dimensionless). @pre restitution ∈ [0, 1].
double hertzdamp_normalised_damping(double restitution);

/// Ye, Li & Zhu's (2009) damping for the same Hertz form, ξ = 8k_h(1 − e)/(5eδ̇₀), as
/// ξδ̇₀/k_h = 8(1 − e)/(5e) (dimensionless). Derived without assuming that the approach speed
/// barely falls, so it holds for low e too (docs/model.md §6a).
/// @pre restitution ∈ (0, 1]: ξ → ∞ as e → 0, so e = 0 is refused for this law.
double hertzdamp_ye_normalised_damping(double restitution);

/// Whether the law gives e = 0 an infinite damping (jankowski, hertzdamp-ye), so refuses it.
bool refuses_plastic(ContactLaw law);

/// Jankowski's (2005) impact damping ratio ξ = 9√5(1 − e²)/(2e(e(9π − 16) +
/// 16)).
/// @pre restitution ∈ (0, 1]: ξ → ∞ as e → 0, so e = 0 is refused for this law.
double jankowski_damping_ratio(double restitution);

/// The overlap (m) below which (down to 0) the damping part of Jankowski's
/// ∂F/∂δ is evaluated at this overlap instead: the term c′(δ)δ̇ ∝ δ^(−3/4) of
/// its damping c ∝ δ^(1/4) is unbounded at onset (docs/model.md §6a).
inline constexpr double kJankowskiSlopeFloor_m = 1e-9;

/// ∂F/∂δ (kN/m) and ∂F/∂δ̇ (kN·s/m) of a law's force.
struct ForceSlopes {
  double per_overlap_kN_per_m = 0.0;
  double per_rate_kNs_per_m = 0.0;
};

/// One contact of a compliant law from onset until its gap opens, its constants
/// fixed at onset:
///   kelvin     F = kδ + cδ̇, c = 2ξ√(k/W); released where F turns tensile;
///   hertzdamp  F = k_h δ^1.5 + ξ δ^1.5 δ̇, ξ = 3k_h(1 − e²)/(4δ̇₀); released
///   where F turns tensile; hertzdamp-ye  the same with ξ = 8k_h(1 − e)/(5eδ̇₀); jankowski  F = βδ^1.5 + cδ̇ approaching
///   (δ̇ > 0), βδ^1.5 separating, c = 2ξ√(β√δ/W);
/// W = G M⁻¹ Gᵀ the pair's inverse effective mass along the normal, δ̇₀ the
/// approach speed. A struck column's local flexibility f (m/kN, slab-to-column
/// contacts) acts in series with the law's spring: kelvin's k becomes
/// 1/(1/k + f); the Hertz laws' δ^1.5 becomes δ_c^1.5 with δ_c the contact's own
/// overlap, δ = δ_c + f k δ_c^1.5 (docs/model.md §6b). Their dashpots act across
/// both springs. A released contact (kelvin, hertzdamp) exerts no force while
/// the slabs fly apart; it acts again where its force would push. Jankowski's
/// force is never tensile: its switch is between the approach and the
/// restitution phase, and it acts throughout.
class CompliantContact {
 public:
  /// stiffness: k (kN/m) for kelvin, k_h or β (kN/m^1.5) for hertzdamp and
  /// jankowski.
  /// @pre law ≠ impulse, stiffness > 0, restitution ∈ [0, 1] (jankowski, hertzdamp-ye: > 0),
  ///   approach_speed_mps > 0, normal_inverse_mass_per_t > 0.
  ///   series_flexibility_m_per_kN ≥ 0.
  CompliantContact(ContactLaw law, double stiffness, double restitution, double approach_speed_mps,
                   double normal_inverse_mass_per_t, double series_flexibility_m_per_kN = 0.0);

  /// False while a kelvin or hertzdamp contact is released (its force would
  /// pull).
  bool acts() const;
  /// F (kN, > 0 pushes the slabs apart) of the acting law; kelvin's may be
  /// negative just past its release root. The Hertz laws take δ < 0 (just
  /// before onset) as δ = 0.
  double force_kN(double overlap_m, double rate_mps) const;
  ForceSlopes slopes(double overlap_m, double rate_mps) const;
  /// Falls through zero where the law switches: the force for kelvin, k_h + ξδ̇
  /// (the force's sign) for hertzdamp and hertzdamp-ye, δ̇ for jankowski; after a switch its
  /// negation (the switch back).
  double switch_value(double overlap_m, double rate_mps) const;
  /// d(switch_value)/dt given δ̈ (m/s²).
  double switch_rate(double overlap_m, double rate_mps, double accel_mps2) const;
  /// At a falling zero of switch_value: release or act again (kelvin,
  /// hertzdamp), restitution or approach phase (jankowski).
  void toggle() { switched_ = !switched_; }
  ContactLaw law() const { return law_; }

 private:
  /// The switch function before any switch.
  double first_switch(double overlap_m, double rate_mps) const;
  /// The Hertz laws' own overlap δ_c of the contact spring in series with the
  /// column (δ itself without one, and for kelvin, whose k already includes it).
  double own_overlap(double overlap_m) const;
  /// dδ_c/dδ.
  double own_overlap_slope(double own_overlap_m) const;
  /// hertzdamp or hertzdamp-ye: F = δ^1.5 (k_h + ξδ̇).
  bool hertzdamp_form() const { return law_ == ContactLaw::hertzdamp || law_ == ContactLaw::hertzdamp_ye; }
  /// The Hertz laws' slopes in δ_c (= δ without a column) and δ̇.
  ForceSlopes hertz_slopes(double own_overlap_m, double root, double rate_mps) const;

  ContactLaw law_;
  double stiffness_;
  /// kelvin: c (kN·s/m); hertzdamp, hertzdamp-ye: ξ (kN·s/m^2.5); jankowski: c/δ^(1/4)
  /// (kN·s/m^1.25).
  double damping_ = 0.0;
  double series_flexibility_ = 0.0;  // f (m/kN)
  bool switched_ = false;
};

}  // namespace pounding::contact
