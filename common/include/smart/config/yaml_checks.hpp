// Contract: strict YAML reading helpers shared by every config parser (QoS profiles, robot
// models). Each throws ConfigError whose message starts "source:line:column:" and says which key
// is wrong and what is accepted.
#pragma once

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace smart::config {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& source, const YAML::Node& node, const std::string& what);
std::string join(const std::vector<std::string>& words);

// Parses YAML text; a syntax error becomes ConfigError with line and column.
YAML::Node load(const std::string& text, const std::string& source);

void require_map(const std::string& source, const YAML::Node& node, const std::string& path);
void reject_unknown(const std::string& source, const YAML::Node& node, const std::string& path,
                    const std::vector<std::string>& known);

template <class T>
T scalar(const std::string& source, const YAML::Node& node, const std::string& key,
         const char* expected) {
  if (!node.IsScalar()) fail(source, node, "'" + key + "' must be " + expected);
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    fail(source, node, "'" + key + "' is '" + node.Scalar() + "' but must be " + expected);
  }
}

// A number >= min (and <= max).
double number(const std::string& source, const YAML::Node& node, const std::string& key, double min,
              double max);
std::chrono::milliseconds millis(const std::string& source, const YAML::Node& node,
                                 const std::string& key);

template <class E>
E choice(const std::string& source, const YAML::Node& node, const std::string& key,
         const std::map<std::string, E>& options) {
  const auto v = scalar<std::string>(source, node, key, "a word");
  const auto it = options.find(v);
  if (it == options.end()) {
    std::vector<std::string> names;
    names.reserve(options.size());
    for (const auto& [n, _] : options) names.push_back(n);
    fail(source, node, "'" + key + "' is '" + v + "'; use one of: " + join(names));
  }
  return it->second;
}

// Reads a whole file; throws ConfigError naming the path when it cannot be opened.
std::string read_file(const std::string& path, const char* what);

}  // namespace smart::config
