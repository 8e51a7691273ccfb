// Contract: every failing Cyclone DDS call made through smart::dds throws smart::dds::Error,
// carrying the return code and dds_strretcode() text plus what was being attempted. Destructors
// never throw. ConfigError is thrown for bad configuration files and names file:line.
#pragma once

#include <dds/dds.h>

#include <stdexcept>
#include <string>

#include "smart/config/yaml_checks.hpp"

namespace smart::dds {

class Error : public std::runtime_error {
 public:
  Error(dds_return_t code, const std::string& what_failed);
  dds_return_t code() const { return code_; }

 private:
  dds_return_t code_;
};

// A configuration problem (QoS YAML, domain settings). The message says where and how to fix it.
using ConfigError = config::ConfigError;

// Throws Error when `ret` is negative (a Cyclone error code); returns it otherwise.
dds_return_t check(dds_return_t ret, const char* what_failed);
inline dds_return_t check(dds_return_t ret, const std::string& what_failed) {
  return check(ret, what_failed.c_str());
}

}  // namespace smart::dds
