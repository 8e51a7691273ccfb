// The run key on the command line (smart/tools/run_key.hpp): files made private and fresh,
// read back, refused with the file named; a private key gone with its owner.
#include "smart/tools/run_key.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "smart/tools/cli_common.hpp"
#include "support/dds_test_support.hpp"

namespace smart::tools {
namespace {

using ::testing::HasSubstr;

TEST(RunKeyFile, MadeWithMode0600AndFreshEachTimeAndReadBack) {
  const auto a = test::temp_file("run_key_a"), b = test::temp_file("run_key_b");
  std::filesystem::remove(a);
  std::filesystem::remove(b);
  make_run_key(a);
  make_run_key(b);
  struct stat st {};
  ASSERT_EQ(::stat(a.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(read_run_key(a).bytes.size(), 32u);
  EXPECT_NE(read_run_key(a).bytes, read_run_key(b).bytes);
  EXPECT_THROW(make_run_key(a), std::invalid_argument);  // never overwrites a key
  std::filesystem::remove(a);
  std::filesystem::remove(b);
}

TEST(RunKeyFile, ABadFileIsRefusedNamingIt) {
  const auto f = test::temp_file("run_key_bad");
  std::ofstream(f) << "not a key\n";
  try {
    read_run_key(f);
    ADD_FAILURE() << "a bad key was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr(f.string() + ": not a run key"));
  }
  std::filesystem::remove(f);
  EXPECT_THROW(read_run_key(f), std::exception);  // missing
}

TEST(RunKeyFile, APrivateKeyIsGoneWithItsOwner) {
  std::filesystem::path file;
  {
    PrivateRunKey key;
    file = key.file();
    EXPECT_EQ(read_run_key(file).bytes.size(), 32u);
  }
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(RunKeyFile, OnlyAGivenKeyProvesAParticipant) {
  dds::Domain domain(test::kRunKeyProve, test::loopback());
  dds::Participant p(domain, "r");
  DdsOptions o;
  EXPECT_FALSE(prove_member(p, o, "sim"));
  EXPECT_TRUE(p.proof().empty());
  PrivateRunKey key;
  o.run_key = key.file().string();
  EXPECT_TRUE(prove_member(p, o, "sim"));
  EXPECT_EQ(wire::proven_role(read_run_key(key.file()), p.proof(), "r", p.guid_prefix()), "sim");
}

}  // namespace
}  // namespace smart::tools
