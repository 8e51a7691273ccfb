// Contract: small pure helpers for the line-oriented readers (no I/O).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace smart::grid {

// Splits into lines on '\n', dropping a trailing '\r' from each; a final newline adds no line.
std::vector<std::string_view> split_lines(std::string_view text);
std::string_view trim(std::string_view s);
std::vector<std::string_view> split(std::string_view s, char sep);
std::vector<std::string_view> split_whitespace(std::string_view s);
// Whole-token integer / number parsing; nullopt unless the entire token is a valid number.
std::optional<long long> parse_int(std::string_view s);
std::optional<double> parse_double(std::string_view s);
// Shortens long input for messages: at most `max` characters, "..." appended when cut.
std::string excerpt(std::string_view s, std::size_t max = 40);

}  // namespace smart::grid
