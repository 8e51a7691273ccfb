#!/usr/bin/env python3
"""Fails when two tests could meet on one DDS domain.

ctest runs every TEST in a process of its own, the TESTs of one file side by side too, so each
TEST needs a domain id of its own (tests/support/dds_test_support.hpp, `enum DomainId`): two
PlannerNode tests on one domain answered each other's requests under ASan (2026-12-01). This
reads that enum and every C++ test file under tests/ and refuses
- two names with one id, or a name's id that another name's comment reserves ("kExperiment =
  165,  // and 166 (--jobs 2)": a test that runs two things at once takes the next ids too);
- a name written in the bodies of more than one TEST (TEST, TEST_F, TEST_P). A helper outside
  any TEST that names an id is not counted: give such a helper the id as a parameter when
  several TESTs call it.
Usage: scripts/check-test-domains.py [REPO]; exit 0 clean, 1 with findings, 2 when the enum is
missing.
"""
import collections
import pathlib
import re
import sys

HEADER = "tests/support/dds_test_support.hpp"
TEST_START = re.compile(r"^TEST(?:_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\)", re.M)


def read_ids(header):
    text = header.read_text()
    m = re.search(r"enum DomainId\s*:\s*int\s*\{(.*?)\};", text, re.S)
    if not m:
        print(f"{header}: no `enum DomainId : int {{ ... }};`; restore it", file=sys.stderr)
        sys.exit(2)
    ids = []  # (name, id, the ids its comment reserves)
    for line in m.group(1).splitlines():
        code, _, comment = line.partition("//")
        named = re.search(r"\b(k\w+)\s*=\s*(\d+)", code)
        if not named:
            continue
        extra = re.search(r"\band (\d+(?:,\s*\d+)*)", comment)
        reserved = [int(v) for v in re.findall(r"\d+", extra.group(1))] if extra else []
        ids.append((named.group(1), int(named.group(2)), reserved))
    return ids


def test_bodies(text):
    """(Suite.Name, body) of each TEST: from its line to the next TEST or the file's end."""
    starts = list(TEST_START.finditer(text))
    for n, m in enumerate(starts):
        end = starts[n + 1].start() if n + 1 < len(starts) else len(text)
        yield f"{m.group(1)}.{m.group(2)}", text[m.start():end]


def findings(repo):
    header = repo / HEADER
    if not header.exists():
        print(f"{header}: missing", file=sys.stderr)
        sys.exit(2)
    ids = read_ids(header)
    out = []
    by_value = collections.defaultdict(list)
    for name, value, reserved in ids:
        by_value[value].append(name)
        for more in reserved:
            by_value[more].append(f"{name} (its comment's {more})")
    for value, names in sorted(by_value.items()):
        if len(names) > 1:
            out.append(f"{HEADER}: domain {value} is given to {', '.join(names)}; give each its "
                       "own (a free id: one no name has)")
    names = {name for name, _, _ in ids}
    used = collections.defaultdict(list)
    for path in sorted((repo / "tests").rglob("*.cpp")):
        rel = path.relative_to(repo)
        for test, body in test_bodies(path.read_text()):
            for name in sorted(names & set(re.findall(r"\bk\w+", body))):
                used[name].append(f"{test} ({rel})")
    for name, tests in sorted(used.items()):
        if len(tests) > 1:
            out.append(f"{name} is used by {len(tests)} TESTs: {'; '.join(tests)}; give each "
                       f"its own id in {HEADER}")
    return out


def main():
    repo = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    found = findings(repo)
    for line in found:
        print(line)
    if found:
        return 1
    print("every TEST has DDS domains of its own")
    return 0


if __name__ == "__main__":
    sys.exit(main())
