#include "smart/serve/bounded_json.hpp"

#include <stdexcept>

namespace smart::serve {

nlohmann::json parse_bounded_json(std::string_view text, const std::string& source) {
  if (text.size() > kMaxJsonBytes) {
    throw std::invalid_argument(source + " is " + std::to_string(text.size()) + " bytes; at most " +
                                std::to_string(kMaxJsonBytes) +
                                " are read: give the file `smart run --out` wrote");
  }
  // The parser reports each value with its depth before it builds the next level: stopping there
  // keeps the document (and the recursion that later writes it out) shallow.
  const nlohmann::json::parser_callback_t depth = [&](int d, nlohmann::json::parse_event_t,
                                                      nlohmann::json&) {
    if (d > kMaxJsonDepth) {
      throw std::invalid_argument(source + " nests deeper than " + std::to_string(kMaxJsonDepth) +
                                  " levels: give the file `smart run --out` wrote");
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, depth);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::invalid_argument(source + " is not JSON (" + e.what() + ")");
  } catch (const nlohmann::json::exception& e) {  // e.g. a number no JSON number type holds
    throw std::invalid_argument(source + " cannot be read as JSON (" + e.what() + ")");
  }
}

}  // namespace smart::serve
