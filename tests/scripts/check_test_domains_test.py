"""scripts/check-test-domains.py on tiny trees of its own: TESTs with ids of their own pass; a
name in two TESTs, two names with one id and an id a comment reserves for another fail naming
them; a missing enum exits 2."""
import pathlib
import subprocess
import sys
import tempfile
import unittest

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "check-test-domains.py"

HEADER = """#pragma once
enum DomainId : int {
  kOne = 10,
  kTwo = 11,  // and 12 (--jobs 2)
};
"""


class CheckTestDomains(unittest.TestCase):
    def tree(self, tests, header=HEADER):
        root = pathlib.Path(self.enterContext(tempfile.TemporaryDirectory()))
        (root / "tests/support").mkdir(parents=True)
        if header is not None:
            (root / "tests/support/dds_test_support.hpp").write_text(header)
        for name, text in tests.items():
            (root / "tests" / name).parent.mkdir(parents=True, exist_ok=True)
            (root / "tests" / name).write_text(text)
        return subprocess.run([sys.executable, str(SCRIPT), str(root)], capture_output=True,
                              text=True)

    def test_tests_with_ids_of_their_own_pass(self):
        r = self.tree({"a/a_test.cpp": "TEST(A, X) { run(kOne); }\nTEST_F(A, Y) { run(kTwo); }\n"})
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("of its own", r.stdout)

    def test_a_name_in_two_tests_fails_naming_both_and_their_files(self):
        r = self.tree({"a/a_test.cpp": "TEST(A, X) { run(kOne); }\n",
                       "b/b_test.cpp": "TEST_P(B, Y) {\n  run(kOne);\n}\n"})
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("kOne is used by 2 TESTs: A.X (tests/a/a_test.cpp); B.Y (tests/b/b_test.cpp)",
                      r.stdout)

    def test_a_name_twice_in_one_test_and_in_a_helper_is_not_a_finding(self):
        r = self.tree({"a/a_test.cpp": "int helper() { return kOne; }\n"
                                       "TEST(A, X) { run(kTwo); run(kTwo); }\n"})
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_two_names_with_one_id_fail(self):
        r = self.tree({}, HEADER.replace("kTwo = 11", "kTwo = 10"))
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("domain 10 is given to kOne, kTwo", r.stdout)

    def test_an_id_a_comment_reserves_for_another_name_fails(self):
        r = self.tree({}, HEADER.replace("kOne = 10", "kOne = 12"))
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("domain 12 is given to kOne, kTwo (its comment's 12)", r.stdout)

    def test_a_missing_enum_exits_2_naming_the_header(self):
        r = self.tree({}, "#pragma once\n")
        self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
        self.assertIn("no `enum DomainId : int", r.stderr)


if __name__ == "__main__":
    unittest.main()
