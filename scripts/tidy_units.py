#!/usr/bin/env python3
"""What scripts/clang-tidy.sh hands to clang-tidy, from a build's compile_commands.json.

With unity builds (SMART_UNITY_BUILD, the default) CMake lists the batch files it generates
(<target>.dir/Unity/unity_N_cxx.cxx, each #including a batch of one target's sources), not the
sources. This writes OUT/compile_commands.json with one entry per source (a batch's command with
the source in place of the batch file) and prints one job a line, tab-separated:

    <.clang-tidy of the job> <file to lint> <1 if it is a batch file, else 0>

for the given sources. A batch is linted as a whole when every source it holds is one of them and
they share one .clang-tidy (clang-tidy reads the configuration beside the file it is given, and a
batch file sits in the build tree): the libraries' headers are then parsed and matched once a
batch instead of once a source, as when it is compiled (sources the build generates may come
along: the header filter shows nothing of them). The other sources are linted one by one
with the per-source database. Usage: tidy_units.py BUILD_DIR OUT_DIR SOURCE...
"""
import json
import os
import re
import sys

INCLUDE = re.compile(r'^#include "([^"]+)"\s*$')


def batch_sources(path):
    """The sources a CMake unity batch file includes, in order (absolute paths)."""
    with open(path, encoding="utf-8") as f:
        return [m.group(1) for m in map(INCLUDE.match, f) if m]


def config_of(source, root):
    """The .clang-tidy clang-tidy would read for source: the nearest one up to root."""
    d = os.path.dirname(source)
    while True:
        candidate = os.path.join(d, ".clang-tidy")
        if os.path.isfile(candidate):
            return candidate
        if d == root or d == os.path.dirname(d):
            return os.path.join(root, ".clang-tidy")
        d = os.path.dirname(d)


def per_source_entries(entries):
    """One entry per source; batches: {batch file: its sources}."""
    out, batches = [], {}
    for e in entries:
        f = os.path.join(e["directory"], e["file"])
        if "/Unity/unity_" not in f:
            out.append(e)
            continue
        batches[f] = batch_sources(f)
        for s in batches[f]:
            copy = dict(e, file=s)
            if "command" in copy:
                copy["command"] = copy["command"].replace(e["file"], s)
            else:
                copy["arguments"] = [s if a == e["file"] else a for a in copy["arguments"]]
            out.append(copy)
    return out, batches


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: tidy_units.py BUILD_DIR OUT_DIR SOURCE...")
    build, out_dir, sources = sys.argv[1], sys.argv[2], sys.argv[3:]
    root = os.getcwd()
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as f:
        entries, batches = per_source_entries(json.load(f))
    with open(os.path.join(out_dir, "compile_commands.json"), "w", encoding="utf-8") as f:
        json.dump(entries, f)
    wanted = {os.path.abspath(s) for s in sources}
    left = set(wanted)
    generated = os.path.abspath(build) + os.sep
    for batch, held in sorted(batches.items()):
        # Sources generated in the build tree (idlc's and the build's own) come along unlinted:
        # the header filter shows nothing of them.
        own = {s for s in held if not s.startswith(generated)}
        configs = {config_of(s, root) for s in own}
        if own and own <= wanted and len(configs) == 1:
            print(f"{configs.pop()}\t{batch}\t1")
            left -= own
    for s in sorted(left):
        print(f"{config_of(s, root)}\t{s}\t0")


if __name__ == "__main__":
    main()
