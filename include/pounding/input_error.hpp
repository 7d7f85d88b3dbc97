#pragma once
// The one exception type for bad input: every layer that validates user data throws it.

#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pounding {

/// Bad input, located as precisely as the thrower knows: the file, the key (a dotted path
/// such as `building[2].mass_t[3]`, or `line 12` in a record file) and the offending value.
/// Layers that do not know the file (the model's validators) leave it empty; the reader that
/// does know it adds it with `in_file()` before the error reaches the user.
class InputError : public std::runtime_error {
 public:
  InputError(std::string key, std::string value, std::string reason, std::string file = {});

  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& value() const { return value_; }
  const std::string& reason() const { return reason_; }

  /// The same error seen from an enclosing scope: `file` is set if it was empty and
  /// `key_prefix` (e.g. `building[1]`) is put in front of the key.
  InputError in_context(const std::string& file, const std::string& key_prefix = {}) const;

  /// The same error blamed on what the user typed: when `names` (key → the CLI option or other
  /// name the user gave that key's value under) holds this error's key, indexes dropped
  /// (`output.peaks[2]` → `output.peaks`), the key becomes that name and `file` is set if it was
  /// empty; otherwise the error is returned unchanged, so a scene file's value keeps its key.
  InputError renamed(const std::map<std::string, std::string>& names, const std::string& file = {}) const;

 private:
  std::string file_, key_, value_, reason_;
};

/// Formats a number for an error message the way a user would type it (shortest round trip).
std::string format_value(double value);

/// The physical range a value must lie in, stated in the message when it does not.
struct Range {
  double min;
  double max;
  std::string_view unit = {};   // as printed after the bounds, e.g. "m" or "s"
  bool min_open = false;        // (min, …]: the bound itself is refused (e.g. a mass of 0)
  std::string_view shown = {};  // the interval as stated instead of the bounds' digits, e.g. "[-1/3, 0]"
};

/// "[min, max] unit" or "(min, max] unit", or `shown` with the unit.
std::string range_text(const Range& range);

/// @throws InputError(key, value, "must lie in " + range_text(range)) unless value lies in `range`
///   (NaN and infinities never do).
void require_range(const std::string& key, double value, const Range& range);

}  // namespace pounding
