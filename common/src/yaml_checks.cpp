#include "smart/config/yaml_checks.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace smart::config {

void fail(const std::string& source, const YAML::Node& node, const std::string& what) {
  const auto m = node.Mark();
  std::ostringstream s;
  s << source;
  if (!m.is_null()) s << ":" << m.line + 1 << ":" << m.column + 1;
  s << ": " << what;
  throw ConfigError(s.str());
}

std::string join(const std::vector<std::string>& xs) {
  std::string out;
  for (const auto& x : xs) out += (out.empty() ? "" : ", ") + x;
  return out;
}

YAML::Node load(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) + ": YAML syntax error: " + e.msg);
  }
}

void require_map(const std::string& source, const YAML::Node& node, const std::string& path) {
  if (!node.IsMap()) fail(source, node, "'" + path + "' must be a mapping of keys to values");
}

void reject_unknown(const std::string& source, const YAML::Node& node, const std::string& path,
                    const std::vector<std::string>& known) {
  const std::set<std::string> k(known.begin(), known.end());
  for (const auto& kv : node) {
    // A key may be any YAML node ("[a, b]: 1"); only a plain word names a setting.
    if (!kv.first.IsScalar()) fail(source, kv.first, "a key in '" + path + "' is not a plain word");
    const auto key = kv.first.Scalar();
    if (!k.count(key)) {
      fail(source, kv.first,
           "unknown key '" + key + "' in '" + path + "'; known keys: " + join(known));
    }
  }
}

double number(const std::string& source, const YAML::Node& node, const std::string& key, double min,
              double max) {
  const auto v = scalar<double>(source, node, key, "a number");
  if (!std::isfinite(v) || v < min || v > max) {
    std::ostringstream range;
    range << "'" << key << "' is " << node.Scalar() << " but must be from " << min << " to " << max;
    fail(source, node, range.str());
  }
  return v;
}

std::chrono::milliseconds millis(const std::string& source, const YAML::Node& node,
                                 const std::string& key) {
  const auto v = scalar<long long>(source, node, key, "a whole number of milliseconds");
  if (v < 0) fail(source, node, "'" + key + "' is negative; give a duration >= 0 ms");
  // Longer than an hour is a typo, and DDS turns huge durations into slow, misleading failures.
  if (v > 3'600'000)
    fail(source, node, "'" + key + "' is more than an hour; give at most 3600000 ms");
  return std::chrono::milliseconds(v);
}

std::string read_file(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in) {
    throw ConfigError(path + ": cannot open the " + what + " file; check the path");
  }
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace smart::config
