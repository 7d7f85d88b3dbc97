#pragma once
// Reads the records of `pounding gap --records`: a list file, or a folder of PEER .AT2 files.
//
// A list file holds one record a line: its path (relative to the list file's folder; in double
// quotes if it holds spaces), then optional `field=value` pairs where the record differs from
// the scene's [excitation]: format, units, dt_s, accel_column, scale, pga_g, direction_deg
// (excitation::RecordChoice says what each replaces and what the new file drops). `#` starts a
// comment; blank lines are skipped.

#include <filesystem>
#include <string>
#include <vector>

#include "pounding/analysis/record_set.hpp"
#include "pounding/excitation/ground_motion.hpp"

namespace pounding::io {

/// The most records a set may hold: a set is a design suite (7 to 40 records), not a database.
inline constexpr std::size_t kMaxRecordsInSet = 10'000;

/// The records of a list file or folder, each as `scene_excitation` with the line's choices applied
/// and validated (files must exist; they are read later, run by run). A folder gives every file
/// ending in .AT2 (any case) in it, sorted by name, read as peer-at2 in g.
/// @throws InputError naming the list file and line (`set.txt:4`), the field and its value for a
///   malformed line, an unknown field, a bad value or a missing record file; naming `--records`
///   for a missing list, an empty one, or more than kMaxRecordsInSet records.
std::vector<analysis::RecordEntry> read_record_list(const std::filesystem::path& list_or_folder,
                                                    const excitation::ExcitationSpec& scene_excitation);

}  // namespace pounding::io
