// The run proof (smart/wire/run_proof.hpp): a member's proof verifies for its own participant,
// role and run only; the key file's text is checked with the file named.
#include "smart/wire/run_proof.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

namespace smart::wire {
namespace {

using ::testing::HasSubstr;

const RunKey kKey = parse_run_key(" 00112233445566778899aabbccddeeff\n", "key");
const GuidPrefix kMember{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};

TEST(RunProof, VerifiesForItsParticipantRoleAndRunOnly) {
  const auto proof = run_proof(kKey, "monitor", "run-1", kMember);
  EXPECT_THAT(proof, HasSubstr("smart-run-proof/1 monitor "));
  EXPECT_EQ(proven_role(kKey, proof, "run-1", kMember), "monitor");
  GuidPrefix other = kMember;
  other[11] ^= 1;
  EXPECT_FALSE(proven_role(kKey, proof, "run-1", other));  // a copy in another participant
  EXPECT_FALSE(proven_role(kKey, proof, "run-2", kMember));
  const auto other_key = parse_run_key("ffeeddccbbaa99887766554433221100", "key");
  EXPECT_FALSE(proven_role(other_key, proof, "run-1", kMember));
  auto forged = proof;
  forged.replace(forged.find("monitor"), 7, "sim    ");  // the role is under the MAC too
  EXPECT_FALSE(proven_role(kKey, forged, "run-1", kMember));
}

TEST(RunProof, AnythingButAProofProvesNothing) {
  const auto proof = run_proof(kKey, "sim", "r", kMember);
  for (const std::string& bad :
       {std::string(), std::string("smart-run-proof/1"), std::string("smart-run-proof/1 sim"),
        proof.substr(0, 40), proof + "0", std::string("smart-run-proof/1  ") + proof.substr(22),
        std::string(5000, 'x')}) {
    EXPECT_FALSE(proven_role(kKey, bad, "r", kMember)) << bad;
  }
  EXPECT_EQ(proven_role(kKey, proof, "r", kMember), "sim");
}

TEST(RunKey, TextIsHexOfSixteenToSixtyFourBytesAndErrorsNameTheFile) {
  EXPECT_EQ(format_run_key(kKey), "00112233445566778899aabbccddeeff\n");
  EXPECT_EQ(parse_run_key(format_run_key(kKey), "k").bytes, kKey.bytes);
  const auto error = [](const std::string& text) {
    try {
      parse_run_key(text, "/etc/run.key");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(error("0011"), HasSubstr("/etc/run.key: not a run key: 4 characters"));
  EXPECT_THAT(error(std::string(130, 'a')), HasSubstr("130 characters"));
  EXPECT_THAT(error(std::string(31, 'a') + "g"), HasSubstr("character 32 is not a hex digit"));
  EXPECT_THAT(error(""), HasSubstr("openssl rand -hex 32"));
  EXPECT_EQ(error(std::string(128, 'A')), "accepted");
}

}  // namespace
}  // namespace smart::wire
