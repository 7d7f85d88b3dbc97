#pragma once
// The Kelvin–Voigt impact element (Anagnostopoulos 1988): a spring k and a dashpot c in parallel
// acting along the struck edge's normal while the slabs overlap, F = k δ + c δ̇, δ = −g > 0: its
// closed forms. The law's force and switches are in contact/compliant_law.hpp.

namespace pounding::contact {

/// ξ = −ln e / √(π² + ln² e), so that a lone Kelvin–Voigt contact rebounds at e (e ∈ (0, 1]).
/// e = 0 gives ξ = 1 (critical damping: the limit of the formula as e → 0; it rebounds slowly,
/// not at 0, see docs/model.md). @pre e ∈ [0, 1].
double kelvin_damping_ratio(double restitution);

/// A lone Kelvin–Voigt contact (δ̈ = −ω²δ − 2ξωδ̇, δ(0) = 0, δ̇(0) = v₀) released where its force
/// turns tensile (kδ + cδ̇ = 0, while δ > 0), as this library releases it; not at δ = 0, where
/// the formula for ξ would put it (the dashpot pulls in between). So the rebound exceeds e:
/// 0.550 for e = 0.5, 0.253 for e = 0.1, exp(−2) = 0.135 for e = 0 (docs/model.md).
struct KelvinRelease {
  double omega_time = 0.0;     // ω t* of the release
  double rebound = 0.0;        // −δ̇(t*)/v₀: the effective restitution
  double overlap_ratio = 0.0;  // ω δ(t*)/v₀: the overlap left at release
};
/// @pre damping_ratio ∈ [0, 1].
KelvinRelease kelvin_release(double damping_ratio);

/// c = 2ξ√(k m) (kN·s/m), m = 1/W the pair's effective mass along the normal (t).
/// @pre stiffness_kN_per_m > 0, normal_inverse_mass_per_t > 0, restitution ∈ [0, 1].
double kelvin_damping(double stiffness_kN_per_m, double restitution, double normal_inverse_mass_per_t);

}  // namespace pounding::contact
