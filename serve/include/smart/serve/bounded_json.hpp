// Contract: JSON from outside (an uploaded summary.json, a results folder given to --open) parsed
// within limits checked before and while parsing, so that no upload can crash or exhaust the
// server (issue 25: a 200 KB summary.json nested 100 000 deep was accepted, then crashed the
// server on the next GET when it was written out again). Pure; throws std::invalid_argument
// naming the source and the limit.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace smart::serve {

inline constexpr std::size_t kMaxJsonBytes = 16u << 20;  // a 10 000-robot summary is < 2 MB
inline constexpr int kMaxJsonDepth = 32;                 // summary.json nests 3 deep

nlohmann::json parse_bounded_json(std::string_view text, const std::string& source);

}  // namespace smart::serve
