// Contract: parses MovingAI .map text (header "type", "height H", "width W", "map", then H rows
// of W symbols). Free: '.', 'G', 'S'; blocked: '@', 'T', 'O', 'W'. Any other symbol, a bad
// header, or wrong row count/length is reported, all at once, as InputError with file and line.
// The LoRR dialect (League of Robot Runners Start-Kit, src/Grid.cpp) blocks '@' and 'T' and
// frees '.', 'E' (emitter) and 'S' (service cell); `marks` then collects the E and S cells, which
// a task generator alternates between (LSMART's 'w' workstations and 'e' endpoints likewise).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::grid {

enum class MapDialect { kMovingAi, kLorr };

// Cells a map marks for tasks, row-major order: LoRR 'E' / LSMART 'w', LoRR 'S' / LSMART 'e'.
struct MapMarks {
  std::vector<Cell> workstations;
  std::vector<Cell> endpoints;
};

Grid parse_map(std::string_view text, const std::string& source,
               MapDialect dialect = MapDialect::kMovingAi, MapMarks* marks = nullptr);

}  // namespace smart::grid
