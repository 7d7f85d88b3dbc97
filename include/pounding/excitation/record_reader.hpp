#pragma once
// Readers for accelerogram files. They return the samples as written (file units, file times);
// conversion, cutting and scaling happen in ground_motion.hpp.

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace pounding::excitation {

enum class RecordFormat {
  peer_at2,  // PEER NGA: 3 text lines, then `NPTS= n, DT= dt SEC` or `n dt NPTS, DT`, then values
  columns,   // one sample a line: time and acceleration columns
  single,    // acceleration values only, any number a line, equally spaced by a given dt
};

/// The most samples a record may hold (10 million: a 3-hour record at 1 kHz, 160 MB in memory).
/// A larger count is a corrupt header or the wrong file, not an accelerogram.
inline constexpr std::size_t kMaxRecordSamples = 10'000'000;

/// Parses "peer-at2", "columns", "single"; empty when the name is unknown.
std::optional<RecordFormat> parse_record_format(std::string_view name);

struct RecordReadOptions {
  RecordFormat format = RecordFormat::peer_at2;
  /// `columns`: 1-based columns of time and acceleration. `single`: if set, the 1-based column
  /// of the acceleration in each line (for files with several components); otherwise every
  /// number in reading order.
  int time_column = 1;
  std::optional<int> accel_column{};
  /// `single` only: the sample spacing (s). Required there.
  std::optional<double> dt_s{};
};

/// Samples as read: strictly increasing times (s) and accelerations in the file's unit.
struct RecordSamples {
  std::vector<double> time_s;
  std::vector<double> accel;
};

/// Reads a record. Lines starting with `#` or `%` are comments in `columns` and `single` files;
/// CRLF line ends and a missing final newline are accepted.
/// @throws InputError naming the file, the line (and field) and the offending text for: a missing
///   or empty file, text in a number field, NaN/inf, NPTS disagreeing with the values,
///   non-positive dt, non-increasing times, a missing column, more than kMaxRecordSamples values.
RecordSamples read_record(const std::filesystem::path& file, const RecordReadOptions& options);

}  // namespace pounding::excitation
