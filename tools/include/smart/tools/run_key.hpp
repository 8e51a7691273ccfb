// Contract: the run key on the command line (--run-key FILE, smart/wire/run_proof.hpp): read from
// its file (every process of the run gives the same file), made first where a command owns the
// run (`smart run`: a missing --run-key file is made; without --run-key, a private one for the
// processes it starts, removed when it ends). The file is made with mode 0600 and 32 random
// bytes from the kernel (getrandom(2)). Errors name the file and what to fix (kExitBadInput).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "smart/dds/participant.hpp"
#include "smart/wire/run_proof.hpp"

namespace smart::tools {

struct DdsOptions;

// The key in `file` (std::invalid_argument: unreadable, or not a key).
wire::RunKey read_run_key(const std::filesystem::path& file);
// Writes a fresh key to `file`, which must not exist (mode 0600).
void make_run_key(const std::filesystem::path& file);

// Proves `participant` a member of its run in `role` when --run-key was given; returns whether.
bool prove_member(dds::Participant& participant, const DdsOptions& options,
                  const std::string& role);

// A key file of this process's own, in the temporary folder; removed on destruction.
class PrivateRunKey {
 public:
  PrivateRunKey();
  PrivateRunKey(const PrivateRunKey&) = delete;
  PrivateRunKey& operator=(const PrivateRunKey&) = delete;
  ~PrivateRunKey();
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
};

}  // namespace smart::tools
