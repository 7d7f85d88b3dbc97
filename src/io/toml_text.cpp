#include "toml_text.hpp"

#include <cstdint>
#include <fmt/format.h>

namespace pounding::io::detail {
namespace {

/// Length of the UTF-8 sequence starting with `lead` (0 if `lead` cannot start one).
std::size_t sequence_length(unsigned char lead) {
  return lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xE ? 3 : (lead >> 3) == 0x1E ? 4 : 0;
}

/// The code point of the well-formed sequence at text[i] of `length` bytes.
std::uint32_t decode(std::string_view text, std::size_t i, std::size_t length) {
  std::uint32_t code =
      length == 1 ? static_cast<unsigned char>(text[i]) : static_cast<unsigned char>(text[i]) & (0xFFu >> (length + 1));
  for (std::size_t k = 1; k < length; ++k) code = (code << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
  return code;
}

std::string escaped(std::uint32_t code) {
  return code <= 0xFFFF ? fmt::format("\\u{:04X}", code) : fmt::format("\\U{:08X}", code);
}

/// Walks a TOML document once, knowing at each character whether it is in a comment or in
/// which kind of string, and writes the ASCII form.
class Asciifier {
 public:
  explicit Asciifier(std::string_view text) : text_(text) {}

  AsciiToml run() {
    while (i_ < text_.size() && !result_.stray_non_ascii) {
      if (in_comment_) {
        comment_character();
      } else if (quote_) {
        string_character();
      } else {
        plain_character();
      }
    }
    return std::move(result_);
  }

 private:
  bool starts_with(std::string_view s) const { return text_.substr(i_, s.size()) == s; }
  void copy(std::size_t count) {
    for (std::size_t k = 0; k < count && i_ < text_.size(); ++k) advance_over(text_[i_], 1);
  }
  void advance_over(char first, std::size_t length) {
    if (first == '\n') {
      ++position_.line;
      position_.column = 1;
    } else {
      position_.column += length;
    }
    result_.text.append(text_.substr(i_, length));
    i_ += length;
  }
  /// A non-ASCII character at i_: its length in bytes and code point.
  std::pair<std::size_t, std::uint32_t> wide() const {
    const std::size_t length = sequence_length(static_cast<unsigned char>(text_[i_]));
    return {length, decode(text_, i_, length)};
  }
  void replace_wide(const std::string& with) {
    const auto [length, code] = wide();
    result_.text += with.empty() ? escaped(code) : with;
    position_.column += length;
    i_ += length;
  }

  void comment_character() {
    const char c = text_[i_];
    if (c == '\n') in_comment_ = false;
    if (static_cast<unsigned char>(c) >= 0x80) {
      replace_wide("?");  // a comment's content means nothing
    } else {
      copy(1);
    }
  }

  void plain_character() {
    const char c = text_[i_];
    if (static_cast<unsigned char>(c) >= 0x80) {
      if (i_ == 0 && starts_with("\xEF\xBB\xBF")) {  // a byte-order mark: toml++ skips it too
        i_ += 3;
        return;
      }
      result_.stray_non_ascii = position_;
      return;
    }
    if (c == '#') {
      in_comment_ = true;
      copy(1);
    } else if (c == '"' || c == '\'') {
      open_string(c);
    } else {
      copy(1);
    }
  }

  void open_string(char quote) {
    quote_ = quote;
    multi_line_ = starts_with(std::string(3, quote));
    literal_ = quote == '\'';
    // A literal string holding non-ASCII text becomes a basic one (escapes need one).
    converted_ = literal_ && holds_non_ascii();
    result_.text += std::string(multi_line_ ? 3 : 1, converted_ ? '"' : quote);
    const std::size_t length = multi_line_ ? 3 : 1;
    position_.column += length;
    i_ += length;
  }

  /// Whether the literal string opening at i_ holds non-ASCII text before it closes.
  bool holds_non_ascii() const {
    const std::string close(multi_line_ ? 3 : 1, quote_);
    const std::size_t end = text_.find(close, i_ + close.size());
    const std::size_t stop = multi_line_ ? end : std::min(end, text_.find('\n', i_ + 1));
    for (std::size_t k = i_; k < std::min(stop, text_.size()); ++k) {
      if (static_cast<unsigned char>(text_[k]) >= 0x80) return true;
    }
    return false;
  }

  void string_character() {
    const char c = text_[i_];
    if (closes_string()) return;
    if (static_cast<unsigned char>(c) >= 0x80) {
      replace_wide("");
    } else if (c == '\\' && !literal_) {
      if (i_ + 1 < text_.size() && static_cast<unsigned char>(text_[i_ + 1]) >= 0x80) {
        result_.stray_non_ascii = position_;  // an escape of a non-ASCII character: invalid
        return;
      }
      copy(2);  // the escaped character never closes the string
    } else if (converted_ && (c == '\\' || c == '"')) {
      result_.text += '\\';  // literal text in a basic string
      copy(1);
    } else {
      if (c == '\n' && !multi_line_) quote_ = 0;  // an unterminated string: toml++ reports it
      copy(1);
    }
  }

  /// At the closing delimiter: writes it (with the up to two quotes a multi-line string may end
  /// with as content) and leaves the string.
  bool closes_string() {
    if (text_[i_] != quote_) return false;
    const char close = converted_ ? '"' : quote_;
    if (!multi_line_) {
      result_.text += close;
      ++position_.column;
      ++i_;
      quote_ = 0;
      return true;
    }
    std::size_t run = 0;
    while (i_ + run < text_.size() && text_[i_ + run] == quote_) ++run;
    if (run < 3) {
      for (std::size_t k = 0; k < run; ++k) result_.text += converted_ ? "\\\"" : std::string(1, quote_);
    } else {
      for (std::size_t k = 0; k < run - 3; ++k) result_.text += converted_ ? "\\\"" : std::string(1, quote_);
      result_.text += std::string(3, close);
      quote_ = 0;
    }
    position_.column += run;
    i_ += run;
    return true;
  }

  std::string_view text_;
  std::size_t i_ = 0;
  TextPosition position_;
  AsciiToml result_;
  bool in_comment_ = false;
  char quote_ = 0;  // the open string's quote character, 0 outside strings
  bool multi_line_ = false, literal_ = false, converted_ = false;
};

}  // namespace

std::optional<TextPosition> find_invalid_utf8(std::string_view text) {
  TextPosition at;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = sequence_length(static_cast<unsigned char>(text[i]));
    if (length == 0 || i + length > text.size()) return at;
    for (std::size_t k = 1; k < length; ++k) {
      if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return at;
    }
    const std::uint32_t code = decode(text, i, length);
    static constexpr std::uint32_t kShortest[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < kShortest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return at;
    if (text[i] == '\n') {
      ++at.line;
      at.column = 1;
    } else {
      at.column += length;
    }
    i += length;
  }
  return std::nullopt;
}

AsciiToml ascii_toml(std::string_view text) { return Asciifier(text).run(); }

}  // namespace pounding::io::detail
