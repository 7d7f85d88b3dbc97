#include "pounding/excitation/record_reader.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <regex>
#include <string>

#include "pounding/input_error.hpp"

namespace pounding::excitation {
namespace {

struct Line {
  int number = 0;  // 1-based, as an editor shows it
  std::string text;
};

std::vector<Line> read_lines(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("", "", "cannot open the record file", file.string());
  std::vector<Line> lines;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    ++number;
    // A NUL ends a number's text for strtod, so "0.0\0 9" would read as 0.0: refuse the line.
    if (text.find('\0') != std::string::npos) {
      throw InputError(fmt::format("line {}", number), "", "holds a NUL byte: not a text record file", file.string());
    }
    lines.push_back({number, text});
  }
  return lines;
}

bool is_blank(const std::string& text) { return text.find_first_not_of(" \t") == std::string::npos; }

bool is_comment(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  return first != std::string::npos && (text[first] == '#' || text[first] == '%');
}

std::vector<std::string> split_fields(const std::string& text) {
  std::vector<std::string> fields;
  std::string field;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == ',') {
      if (!field.empty()) fields.push_back(std::move(field));
      field.clear();
    } else {
      field += c;
    }
  }
  if (!field.empty()) fields.push_back(std::move(field));
  return fields;
}

class Parser {
 public:
  /// @throws InputError once a record grows past kMaxRecordSamples (a wrong file, not a record).
  void check_count(std::size_t count, const Line& line) const {
    if (count > kMaxRecordSamples) {
      throw error(line, 0, fmt::format("sample {}", count),
                  fmt::format("the record exceeds the limit of {} samples", kMaxRecordSamples));
    }
  }

  explicit Parser(const std::filesystem::path& file) : file_(file.string()) {}

  double number(const std::string& text, const Line& line, std::size_t field) const {
    // strtod rather than from_chars: Fortran-style ".9984852E-03" and "1.0D-03" both occur.
    std::string normalised = text;
    for (char& c : normalised) {
      if (c == 'D' || c == 'd') c = 'E';
    }
    char* end = nullptr;
    const double value = std::strtod(normalised.c_str(), &end);
    if (end == normalised.c_str() || *end != '\0') {
      throw error(line, field, text, "is not a number");
    }
    if (!std::isfinite(value)) throw error(line, field, text, "is not finite");
    return value;
  }

  InputError error(const Line& line, std::size_t field, const std::string& value, const std::string& reason) const {
    const std::string key =
        field == 0 ? fmt::format("line {}", line.number) : fmt::format("line {}, field {}", line.number, field);
    return InputError(key, "'" + value + "'", reason, file_);
  }

  InputError error(const std::string& reason) const { return InputError("", "", reason, file_); }

 private:
  std::string file_;
};

std::vector<double> times_from_spacing(std::size_t count, double dt_s) {
  std::vector<double> time(count);
  for (std::size_t i = 0; i < count; ++i) time[i] = static_cast<double>(i) * dt_s;
  return time;
}

struct At2Header {
  long npts = 0;
  double dt_s = 0.0;
};

At2Header parse_at2_header(const Line& line, const Parser& parser) {
  // Older PEER style: "NPTS=  1559, DT= .02000 SEC"; NGA-West2: "  5372    0.0100    NPTS, DT".
  static const std::regex older(R"(NPTS\s*=\s*([^,\s]+)\s*,?\s*DT\s*=\s*([^,\s]+))", std::regex::icase);
  static const std::regex west2(R"(^\s*(\S+)[\s,]+(\S+)\s+NPTS\s*,\s*DT)", std::regex::icase);
  // std::regex backtracks: bound the text it sees (a real header line is under 80 characters).
  constexpr std::size_t kMaxHeaderLength = 200;
  if (line.text.size() > kMaxHeaderLength) {
    throw parser.error(line, 0, line.text.substr(0, 40) + "...",
                       fmt::format("a PEER header line has at most {} characters", kMaxHeaderLength));
  }
  std::smatch match;
  if (!std::regex_search(line.text, match, older) && !std::regex_search(line.text, match, west2)) {
    throw parser.error(line, 0, line.text, "expected the PEER header line 'NPTS= n, DT= dt SEC' or 'n dt NPTS, DT'");
  }
  At2Header header;
  const double npts = parser.number(match[1].str(), line, 0);
  if (npts < 1 || npts != std::floor(npts)) {
    throw parser.error(line, 0, match[1].str(), "NPTS must be a positive whole number");
  }
  if (npts > static_cast<double>(kMaxRecordSamples)) {  // also keeps the conversion below defined
    throw parser.error(line, 0, match[1].str(), fmt::format("NPTS exceeds the limit of {} samples", kMaxRecordSamples));
  }
  header.npts = static_cast<long>(npts);
  header.dt_s = parser.number(match[2].str(), line, 0);
  if (!(header.dt_s > 0.0)) throw parser.error(line, 0, match[2].str(), "DT must be positive");
  return header;
}

RecordSamples read_peer_at2(const std::vector<Line>& lines, const Parser& parser) {
  constexpr std::size_t kHeaderLines = 4;
  if (lines.size() < kHeaderLines) {
    throw parser.error(fmt::format("a PEER AT2 file needs {} header lines, found {}", kHeaderLines, lines.size()));
  }
  const At2Header header = parse_at2_header(lines[3], parser);
  RecordSamples samples;
  for (std::size_t i = kHeaderLines; i < lines.size(); ++i) {
    // An AT2 file separates its values by spaces: a comma is a decimal comma, which would split
    // one value into two (and then the count would be blamed on the header) or misread it.
    if (lines[i].text.find(',') != std::string::npos) {
      throw parser.error(lines[i], 0, lines[i].text,
                         "holds a comma: PEER AT2 values are written with a decimal point and separated by spaces");
    }
    const auto fields = split_fields(lines[i].text);
    for (std::size_t f = 0; f < fields.size(); ++f) {
      samples.accel.push_back(parser.number(fields[f], lines[i], f + 1));
    }
    parser.check_count(samples.accel.size(), lines[i]);
  }
  if (static_cast<long>(samples.accel.size()) != header.npts) {
    throw parser.error(
        lines[3], 0, fmt::format("NPTS={}", header.npts),
        fmt::format("the header announces {} values but the file holds {}", header.npts, samples.accel.size()));
  }
  samples.time_s = times_from_spacing(samples.accel.size(), header.dt_s);
  return samples;
}

const std::string& field_at(const std::vector<std::string>& fields, int column, const Line& line,
                            const Parser& parser) {
  if (column < 1 || static_cast<std::size_t>(column) > fields.size()) {
    throw parser.error(line, 0, line.text,
                       fmt::format("has {} columns, column {} was asked for", fields.size(), column));
  }
  return fields[column - 1];
}

RecordSamples read_columns(const std::vector<Line>& lines, const RecordReadOptions& options, const Parser& parser) {
  const int accel_column = options.accel_column.value_or(2);
  RecordSamples samples;
  for (const Line& line : lines) {
    if (is_blank(line.text) || is_comment(line.text)) continue;
    const auto fields = split_fields(line.text);
    const double t = parser.number(field_at(fields, options.time_column, line, parser), line, options.time_column);
    const double a = parser.number(field_at(fields, accel_column, line, parser), line, accel_column);
    if (!samples.time_s.empty() && !(t > samples.time_s.back())) {
      throw parser.error(line, options.time_column, fields[options.time_column - 1],
                         fmt::format("times must increase (previous sample at {} s)", samples.time_s.back()));
    }
    samples.time_s.push_back(t);
    samples.accel.push_back(a);
    parser.check_count(samples.accel.size(), line);
  }
  return samples;
}

RecordSamples read_single(const std::vector<Line>& lines, const RecordReadOptions& options, const Parser& parser) {
  RecordSamples samples;
  for (const Line& line : lines) {
    if (is_blank(line.text) || is_comment(line.text)) continue;
    const auto fields = split_fields(line.text);
    if (options.accel_column) {
      const int column = *options.accel_column;
      samples.accel.push_back(parser.number(field_at(fields, column, line, parser), line, column));
    } else {
      for (std::size_t f = 0; f < fields.size(); ++f) samples.accel.push_back(parser.number(fields[f], line, f + 1));
    }
    parser.check_count(samples.accel.size(), line);
  }
  samples.time_s = times_from_spacing(samples.accel.size(), *options.dt_s);
  return samples;
}

}  // namespace

std::optional<RecordFormat> parse_record_format(std::string_view name) {
  if (name == "peer-at2") return RecordFormat::peer_at2;
  if (name == "columns") return RecordFormat::columns;
  if (name == "single") return RecordFormat::single;
  return std::nullopt;
}

RecordSamples read_record(const std::filesystem::path& file, const RecordReadOptions& options) {
  const Parser parser(file);
  if (options.format == RecordFormat::single && !(options.dt_s && *options.dt_s > 0.0)) {
    throw parser.error("format 'single' needs a positive time step (excitation.dt_s)");
  }
  const std::vector<Line> lines = read_lines(file);
  RecordSamples samples;
  switch (options.format) {
    case RecordFormat::peer_at2: samples = read_peer_at2(lines, parser); break;
    case RecordFormat::columns: samples = read_columns(lines, options, parser); break;
    case RecordFormat::single: samples = read_single(lines, options, parser); break;
  }
  if (samples.accel.empty()) throw parser.error("the record holds no samples");
  if (samples.accel.size() < 2) throw parser.error("the record needs at least two samples");
  return samples;
}

}  // namespace pounding::excitation
