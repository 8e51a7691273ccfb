// Contract: parses MovingAI .map text (header "type", "height H", "width W", "map", then H rows
// of W symbols). Free: '.', 'G', 'S'; blocked: '@', 'T', 'O', 'W'. Any other symbol, a bad
// header, or wrong row count/length is reported, all at once, as InputError with file and line.
#pragma once

#include <string>
#include <string_view>

#include "smart/grid/grid.hpp"

namespace smart::grid {

Grid parse_map(std::string_view text, const std::string& source);

}  // namespace smart::grid
