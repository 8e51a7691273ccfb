#include "smart/dds/error.hpp"

namespace smart::dds {

Error::Error(dds_return_t code, const std::string& what_failed)
    : std::runtime_error(what_failed + ": " + dds_strretcode(code) + " (DDS return code " +
                         std::to_string(code) + ")"),
      code_(code) {}

dds_return_t check(dds_return_t ret, const char* what_failed) {
  if (ret < 0) throw Error(ret, what_failed);
  return ret;
}

}  // namespace smart::dds
