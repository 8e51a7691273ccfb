// Contract: a LoRR problem folder uploaded from the form (issue 28: "a LoRR problem folder"),
// decided before a byte of it is written. Each file comes with its path inside the folder, as the
// browser gives it (webkitRelativePath, e.g. "random.domain/maps/random-64-64-10.map"; the
// problem JSON names its map, agents and tasks files relative to itself). That path is untrusted:
// it is accepted only as a relative path of plain components, so that it can only name a file
// under the run's own folder. The problem is the JSON the form names, or else the only .json file
// at the folder's top (maps of LSMART's kind are .json files too, one level down). Pure.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace smart::serve {

// The most files and the deepest path a problem folder may have (LoRR's: 4 files, 2 levels).
inline constexpr std::size_t kMaxFolderFiles = 64;
inline constexpr std::size_t kMaxFolderDepth = 6;

// Empty when `path` is a relative path of 1 to kMaxFolderDepth components, each of letters,
// digits, '.', '_' and '-' and none of them "." or ".."; otherwise what is wrong with it.
std::string check_folder_path(const std::string& path);

// The problem JSON among the folder's `paths`: `named` when given (it must be one of them and
// end in ".json"), else the only .json file at the top (the fewest components of any path).
struct ProblemChoice {
  std::string problem;  // one of paths; empty on error
  std::string error;    // what to do instead
};
ProblemChoice choose_problem(const std::vector<std::string>& paths, const std::string& named);

}  // namespace smart::serve
