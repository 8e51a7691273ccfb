"""scripts/check-layers.py on tiny repositories of its own: a clean tree passes, an include that
goes up a layer and a source file in no layer fail naming the file, a broken table exits 2."""
import pathlib
import subprocess
import sys
import tempfile
import unittest

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "check-layers.py"

TABLE = """# Architecture
<!-- layers:begin -->
| layer | files | library | pure? | may include |
|---|---|---|---|---|
| low | `low/*` | `low` | yes | — |
| high | `high/*` | `high` | no | low |
<!-- layers:end -->
"""


class CheckLayers(unittest.TestCase):
    def tree(self, files, table=TABLE):
        root = pathlib.Path(self.enterContext(tempfile.TemporaryDirectory()))
        subprocess.run(["git", "init", "-q", str(root)], check=True)
        (root / "docs").mkdir()
        (root / "docs/architecture.md").write_text(table)
        for name, text in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        return subprocess.run([sys.executable, str(SCRIPT), str(root)], capture_output=True,
                              text=True)

    def test_includes_down_the_layers_pass(self):
        r = self.tree({"low/include/smart/low/a.hpp": "#pragma once\n",
                       "high/src/b.cpp": '#include "smart/low/a.hpp"\n',
                       "tests/t.cpp": '#include "smart/high/c.hpp"\n'})
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("none goes up a layer", r.stdout)

    def test_an_include_up_a_layer_fails_naming_file_line_and_what_is_allowed(self):
        r = self.tree({"high/include/smart/high/c.hpp": "#pragma once\n",
                       "low/src/a.cpp": '#include <vector>\n#include "smart/high/c.hpp"\n'})
        self.assertEqual(r.returncode, 1)
        self.assertIn("low/src/a.cpp:2: layer 'low' includes \"smart/high/c.hpp\" of layer 'high'",
                      r.stdout)

    def test_a_source_file_in_no_layer_fails(self):
        r = self.tree({"stray/x.cpp": "int x;\n", "bench/b.cpp": "int b;\n"})
        self.assertEqual(r.returncode, 1)
        self.assertIn("stray/x.cpp: in no layer of the table", r.stdout)
        self.assertNotIn("bench/b.cpp", r.stdout)

    def test_a_table_naming_an_unknown_layer_exits_2(self):
        r = self.tree({}, TABLE.replace("| no | low |", "| no | lowest |"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("'lowest'", r.stdout + r.stderr)


if __name__ == "__main__":
    unittest.main()
