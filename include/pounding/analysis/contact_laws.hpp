#pragma once
// The table of contact laws, like the methods registry (methods.hpp): per law its name, a
// one-line description, the [contact] keys that apply to it, its published default stiffness and
// the methods that run it. Validation, `--help` and summary.json read it.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/analysis/methods.hpp"
#include "pounding/contact/kelvin.hpp"

namespace pounding::analysis {

struct ContactLawInfo {
  std::string_view name;
  std::string_view description;          // one line
  contact::ContactLaw law;
  std::vector<std::string_view> keys{};  // [contact] keys that only this kind of law uses
  double default_stiffness_kN_per_m = 0.0;
  std::string_view stiffness_source;     // where the default comes from
  std::vector<std::string_view> methods{};  // names of the methods that run it; empty: every method
  /// The ratio of separation to approach speed a lone contact of this law achieves for the
  /// scene's restitution e (closed form, as the law releases a contact; the stiff limit for
  /// laws whose ratio depends on the stiffness); null when no closed form is known.
  double (*rebound)(double restitution) = nullptr;
};

/// Every law, the default (impulse) first.
std::span<const ContactLawInfo> contact_laws();
/// @throws InputError(key, "\"name\"", "expected impulse or kelvin") for a name not in the table.
const ContactLawInfo& contact_law_info(std::string_view name, const std::string& key = "contact.law");
/// "impulse or kelvin".
std::string contact_law_names();
bool supports(const ContactLawInfo& law, const MethodInfo& method);
/// @throws InputError (key `contact.law`) naming the law and the method when the method cannot
///   run the law (hht and exact resolve contacts by impulses only).
void require_supported(const ContactLawInfo& law, const MethodInfo& method);
/// Text for `--help` of --contact-law.
std::string contact_laws_help();

}  // namespace pounding::analysis
