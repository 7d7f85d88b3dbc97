#pragma once
// One user-facing key of a plain settings struct, declared once as a row: [contact]'s keys
// (analysis::ContactSettings, scene.hpp), the run limits (analysis::RunLimits, run_scene.hpp),
// [building.limit_states] (model::DriftLimits) and [building.shear_capacity]
// (model::ShearCapacityFormula), both in analysis/limit_states.hpp, and [building.hysteresis]
// (model::HystereticLaw, model/building.hpp). From the rows come
// the scene reader, the command-line options, the Python keywords, the range checks, `pounding
// settings` and the docs' tables, so a new key is one row plus the line that uses it. (The
// [solver] keys have their own row type, SettingSpec in methods.hpp, because each is kept as given
// and resolved per method.)

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pounding/input_error.hpp"

namespace pounding {

/// A value given for a key on the command line or from Python: whole numbers for `long` keys.
using KeyValue = std::variant<long, double, std::string>;

template <typename Owner>
struct KeySpec {
  std::string_view key;       // the key, `<section>.<key>` in errors and summary.json
  std::string_view option{};  // the command-line option that replaces it; empty: none. Python's
                              // keyword is the option without `--`, `-` as `_` (python_keyword())
  /// A number, an optional one, text, a whole number, true or false, or one number for every
  /// storey or a list of one a storey (storey 1 first; the reader spreads a single number).
  std::variant<double Owner::*, std::optional<double> Owner::*, std::string Owner::*, long Owner::*, bool Owner::*,
               std::vector<double> Owner::*>
      member;
  bool required = false;
  std::optional<Range> range = std::nullopt;  // numbers: the values accepted
  std::vector<std::string_view> choices{};    // text: the values accepted (empty: checked elsewhere)
  std::string_view description{};             // one line, with units
  std::string_view details{};                 // the docs' meaning column, after the description
  std::string_view default_note{};            // the docs' default column, when not the member's initialiser
  std::string_view type_note{};               // the docs' type column, when not the type and range (checked elsewhere)
  /// The values of the table's selector (e.g. hysteresis.law) under which the key may be given;
  /// empty: any. The reader refuses the key under another.
  std::vector<std::string_view> applies_to{};
  /// How the option's value is stored, when not by assignment to `member` (e.g. one option for
  /// two stiffness keys, the law deciding which).
  void (*set)(Owner&, const KeyValue&) = nullptr;
  /// The option's `--help` line, when not the description with the accepted values.
  std::string (*option_help)() = nullptr;
};

/// A number given as a whole number or not; none for text.
inline std::optional<double> number_of(const KeyValue& value) {
  if (const auto* whole = std::get_if<long>(&value)) return static_cast<double>(*whole);
  if (const auto* number = std::get_if<double>(&value)) return *number;
  return std::nullopt;
}

/// `a or b or c`, each choice quoted when `quote`: what a text key accepts, as `--help` and its
/// errors say it.
inline std::string or_list(const std::vector<std::string_view>& choices, bool quote) {
  std::string text;
  for (std::string_view choice : choices)
    text += fmt::format("{}{}{}{}", text.empty() ? "" : " or ", quote ? "\"" : "", choice, quote ? "\"" : "");
  return text;
}

/// "integer", "number" or "string": the type a key's reader expects.
template <typename Owner>
std::string_view type_name(const KeySpec<Owner>& spec) {
  if (std::holds_alternative<long Owner::*>(spec.member)) return "integer";
  if (std::holds_alternative<bool Owner::*>(spec.member)) return "boolean";
  return std::holds_alternative<std::string Owner::*>(spec.member) ? "string" : "number";
}

/// True for a key given as one number for every storey or as one a storey.
template <typename Owner>
bool is_per_storey(const KeySpec<Owner>& spec) {
  return std::holds_alternative<std::vector<double> Owner::*>(spec.member);
}

/// `restitution` for `--restitution`, `contact_law` for `--contact-law`; empty for no option.
inline std::string python_keyword(std::string_view option) {
  const std::size_t start = option.find_first_not_of('-');
  std::string keyword(start == std::string_view::npos ? std::string_view() : option.substr(start));
  std::replace(keyword.begin(), keyword.end(), '-', '_');
  return keyword;
}

/// A row's default as the docs print it: its note, or the initialiser of Owner's member
/// ("required" for a required key, empty for an unset optional or an empty list).
template <typename Owner>
std::string default_text(const KeySpec<Owner>& spec) {
  if (!spec.default_note.empty()) return std::string(spec.default_note);
  if (spec.required) return "required";
  const Owner defaults{};
  return std::visit(
      [&](auto Owner::*member) -> std::string {
        const auto& value = defaults.*member;
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::string>) {
          return fmt::format("\"{}\"", value);
        } else if constexpr (std::is_same_v<T, std::optional<double>>) {
          return value ? fmt::format("{}", *value) : std::string();
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          return value.empty() ? std::string() : fmt::format("{}", value.front());
        } else {
          return fmt::format("{}", value);
        }
      },
      spec.member);
}

/// The `--help` line of a key's option: its own, or the description with the accepted values and
/// the default.
template <typename Owner>
std::string option_help(const KeySpec<Owner>& spec) {
  if (spec.option_help != nullptr) return spec.option_help();
  const std::string accepted = spec.range             ? ", in " + range_text(*spec.range)
                               : spec.choices.empty() ? std::string()
                                                      : ": " + or_list(spec.choices, false);
  const std::string default_value = default_text(spec);
  return fmt::format("{}{}{}", spec.description, accepted,
                     default_value.empty() || spec.required ? "" : fmt::format(" (default {})", default_value));
}

/// Stores `value` in `owner` as the row says (its `set`, else assigned to its member).
/// @throws InputError(`<section>.<key>`, value, "expected ...") for a value of another type.
template <typename Owner>
void set_key(Owner& owner, const KeySpec<Owner>& spec, std::string_view section, const KeyValue& value) {
  if (spec.set != nullptr) return spec.set(owner, value);
  const std::string name = fmt::format("{}.{}", section, spec.key);
  std::visit(
      [&](auto Owner::*member) {
        auto& target = owner.*member;
        using T = std::decay_t<decltype(target)>;
        if constexpr (std::is_same_v<T, std::string>) {
          if (!std::holds_alternative<std::string>(value)) throw InputError(name, "", "expected a string");
          target = std::get<std::string>(value);
        } else if constexpr (std::is_same_v<T, long>) {
          if (!std::holds_alternative<long>(value)) throw InputError(name, "", "expected an integer");
          target = std::get<long>(value);
        } else if constexpr (std::is_same_v<T, bool>) {
          const auto* text = std::get_if<std::string>(&value);
          if (text == nullptr || (*text != "true" && *text != "false"))
            throw InputError(name, "", "expected true or false");
          target = *text == "true";
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          throw InputError(name, "", "is given in the scene file only (one number or one a storey)");
        } else {
          const std::optional<double> number = number_of(value);
          if (!number) throw InputError(name, std::get<std::string>(value), "expected a number");
          target = *number;
        }
      },
      spec.member);
}

/// Checks every row's value in `owner`: numbers against their range (an unset optional passes;
/// a list entry by entry, named `key[i]` from 1), text against its choices. Each range is
/// checked here and nowhere else (but for a single number a list stands for, which the scene
/// reader checks under the key typed).
/// @throws InputError(`<section>.<key>`, value, "must lie in ..." | "expected ...").
template <typename Owner>
void validate_keys(const Owner& owner, std::span<const KeySpec<Owner>> specs, std::string_view section) {
  for (const KeySpec<Owner>& spec : specs) {
    const std::string name = fmt::format("{}.{}", section, spec.key);
    std::visit(
        [&](auto Owner::*member) {
          const auto& value = owner.*member;
          using T = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<T, std::string>) {
            if (spec.choices.empty() ||
                std::find(spec.choices.begin(), spec.choices.end(), value) != spec.choices.end())
              return;
            throw InputError(name, fmt::format("\"{}\"", value), "expected " + or_list(spec.choices, true));
          } else if constexpr (std::is_same_v<T, std::optional<double>>) {
            if (value && spec.range) require_range(name, *value, *spec.range);
          } else if constexpr (std::is_same_v<T, std::vector<double>>) {
            for (std::size_t i = 0; i < value.size() && spec.range; ++i)
              require_range(fmt::format("{}[{}]", name, i + 1), value[i], *spec.range);
          } else if constexpr (std::is_same_v<T, bool>) {
            return;
          } else if (spec.range) {
            require_range(name, static_cast<double>(value), *spec.range);
          }
        },
        spec.member);
  }
}

}  // namespace pounding

namespace pounding::analysis {  // where the tables were declared first; their users name them so
using pounding::default_text;
using pounding::KeySpec;
using pounding::KeyValue;
using pounding::number_of;
using pounding::option_help;
using pounding::or_list;
using pounding::python_keyword;
using pounding::set_key;
using pounding::type_name;
using pounding::validate_keys;
}  // namespace pounding::analysis
