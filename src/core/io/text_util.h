// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#pragma once

#include <charconv>
#include <cstddef>
#include <string_view>
#include <system_error>
#include <vector>

/// @file text_util.h
/// Locale-independent tokenizing and number parsing for the text formats (STL, OBJ, PLY).
/// std::from_chars is used instead of strtod/streams so a ROS node that sets a locale with a
/// decimal comma cannot change how files are read.

namespace freeform_inspection {
namespace io_internal {

inline bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

/// Iterates over the lines of a text, without their '\n' or "\r\n" ending.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  /// @return false when the text is exhausted.
  bool next(std::string_view* line) {
    if (pos_ >= text_.size()) {
      return false;
    }
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) {
      end = text_.size();
    }
    *line = text_.substr(pos_, end - pos_);
    if (!line->empty() && line->back() == '\r') {
      line->remove_suffix(1);
    }
    pos_ = end + 1;
    ++line_number_;
    return true;
  }

  /// 1-based number of the line last returned by next().
  std::size_t lineNumber() const { return line_number_; }
  /// Offset of the first byte after the line last returned by next().
  std::size_t offset() const { return pos_ < text_.size() ? pos_ : text_.size(); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_number_ = 0;
};

/// Next whitespace-separated token of `text` at or after `*pos`; advances `*pos` past it.
inline bool nextToken(std::string_view text, std::size_t* pos, std::string_view* token) {
  std::size_t i = *pos;
  while (i < text.size() && isSpace(text[i])) {
    ++i;
  }
  if (i >= text.size()) {
    *pos = i;
    return false;
  }
  const std::size_t begin = i;
  while (i < text.size() && !isSpace(text[i])) {
    ++i;
  }
  *token = text.substr(begin, i - begin);
  *pos = i;
  return true;
}

/// Splits a header line into its whitespace-separated words (views into `line`).
inline std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> result;
  std::size_t pos = 0;
  std::string_view token;
  while (nextToken(line, &pos, &token)) {
    result.push_back(token);
  }
  return result;
}

/// Parses the whole token as a double ("1", "-2.5e3", "+4", "nan", "inf").
inline bool parseDouble(std::string_view token, double* value) {
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end && !token.empty();
}

/// Parses the whole token as a signed integer.
inline bool parseInteger(std::string_view token, long long* value) {
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, *value);
  return result.ec == std::errc() && result.ptr == end && !token.empty();
}

}  // namespace io_internal
}  // namespace freeform_inspection
