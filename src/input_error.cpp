#include "pounding/input_error.hpp"

#include <fmt/format.h>

namespace pounding {
namespace {

/// A key or value as the message shows it: cut after 200 characters (a 500 kB key typed by
/// mistake would otherwise make a 500 kB message); the error's fields keep it whole.
std::string shown(const std::string& text) {
  constexpr std::size_t kMaxShown = 200;
  if (text.size() <= kMaxShown) return text;
  return fmt::format("{}... ({} characters)", text.substr(0, kMaxShown), text.size());
}

std::string compose(const std::string& file, const std::string& key, const std::string& value,
                    const std::string& reason) {
  std::string message = file.empty() ? std::string{} : shown(file) + ": ";
  if (!key.empty()) message += shown(key);
  if (!value.empty()) message += (key.empty() ? "" : " = ") + shown(value);
  if (!key.empty() || !value.empty()) message += ": ";
  return message + reason;
}

}  // namespace

InputError::InputError(std::string key, std::string value, std::string reason, std::string file)
    : std::runtime_error(compose(file, key, value, reason)),
      file_(std::move(file)),
      key_(std::move(key)),
      value_(std::move(value)),
      reason_(std::move(reason)) {}

InputError InputError::in_context(const std::string& file, const std::string& key_prefix) const {
  std::string key = key_;
  if (!key_prefix.empty()) key = key.empty() ? key_prefix : key_prefix + "." + key;
  return InputError(key, value_, reason_, file_.empty() ? file : file_);
}

InputError InputError::renamed(const std::map<std::string, std::string>& names, const std::string& file) const {
  const auto found = names.find(key_.substr(0, key_.find('[')));
  if (found == names.end()) return *this;
  return InputError(found->second, value_, reason_, file_.empty() ? file : file_);
}

std::string format_value(double value) { return fmt::format("{}", value); }

std::string range_text(const Range& range) {
  const std::string interval = range.shown.empty() ? fmt::format("{}{}, {}]", range.min_open ? "(" : "[",
                                                                 format_value(range.min), format_value(range.max))
                                                   : std::string(range.shown);
  return range.unit.empty() ? interval : interval + " " + std::string(range.unit);
}

void require_range(const std::string& key, double value, const Range& range) {
  const bool above_min = range.min_open ? value > range.min : value >= range.min;
  if (above_min && value <= range.max) return;  // false for NaN
  throw InputError(key, format_value(value), "must lie in " + range_text(range));
}

}  // namespace pounding
