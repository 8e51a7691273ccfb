#include "smart/serve/problem_folder.hpp"

#include <algorithm>
#include <limits>

namespace smart::serve {

namespace {

std::vector<std::string> components(const std::string& path) {
  std::vector<std::string> out(1);
  for (const char c : path) {
    if (c == '/') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

bool ends_with_json(const std::string& s) {
  return s.size() > 5 && s.compare(s.size() - 5, 5, ".json") == 0;
}

}  // namespace

std::string check_folder_path(const std::string& path) {
  if (path.empty()) return "a file of the folder has no name";
  if (path.size() > 255) return "'" + path.substr(0, 64) + "...' is longer than 255 characters";
  const auto parts = components(path);
  if (parts.size() > kMaxFolderDepth) {
    return "'" + path + "' is more than " + std::to_string(kMaxFolderDepth) + " folders deep";
  }
  for (const auto& part : parts) {
    const bool plain = !part.empty() && part != "." && part != ".." &&
                       part.find_first_not_of(
                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") ==
                           std::string::npos;
    if (!plain) {
      return "'" + path +
             "' is not a plain relative path (letters, digits, '.', '_', '-' between '/'; no "
             "'..'): rename the file or folder";
    }
  }
  return {};
}

ProblemChoice choose_problem(const std::vector<std::string>& paths, const std::string& named) {
  if (!named.empty()) {
    if (std::find(paths.begin(), paths.end(), named) == paths.end() || !ends_with_json(named)) {
      return {{}, "problem_file '" + named + "' is not a .json file of the uploaded folder"};
    }
    return {named, {}};
  }
  std::size_t top = std::numeric_limits<std::size_t>::max();
  for (const auto& p : paths) top = std::min(top, components(p).size());
  std::vector<std::string> found;
  for (const auto& p : paths) {
    if (ends_with_json(p) && components(p).size() == top) found.push_back(p);
  }
  if (found.size() == 1) return {found.front(), {}};
  if (found.empty()) {
    return {{},
            "the folder has no problem JSON at its top: choose a LoRR problem folder (its "
            ".json names mapFile, agentFile and taskFile)"};
  }
  std::string list;
  for (const auto& f : found) list += (list.empty() ? "" : ", ") + f;
  return {{},
          "the folder has " + std::to_string(found.size()) + " problem JSON files (" + list +
              "): choose one as problem_file"};
}

}  // namespace smart::serve
