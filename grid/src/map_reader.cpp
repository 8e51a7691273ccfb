#include "smart/grid/map_reader.hpp"

#include "smart/grid/problem.hpp"
#include "smart/grid/text.hpp"

namespace smart::grid {

namespace {

// Returns -1 for a symbol that is neither free nor blocked.
int classify(char c, MapDialect dialect) {
  if (dialect == MapDialect::kLorr) {
    if (c == '@' || c == 'T') return 1;
    return c == '.' || c == 'E' || c == 'S' ? 0 : -1;
  }
  switch (c) {
    case '.':
    case 'G':
    case 'S':
      return 0;
    case '@':
    case 'T':
    case 'O':
    case 'W':
      return 1;
    default:
      return -1;
  }
}

// Before the grid is allocated: a size no map has, or a header promising more rows than the
// text holds (a 100000x100000 header used to allocate 10 GB first).
void check_size(long long width, long long height, std::size_t rows_left, int last_line,
                const std::string& source, std::vector<Problem>& problems) {
  if (width * height > kMaxGridCells) {
    problems.push_back({source, 0, -1,
                        "a " + std::to_string(width) + "x" + std::to_string(height) +
                            " map has more than " + std::to_string(kMaxGridCells) +
                            " cells, more than this reader accepts"});
  } else if (static_cast<long long>(rows_left) < height) {
    problems.push_back({source, last_line, -1,
                        "the map has " + std::to_string(rows_left) + " rows but 'height' is " +
                            std::to_string(height) + "; the file may be truncated"});
  }
}

struct Header {
  long long height = -1, width = -1;
  std::size_t first_row_line = 0;  // index of the line after 'map'
};

// Reads 'type', 'height', 'width' up to and including 'map'; problems go to `problems`.
Header parse_header(const std::vector<std::string_view>& lines, const std::string& source,
                    std::vector<Problem>& problems) {
  auto problem = [&](int line, std::string msg) {
    problems.push_back({source, line, -1, std::move(msg)});
  };
  Header header;
  std::size_t i = 0;
  bool saw_type = false, saw_map = false;
  for (; i < lines.size() && !saw_map; ++i) {
    const auto words = split_whitespace(lines[i]);
    const int ln = static_cast<int>(i) + 1;
    if (words.empty()) continue;
    if (words[0] == "type") {
      saw_type = true;
    } else if (words[0] == "height" || words[0] == "width") {
      const auto v = words.size() == 2 ? parse_int(words[1]) : std::nullopt;
      if (!v || *v <= 0 || *v > kMaxGridSide) {
        problem(ln, "'" + excerpt(lines[i]) + "': " + std::string(words[0]) +
                        " must be a positive whole number up to " + std::to_string(kMaxGridSide) +
                        ", e.g. '" + std::string(words[0]) + " 32'");
      } else {
        (words[0] == "height" ? header.height : header.width) = *v;
      }
    } else if (words[0] == "map") {
      saw_map = true;
    } else {
      problem(ln, "unexpected header line '" + excerpt(lines[i]) +
                      "'; a MovingAI map starts with 'type octile', 'height H', 'width W', "
                      "'map'");
      break;
    }
  }
  if (!saw_type && problems.empty()) {
    problem(1, "missing 'type octile' header line; is this a MovingAI .map file?");
  }
  if (header.height < 0 && problems.empty()) problem(0, "missing 'height H' header line");
  if (header.width < 0 && problems.empty()) problem(0, "missing 'width W' header line");
  if (!saw_map && problems.empty()) problem(0, "missing 'map' line before the grid rows");
  header.first_row_line = i;
  return header;
}

}  // namespace

Grid parse_map(std::string_view text, const std::string& source, MapDialect dialect,
               MapMarks* marks) {
  const auto lines = split_lines(text);
  std::vector<Problem> problems;
  auto problem = [&](int line, std::string msg) {
    problems.push_back({source, line, -1, std::move(msg)});
  };
  const Header header = parse_header(lines, source, problems);
  std::size_t i = header.first_row_line;
  if (problems.empty()) {
    check_size(header.width, header.height, lines.size() - i, static_cast<int>(lines.size()),
               source, problems);
  }
  throw_if_any(problems);

  const auto w = static_cast<int32_t>(header.width), h = static_cast<int32_t>(header.height);
  std::vector<uint8_t> blocked(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 1);
  int32_t row = 0;
  for (; i < lines.size(); ++i) {
    const auto line = lines[i];
    const int ln = static_cast<int>(i) + 1;
    if (row >= h) {
      if (!trim(line).empty()) {
        problem(ln, "more rows than 'height " + std::to_string(h) +
                        "'; fix the height or remove the extra rows");
      }
      continue;
    }
    if (static_cast<long long>(line.size()) != w) {
      problem(ln, "row " + std::to_string(row) + " has " + std::to_string(line.size()) +
                      " symbols but 'width' is " + std::to_string(w));
    }
    for (int32_t x = 0; x < w && x < static_cast<int32_t>(line.size()); ++x) {
      const char symbol = line[static_cast<std::size_t>(x)];
      const int c = classify(symbol, dialect);
      if (c < 0) {
        problem(ln, "unknown map symbol '" + std::string(1, symbol) + "' at column " +
                        std::to_string(x) +
                        (dialect == MapDialect::kLorr
                             ? "; a LoRR map uses '.', 'E', 'S' (free) or '@', 'T' (blocked)"
                             : "; use '.', 'G', 'S' (free) or '@', 'T', 'O', 'W' (blocked)"));
        continue;
      }
      if (marks && dialect == MapDialect::kLorr && (symbol == 'E' || symbol == 'S')) {
        (symbol == 'E' ? marks->workstations : marks->endpoints).push_back({x, row});
      }
      blocked[static_cast<std::size_t>(row) * static_cast<std::size_t>(w) +
              static_cast<std::size_t>(x)] = static_cast<uint8_t>(c);
    }
    ++row;
  }
  if (row < h) {
    problem(static_cast<int>(lines.size()), "the map has " + std::to_string(row) +
                                                " rows but 'height' is " + std::to_string(h) +
                                                "; the file may be truncated");
  }
  throw_if_any(problems);
  return Grid(w, h, std::move(blocked), source);
}

}  // namespace smart::grid
