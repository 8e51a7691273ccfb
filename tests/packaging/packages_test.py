"""The two Debian packages (packaging/CMakeLists.txt, docs/lab.md) made by CPack: `smart-dds`
from the full build under test, `smart-dds-agent` from an agent-only build of the same source
made here. Each is checked for what it holds and depends on, then extracted and run: the
installed executable finds its configuration beside it (a robot model only the extracted tree
has), and the systemd unit's command line starts an agent.

Usage: packages_test.py SOURCE_DIR BUILD_DIR DOMAIN"""
import os
import pathlib
import re
import secrets
import shutil
import subprocess
import sys
import tempfile
import unittest

SOURCE, BUILD, DOMAIN = (pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3])


def run(argv, **kw):
    return subprocess.run([str(a) for a in argv], capture_output=True, text=True, **kw)


def cpack(build_dir, out):
    done = run(["cpack", "-B", out], cwd=build_dir)
    assert done.returncode == 0, done.stdout + done.stderr
    debs = list(pathlib.Path(out).glob("*.deb"))
    assert len(debs) == 1, debs
    return debs[0]


def field(deb, name):
    return run(["dpkg-deb", "-f", deb, name]).stdout.strip()


def contents(deb):
    return {line.split()[-1].lstrip(".") for line in run(["dpkg-deb", "-c", deb]).stdout.splitlines()}


def extract(deb, root):
    done = run(["dpkg-deb", "-x", deb, root])
    assert done.returncode == 0, done.stderr
    # A robot model only the installed tree has: found there, not in the source tree.
    robots = pathlib.Path(root) / "usr/share/smart-dds/config/robots"
    shutil.copy(robots / "jetbot.yaml", robots / "installed-bot.yaml")
    return pathlib.Path(root) / "usr/bin/smart"


def clean_env():
    env = {k: v for k, v in os.environ.items() if not k.startswith("SMART_")}
    return env


class Packages(unittest.TestCase):
    def setUp(self):
        self.tmp = pathlib.Path(self.enterContext(tempfile.TemporaryDirectory()))

    def test_the_full_package_holds_everything_and_finds_its_configuration(self):
        deb = cpack(BUILD, self.tmp / "out")
        self.assertEqual(field(deb, "Package"), "smart-dds")
        depends = field(deb, "Depends")
        for dep in ("libsimbody", "libddsc0debian", "python3-matplotlib"):
            self.assertIn(dep, depends)
        files = contents(deb)
        for f in ("/usr/bin/smart", "/usr/share/smart-dds/web/index.html",
                  "/usr/share/smart-dds/experiment_plot.py",
                  "/usr/share/smart-dds/config/qos/sim-lossy-wifi.yaml",
                  "/usr/lib/systemd/system/smart-agent@.service",
                  "/usr/share/doc/smart-dds/lab.md"):
            self.assertIn(f, files)
        smart = extract(deb, self.tmp / "root")
        m = self.tmp / "m.map"
        m.write_text("type octile\nheight 1\nwidth 3\nmap\n...\n")
        s = self.tmp / "m.scen"
        s.write_text("version 1\n0\tm.map\t3\t1\t0\t0\t2\t0\t2\n")
        p = self.tmp / "m.plan"
        p.write_text("Agent 0:(0,0)->(1,0)->(2,0)->\n")
        done = run([smart, "check-plan", "--map", m, "--scen", s, "--plan", p, "--axis", "xy",
                    "--robot", "installed-bot"], env=clean_env())
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn('"valid": true', done.stdout)

    def test_the_agent_package_has_no_simbody_web_app_or_chromium_and_its_unit_starts_an_agent(self):
        build = self.tmp / "agent-build"
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        # Compiled without optimisation (build type None: no flags): this checks what the package
        # holds and that its agent runs, not its speed, and it saves much of the build's CPU,
        # which `make test` spends beside the suite on two cores (docs/performance.md, "CI time").
        done = run(["cmake", "-S", SOURCE, "-B", build, *generator, "-DCMAKE_BUILD_TYPE=None",
                    "-DSMART_AGENT_ONLY=ON"])
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        # At a lower priority than the tests beside it in `make test` (they wait for events).
        done = run(["nice", "-n", "10", "cmake", "--build", build, "-j", "2"])
        self.assertEqual(done.returncode, 0, done.stdout[-4000:] + done.stderr[-4000:])
        deb = cpack(build, self.tmp / "out")
        self.assertEqual(field(deb, "Package"), "smart-dds-agent")
        self.assertEqual(field(deb, "Conflicts"), "smart-dds")
        depends = field(deb, "Depends")
        self.assertIn("libddsc0debian", depends)
        for absent in ("simbody", "chromium", "matplotlib", "httplib", "node"):
            self.assertNotIn(absent, depends)
        files = contents(deb)
        self.assertIn("/usr/lib/systemd/system/smart-agent@.service", files)
        self.assertFalse(any("/web/" in f or f.endswith(".py") for f in files), files)
        smart = extract(deb, self.tmp / "root")
        commands = run([smart, "--help"]).stdout
        self.assertRegex(commands, r"\n  agent ")
        self.assertNotRegex(commands, r"\n  (run|sim|serve) ")
        # The unit's command line, as systemd would run it for robot 3: its run key a
        # credential, its settings the unit's defaults plus an env file's (docs/lab.md).
        unit = (self.tmp / "root/usr/lib/systemd/system/smart-agent@.service").read_text()
        exec_start = re.search(r"^ExecStart=(.*)$", unit, re.M).group(1)
        defaults = re.search(r'^Environment=SMART_AGENT_ARGS="(.*)"$', unit, re.M).group(1)
        self.assertEqual(defaults, "--backend jetbot --config jetbot")
        # /etc/smart-dds/agent-3.env's SMART_AGENT_ARGS: a model only the installed tree has.
        args = "--backend jetbot --config installed-bot --i2c /nonexistent/i2c-9 --vicon-port 0"
        creds = self.tmp / "credentials"
        creds.mkdir()
        (creds / "run.key").write_text(secrets.token_hex(32) + "\n")
        line = (exec_start.replace("%i", "3").replace("${CREDENTIALS_DIRECTORY}", str(creds))
                .replace("$SMART_AGENT_ARGS", args).replace("/usr/bin/smart", str(smart)))
        argv = line.split()
        env = dict(clean_env(), SMART_INTERFACE="lo", SMART_DOMAIN=DOMAIN)
        done = run(argv, env=env, timeout=60)
        # Everything parsed and the robot model found in the installed tree: the agent gets as
        # far as the missing motor board (exit 3, README exit codes).
        self.assertEqual(done.returncode, 3, done.stdout + done.stderr)
        self.assertIn("I2C error: cannot open I2C bus /nonexistent/i2c-9", done.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
