#include "pounding/io/record_list.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <optional>
#include <string_view>
#include <type_traits>

#include "pounding/excitation/record_choice.hpp"
#include "pounding/input_error.hpp"

namespace pounding::io {
namespace {

using excitation::RecordChoice;

/// The most bytes of a list file: 10'000 lines of a path and a few options.
constexpr std::uintmax_t kMaxListBytes = 4 << 20;

/// The field of a list line that sets the excitation key `key` (as with_record() names it).
const std::map<std::string, std::string>& field_of_key() {
  static const std::map<std::string, std::string> kFields = {{"excitation.file", "file"},
                                                             {"excitation.format", "format"},
                                                             {"excitation.units", "units"},
                                                             {"excitation.dt_s", "dt_s"},
                                                             {"excitation.accel_column", "accel_column"},
                                                             {"excitation.scale_factor", "scale_factor"},
                                                             {"excitation.scale_to_pga_g", "scale_to_pga_g"},
                                                             {"excitation.second.file", "record2"},
                                                             {"excitation.second.accel_column", "record2_column"},
                                                             {"excitation.scale_to_sa", "scale_to_sa"},
                                                             {"excitation.direction_deg", "direction_deg"}};
  return kFields;
}

/// One line being read, for errors that name `list:line`.
class ListLine {
 public:
  ListLine(std::string where, std::string_view text) : where_(std::move(where)), text_(text) {}

  const std::string& where() const { return where_; }
  InputError error(const std::string& field, const std::string& value, const std::string& reason) const {
    return InputError(field, value, reason, where_);
  }

  /// The next whitespace-separated word, or a double-quoted one; empty at the end of the line.
  std::optional<std::string> next_word() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    if (at_ == text_.size()) return std::nullopt;
    if (text_[at_] == '"') {
      const std::size_t close = text_.find('"', at_ + 1);
      if (close == std::string_view::npos) throw error("file", std::string(text_.substr(at_)), "no closing quote");
      std::string word(text_.substr(at_ + 1, close - at_ - 1));
      at_ = close + 1;
      return word;
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    return std::string(text_.substr(start, at_ - start));
  }

  /// Remembers how this line spelled a field (`scale_factor` or its alias `scale`), so that an
  /// error found later names it as written.
  void spelled(const std::string& field, const std::string& as_written) { spelling_[field] = as_written; }
  /// As the line wrote `field` (a field it did not write: its own name).
  std::string spelling(const std::string& field) const {
    const auto found = spelling_.find(field);
    return found != spelling_.end() ? found->second : field;
  }

  template <class Number>
  Number number(const std::string& field, const std::string& value) const {
    Number parsed{};
    const auto [end, status] = std::from_chars(value.data(), value.data() + value.size(), parsed);
    if (status != std::errc() || end != value.data() + value.size()) {
      throw error(field, value, std::is_integral_v<Number> ? "expected a whole number" : "expected a number");
    }
    return parsed;
  }

 private:
  std::string where_;
  std::string_view text_;
  std::size_t at_ = 0;
  std::map<std::string, std::string> spelling_;
};

/// A field by its scene name: the scaling fields' short names, which the lists had first, are
/// kept as aliases (as `--scale` and `--pga-g` are) of the scene's names the docs give.
const std::string& scene_name(const std::string& field) {
  static const std::map<std::string, std::string> kAliases = {
      {"scale", "scale_factor"}, {"pga_g", "scale_to_pga_g"}, {"sa", "scale_to_sa"}};
  const auto found = kAliases.find(field);
  return found != kAliases.end() ? found->second : field;
}

/// Sets the field `field` of `choice` from its text (a pair's record2 resolved against `folder`).
/// @throws InputError for an unknown or repeated field.
void set_field(ListLine& line, const std::string& written, const std::string& value,
               const std::filesystem::path& folder, RecordChoice& choice) {
  const std::string& field = scene_name(written);
  line.spelled(field, written);
  auto once = [&](auto& slot, auto parsed) {
    if (slot) throw line.error(written, value, "given twice on this line");
    slot = parsed;
  };
  if (field == "format") return once(choice.format, value);
  if (field == "units") return once(choice.units, value);
  if (field == "dt_s") return once(choice.dt_s, line.number<double>(written, value));
  if (field == "accel_column") return once(choice.accel_column, line.number<int>(written, value));
  if (field == "scale_factor") return once(choice.scale_factor, line.number<double>(written, value));
  if (field == "scale_to_pga_g") return once(choice.pga_g, line.number<double>(written, value));
  if (field == "scale_to_sa") return once(choice.sa, value);
  if (field == "direction_deg") return once(choice.direction_deg, line.number<double>(written, value));
  if (field == "record2") {
    const std::filesystem::path second(value);
    return once(choice.second_file, (second.is_absolute() ? second : folder / second).lexically_normal());
  }
  if (field == "record2_column") return once(choice.second_accel_column, line.number<int>(written, value));
  throw line.error(written, value,
                   "unknown field (expected format, units, dt_s, accel_column, scale_factor, scale_to_pga_g, "
                   "scale_to_sa, direction_deg, record2 or record2_column; scale, pga_g and sa are short for the "
                   "scaling fields)");
}

/// `base` with `choice` applied; errors name the list line and the field.
analysis::RecordEntry entry(const ListLine& line, const RecordChoice& choice, const excitation::ExcitationSpec& base) {
  try {
    // A pair is named by both files ("kobe.txt+kobe.txt" for two columns of one).
    const std::string name = choice.second_file ? fmt::format("{}+{}", choice.file->filename().string(),
                                                              choice.second_file->filename().string())
                                                : choice.file->filename().string();
    return {name, line.where(), excitation::with_record(base, choice), choice};
  } catch (const InputError& error) {
    const auto field = field_of_key().find(error.key());
    throw line.error(field != field_of_key().end() ? line.spelling(field->second) : error.key(), error.value(),
                     error.reason());
  }
}

std::string read_text(const std::filesystem::path& file) {
  std::error_code error;
  const auto size = std::filesystem::file_size(file, error);
  if (error || size > kMaxListBytes) {
    throw InputError("--records", file.string(), fmt::format("a record list may hold at most {} bytes", kMaxListBytes));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("--records", file.string(), "cannot open the record list");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<analysis::RecordEntry> read_list_file(const std::filesystem::path& file,
                                                  const excitation::ExcitationSpec& base) {
  const std::string text = read_text(file);
  std::vector<analysis::RecordEntry> records;
  std::size_t begin = 0;
  for (int number = 1; begin < text.size(); ++number) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string_view content(text.data() + begin, end - begin);
    begin = end + 1;
    if (content.find('\0') != std::string_view::npos) {
      throw InputError("--records", fmt::format("{}:{}", file.string(), number), "the line holds a NUL byte");
    }
    content = content.substr(0, content.find('#'));
    ListLine line(fmt::format("{}:{}", file.string(), number), content);
    const std::optional<std::string> path = line.next_word();
    if (!path) continue;  // blank or comment
    RecordChoice choice;
    const std::filesystem::path record(*path);
    choice.file = (record.is_absolute() ? record : file.parent_path() / record).lexically_normal();
    while (const std::optional<std::string> word = line.next_word()) {
      const std::size_t equals = word->find('=');
      if (equals == std::string::npos || equals == 0) {
        throw line.error("", *word, "expected field=value after the record's path");
      }
      set_field(line, word->substr(0, equals), word->substr(equals + 1), file.parent_path(), choice);
    }
    if (records.size() == kMaxRecordsInSet) {
      throw InputError("--records", file.string(), fmt::format("a set may hold at most {} records", kMaxRecordsInSet));
    }
    records.push_back(entry(line, choice, base));
  }
  return records;
}

bool is_at2(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return extension == ".AT2";
}

std::vector<analysis::RecordEntry> read_folder(const std::filesystem::path& folder,
                                               const excitation::ExcitationSpec& base) {
  std::vector<std::filesystem::path> files;
  std::error_code error;
  std::filesystem::directory_iterator listing(folder, error);
  if (error) throw InputError("--records", folder.string(), "cannot list the folder: " + error.message());
  for (const auto& item : listing) {
    if (item.is_regular_file() && is_at2(item.path())) files.push_back(item.path());
    if (files.size() > kMaxRecordsInSet) {
      throw InputError("--records", folder.string(),
                       fmt::format("a set may hold at most {} records", kMaxRecordsInSet));
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<analysis::RecordEntry> records;
  for (const std::filesystem::path& file : files) {
    RecordChoice choice{.file = file, .format = "peer-at2", .units = "g"};
    records.push_back(entry(ListLine(file.string(), ""), choice, base));
  }
  return records;
}

}  // namespace

std::vector<analysis::RecordEntry> read_record_list(const std::filesystem::path& list_or_folder,
                                                    const excitation::ExcitationSpec& scene_excitation) {
  std::error_code error;
  std::vector<analysis::RecordEntry> records;
  if (std::filesystem::is_directory(list_or_folder, error)) {
    records = read_folder(list_or_folder, scene_excitation);
  } else if (std::filesystem::is_regular_file(list_or_folder, error)) {
    records = read_list_file(list_or_folder, scene_excitation);
  } else {
    throw InputError("--records", list_or_folder.string(), "no such record list or folder");
  }
  if (records.empty()) {
    throw InputError(
        "--records", list_or_folder.string(),
        std::filesystem::is_directory(list_or_folder) ? "the folder holds no .AT2 file" : "the list names no record");
  }
  return records;
}

}  // namespace pounding::io
