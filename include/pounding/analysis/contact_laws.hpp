#pragma once
// The table of contact laws, like the methods registry (methods.hpp): per law its name, a
// one-line description, the [contact] keys that apply to it, its published default stiffness and
// the methods that run it. Validation, `--help` and summary.json read it.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/analysis/methods.hpp"
#include "pounding/contact/compliant_law.hpp"

namespace pounding::analysis {

struct ContactLawInfo {
  std::string_view name;
  std::string_view description;  // one line
  contact::ContactLaw law;
  /// The [contact] key of the law's stiffness (empty: the law has none); it names the unit.
  std::string_view stiffness_key;
  std::string_view stiffness_unit;    // "kN/m" or "kN/m^1.5"
  double default_stiffness = 0.0;     // in stiffness_unit
  std::string_view stiffness_source;  // where the default comes from
  /// What contact_damping() gives: "damping_ratio" (kelvin's and jankowski's ξ) or
  /// "normalised_damping" (hertzdamp's ξδ̇₀/k_h); empty for impulse.
  std::string_view damping_key;
  std::vector<std::string_view> methods{};  // names of the methods that run it; empty: every method
  /// The ratio of separation to approach speed a lone contact of this law achieves for the
  /// scene's restitution e (closed form, as the law releases a contact; the stiff limit for
  /// laws whose ratio depends on the stiffness); null when no closed form is known.
  double (*rebound)(double restitution) = nullptr;
};

/// Every law, the default (impulse) first.
std::span<const ContactLawInfo> contact_laws();
/// @throws InputError(key, "\"name\"", "expected impulse, kelvin, ...") for a name not in the table.
const ContactLawInfo& contact_law_info(std::string_view name, const std::string& key = "contact.law");
/// "impulse, kelvin, hertzdamp or jankowski".
std::string contact_law_names();
/// The law's damping parameter for restitution e, named by law.damping_key; 0 for impulse.
/// @pre e ∈ [0, 1] (jankowski, hertzdamp-ye: e > 0).
double contact_damping(const ContactLawInfo& law, double restitution);
bool supports(const ContactLawInfo& law, const MethodInfo& method);
/// @throws InputError (key `contact.law`) naming the law and the method when the method cannot
///   run the law (hht and exact resolve contacts by impulses only).
void require_supported(const ContactLawInfo& law, const MethodInfo& method);
/// Text for `--help` of --contact-law.
std::string contact_laws_help();
/// Text for `--help` of --contact-stiffness: each law's key, unit and default.
std::string contact_stiffness_help();

}  // namespace pounding::analysis
