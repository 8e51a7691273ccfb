// Contract: a run's own credential, with or without DDS Security (issue 25, "bind every stream
// to the participant the run admitted"). The processes of one run share a secret key (a file:
// `smart run` makes a private one for the processes it starts; `--run-key FILE` shares one with
// processes started by hand). Each process proves its membership and its role with an
// HMAC-SHA256 (RFC 2104) over the role, the run name and its own DDS participant's GUID prefix;
// the proof travels in its writers' USER_DATA QoS (DDS 1.4, 2.2.3.1), which discovery delivers
// with each writer before any of its samples. A reader admits a writer only when the proof
// verifies for the GUID of the participant that discovery says owns the writer: an intruder that
// copies a proof has another GUID, so the copy fails. Pure: no DDS, no files, no randomness.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace smart::wire {

struct RunKey {
  std::vector<uint8_t> bytes;
};

inline constexpr std::size_t kRunKeyMinBytes = 16;  // 128 bits
inline constexpr std::size_t kRunKeyMaxBytes = 64;  // HMAC-SHA256's block
inline constexpr std::string_view kRunProofTag = "smart-run-proof/1";

// The key file's text: 32 to 128 hex digits, surrounding whitespace allowed. Throws
// std::invalid_argument naming `source` and what to fix.
RunKey parse_run_key(std::string_view text, const std::string& source);
std::string format_run_key(const RunKey& key);  // lower-case hex and a newline

using GuidPrefix = std::array<uint8_t, 12>;

// "smart-run-proof/1 <role> <64 hex digits>"; role: one word (monitor, sim, agent).
std::string run_proof(const RunKey& key, std::string_view role, std::string_view run,
                      const GuidPrefix& participant);
// The role `user_data` proves for that participant in that run with this key, or nothing (no
// proof, another key, another participant, another run). Compares in constant time.
std::optional<std::string> proven_role(const RunKey& key, std::string_view user_data,
                                       std::string_view run, const GuidPrefix& participant);

}  // namespace smart::wire
