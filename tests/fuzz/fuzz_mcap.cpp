// Fuzz target: an MCAP file as `smart serve --open FILE.mcap` reads it (record/mcap_reader.hpp),
// each smart/state message decoded as a RobotState from the untrusted bytes (record/cdr.hpp
// read_cdr, Cyclone's normalizer first). Any input may be refused with std::invalid_argument
// (McapError included); anything else escaping, a crash or a sanitizer report is a bug. Limits
// are small so that a declared size is refused before memory is spent on it.
#include <string_view>

#include "fuzz_input.hpp"
#include "smart/dds/topics.hpp"
#include "smart/record/cdr.hpp"
#include "smart/record/mcap_reader.hpp"

namespace {

struct DecodeStates : smart::record::McapVisitor {
  void message(const smart::record::McapMessageView& m) override {
    if (m.channel.topic != smart_msg_TOPIC_STATE) return;
    smart_msg_RobotState s{};
    try {
      smart::record::read_cdr(m.data, s);
    } catch (const std::invalid_argument&) {
    }
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  smart::record::StringSource source(std::string_view(reinterpret_cast<const char*>(data), size));
  DecodeStates visitor;
  try {
    smart::record::read_mcap(source, visitor, "fuzz.mcap",
                             {.max_chunk_bytes = 1 << 20, .max_record_bytes = 1 << 20});
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
