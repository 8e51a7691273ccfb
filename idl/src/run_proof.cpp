#include "smart/wire/run_proof.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>

#include <cctype>
#include <stdexcept>

namespace smart::wire {

namespace {
int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string hex(const uint8_t* data, std::size_t n) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    out += kDigits[data[i] >> 4];
    out += kDigits[data[i] & 0xf];
  }
  return out;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// HMAC-SHA256 over "tag|role|run|guid-hex", as hex.
std::string mac(const RunKey& key, std::string_view role, std::string_view run,
                const GuidPrefix& participant) {
  std::string message(kRunProofTag);
  message += '|';
  message += role;
  message += '|';
  message += run;
  message += '|';
  message += hex(participant.data(), participant.size());
  unsigned char out[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  HMAC(EVP_sha256(), key.bytes.data(), static_cast<int>(key.bytes.size()),
       reinterpret_cast<const unsigned char*>(message.data()), message.size(), out, &n);
  return hex(out, n);
}
}  // namespace

RunKey parse_run_key(std::string_view text, const std::string& source) {
  const auto digits = trimmed(text);
  const auto fail = [&](const std::string& why) {
    return std::invalid_argument(source + ": not a run key: " + why +
                                 "; make one with `openssl rand -hex 32 > FILE` (`smart run "
                                 "--run-key FILE` makes it when missing) and give every process "
                                 "of the run that file");
  };
  if (digits.size() % 2 != 0 || digits.size() < 2 * kRunKeyMinBytes ||
      digits.size() > 2 * kRunKeyMaxBytes) {
    throw fail(std::to_string(digits.size()) +
               " characters where 32 to 128 hex digits (an even "
               "number) are expected");
  }
  RunKey key;
  for (std::size_t i = 0; i < digits.size(); i += 2) {
    const int hi = hex_value(digits[i]), lo = hex_value(digits[i + 1]);
    if (hi < 0 || lo < 0) {
      throw fail("character " + std::to_string(i + (hi < 0 ? 1 : 2)) + " is not a hex digit");
    }
    key.bytes.push_back(static_cast<uint8_t>(hi * 16 + lo));
  }
  return key;
}

std::string format_run_key(const RunKey& key) {
  return hex(key.bytes.data(), key.bytes.size()) + "\n";
}

std::string run_proof(const RunKey& key, std::string_view role, std::string_view run,
                      const GuidPrefix& participant) {
  return std::string(kRunProofTag) + " " + std::string(role) + " " +
         mac(key, role, run, participant);
}

std::optional<std::string> proven_role(const RunKey& key, std::string_view user_data,
                                       std::string_view run, const GuidPrefix& participant) {
  if (user_data.substr(0, kRunProofTag.size()) != kRunProofTag) return std::nullopt;
  auto rest = user_data.substr(kRunProofTag.size());
  if (rest.empty() || rest.front() != ' ') return std::nullopt;
  rest.remove_prefix(1);
  const auto space = rest.find(' ');
  if (space == std::string_view::npos || space == 0 || space > 32) return std::nullopt;
  const auto role = rest.substr(0, space);
  const auto given = rest.substr(space + 1);
  const auto expected = mac(key, role, run, participant);
  if (given.size() != expected.size() ||
      CRYPTO_memcmp(given.data(), expected.data(), expected.size()) != 0) {
    return std::nullopt;
  }
  return std::string(role);
}

}  // namespace smart::wire
