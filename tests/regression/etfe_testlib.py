"""Shared helpers of the scene tests (tests/regression/test_<label>_<name>.py).

A test is run by ctest as `/usr/bin/python3 tests/regression/test_x_y.py <path-to-etfe>` from the
repository root. It uses:
  etfe = etfe_path()                      the solver (argv[1], default build/etfe)
  rc, out = run(etfe, [...], np=2)        one run; raises TestFailure on an unexpected exit code
  scene_values(out, "patch")              {tag: {key: number}} from the scene's `key = value` lines
  summary(out), increments(out), ...      etfe's printed lines, parsed by scripts/etfepy/lines.py
  with scratch_dir() as tmp: ...          a temp dir outside the repo (kept if ETFE_KEEP_TMP=1)
  chk = Checker("name"); chk.check(cond, msg); ...; chk.finish()
"""
import contextlib
import csv
import math
import os
import re
import shutil
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "scripts"))

import h5compare  # noqa: E402,F401  (scripts/h5compare.py; tests use T.h5compare)
from etfepy import lines, runner  # noqa: E402  (scripts/etfepy)
from etfepy import options as optionsfile  # noqa: E402,F401
from etfepy.lines import (NUMBER, cutpattern_report, error_message, numbers, patch_ranges, saddle_report,  # noqa: E402,F401
                          scene_lines, scene_values, snes_histories, tail)
from etfepy.results import read_steps, status  # noqa: E402,F401

OPTIONS = os.path.join(REPO, "options")


class TestFailure(Exception):
    pass


def etfe_path():
    p = sys.argv[1] if len(sys.argv) > 1 else os.path.join(REPO, "build", "etfe")
    p = os.path.abspath(p)
    if not os.access(p, os.X_OK):
        sys.stderr.write("FAIL: solver %s not found or not executable (build it: cmake --build build)\n" % p)
        sys.exit(2)
    return p


def opts(scene):
    """Path of options/<scene>.opts."""
    return os.path.join(OPTIONS, scene + ".opts")


def run(etfe, args, np=1, expect_fail=False, timeout=300, oversubscribe=None, echo=False, cwd=None):
    """Run the solver (under mpirun when np > 1) from the repository root (or cwd).

    Returns (returncode, stdout + stderr). Raises TestFailure when the run succeeds although
    expect_fail is True, fails although expect_fail is False, or exceeds timeout seconds
    (expect_fail=None accepts any exit code).
    """
    res = runner.run(args, np=np, etfe=etfe, timeout=timeout, oversubscribe=oversubscribe, cwd=cwd)
    cmd, out = res.command, res.output
    run.last_wall = res.wall
    if res.timed_out:
        raise TestFailure("timed out after %g s: %s\n%s" % (timeout, " ".join(cmd), tail(out)))
    if res.returncode == 127 and out.startswith("cannot run"):
        raise TestFailure(out)
    if echo:
        print(out)
    if expect_fail is True and res.returncode == 0:
        raise TestFailure("expected a failure (non-zero exit) but the run succeeded: %s\n%s"
                          % (" ".join(cmd), tail(out)))
    if expect_fail is False and res.returncode != 0:
        raise TestFailure("run failed with exit code %d: %s\n%s" % (res.returncode, " ".join(cmd), tail(out)))
    return res.returncode, out


run.last_wall = 0.0


def scene_value(out, scene, tag, key=None):
    """One number of a scene line; raises TestFailure when it was not printed."""
    v = scene_values(out, scene)
    key = key or tag
    if tag not in v or key not in v[tag]:
        raise TestFailure("the run did not print `%s: %s ... %s = <number>`; scene lines:\n%s"
                          % (scene, tag, key, "\n".join(scene_lines(out, scene))))
    return v[tag][key]


def summary(out):
    """Numbers of the `etfe: completed after N increments (...), M Newton iterations, C cut-backs, W s` line."""
    s = lines.summary(out)
    if s is None:
        raise TestFailure("no `etfe: completed/STOPPED after ...` line in the output:\n" + tail(out))
    return s


def increments(out):
    """Per converged increment: dict(step, t, stage, newton, residual, ...) from the load monitor lines."""
    return lines.progress(out)


def printed_ulp(s):
    """One unit in the last printed digit of a number string such as 2.595566e+01."""
    m = re.match(r"[-+]?(\d*)\.?(\d*)(?:[eE]([-+]?\d+))?$", s.strip())
    if not m:
        return 0.0
    frac = len(m.group(2))
    exp = int(m.group(3) or 0)
    return 10.0 ** (exp - frac)


def printed_agree(a, b, slack=1.0):
    """Two printed numbers are equal up to `slack` units in their last printed digit."""
    return abs(float(a) - float(b)) <= slack * max(printed_ulp(a), printed_ulp(b)) * (1 + 1e-12)


@contextlib.contextmanager
def scratch_dir(name="etfe-test"):
    """A temporary directory (outside the repository); removed afterwards unless ETFE_KEEP_TMP=1."""
    d = tempfile.mkdtemp(prefix=name + "-")
    try:
        yield d
    finally:
        if os.environ.get("ETFE_KEEP_TMP"):
            print("(scratch files kept in %s)" % d)
        else:
            shutil.rmtree(d, ignore_errors=True)


def stop_and_restart(etfe, args, part, ck, stop_after, full):
    """Runs args (results into part) stopped after stop_after increments with a checkpoint ck, then
    restarted from ck, and compares part with the uninterrupted run's results full bit for bit:
    (the differences, as h5compare lists them, and the restarted run's printed output)."""
    run(etfe, args + ["-output_file", part, "-load_stop_after", stop_after, "-checkpoint_file", ck])
    _, out = run(etfe, args + ["-output_file", part, "-restart", ck])
    return h5compare.compare(full, part, step="all", default_rtol=0.0, default_atol=0.0), out


def read_history(path):
    """Rows of a `<case>_history.csv` (-saddle_history) as dicts of strings."""
    with open(path) as f:
        return list(csv.DictReader(f))


def largest_history_difference(h0, h, columns):
    """Largest |h - h0| over the rows and columns, relative to each column's largest |h0|,
    and where it is (step, column); columns that are zero throughout h0 are skipped."""
    worst, where = 0.0, None
    for c in columns:
        scale = max(abs(float(r[c])) for r in h0)
        if scale == 0:
            continue
        for r0, r in zip(h0, h):
            d = abs(float(r0[c]) - float(r[c])) / scale
            if d > worst:
                worst, where = d, (r0["step"], c)
    return worst, where


# History columns by the quantity they hold (the general scene's CSV): parallel runs are compared
# against the scale of the quantity, not of the column (a probe on a symmetry line has a near-zero
# component).
FAMILIES = {"u": ("_uX", "_uY", "_uZ"), "strain": ("_Exx", "_Eyy", "_Exy", "_emin"),
            "stress": ("_mises", "_mises_max", "_smin"), "ep": ("_ep_max",), "reaction": ("_RX", "_RY", "_RZ"),
            "chamber": ("_p_kPa",)}


def largest_family_difference(h0, h):
    """Largest |h - h0| over the rows and the columns of each family, relative to the family's
    largest |h0|, and where it is (step, column)."""
    return largest_group_difference(h0, h, [[c for c in h0[0] if c.endswith(ends)] for ends in FAMILIES.values()])


def largest_group_difference(h0, h, groups):
    """Largest |h - h0| over the rows and the columns of each group of columns, relative to the
    group's largest |h0| (1 where that is 0), and where it is (step, column)."""
    worst, where = 0.0, None
    for cols in groups:
        if not cols:
            continue
        scale = max(abs(float(r[c])) for r in h0 for c in cols) or 1.0
        for r0, r in zip(h0, h):
            for c in cols:
                d = abs(float(r0[c]) - float(r[c])) / scale
                if d > worst:
                    worst, where = d, (r0["step"], c)
    return worst, where


def dd1511_case(etfe, msh, tmp, name, args, np=1):
    """DD1511 (options/saddle/dd1511.opts) on the surface msh with args, results off, its files
    named tmp/<name>.*: returns (output, rows of its history CSV)."""
    _, out = run(etfe, ["-options_file", os.path.join(REPO, "options", "saddle", "dd1511.opts"), "-mesh_file", msh,
                        "-output", 0, "-output_file", os.path.join(tmp, name + ".h5"),
                        "-saddle_history", os.path.join(tmp, name + ".csv")] + list(args), np=np)
    return out, read_history(os.path.join(tmp, name + ".csv"))


def form_found_saddle(etfe, tmp, options="ff_r15_s11_n19.opts", extra=(), name="ff"):
    """Form-finds a saddle start (options/saddle/<options>) into tmp and returns its .msh: a clean
    checkout has no results/saddle/, and the stretch cases name that file."""
    msh = os.path.join(tmp, name + ".msh")
    run(etfe, ["-options_file", os.path.join(REPO, "options", "saddle", options), "-formfind_monitor", 0,
               "-formfind_mesh_out", msh, "-output", 0, "-output_file", os.path.join(tmp, name + ".h5")] + list(extra))
    return msh


class Checker:
    """Collects named checks, prints one line per check, exits non-zero at the end on failure."""

    def __init__(self, name):
        self.name = name
        self.failures = []
        self.t0 = time.time()

    def check(self, cond, msg):
        print(("  ok    " if cond else "  FAIL  ") + msg)
        if not cond:
            self.failures.append(msg)
        return bool(cond)

    def less(self, value, limit, what):
        ok = value < limit if not (isinstance(value, float) and math.isnan(value)) else False
        return self.check(ok, "%s = %.3e < %.1e" % (what, value, limit))

    def finish(self):
        wall = time.time() - self.t0
        if self.failures:
            print("\n%s: FAILED %d check(s) (%.1f s):" % (self.name, len(self.failures), wall))
            for f in self.failures:
                print("  - " + f)
            sys.exit(1)
        print("\n%s: passed (%.1f s)" % (self.name, wall))
        sys.exit(0)


def main(test):
    """Runs test(etfe, checker); a TestFailure or an unexpected exception fails the test."""
    name = os.path.splitext(os.path.basename(sys.argv[0]))[0]
    chk = Checker(name)
    try:
        test(etfe_path(), chk)
    except TestFailure as e:
        chk.check(False, str(e))
    chk.finish()
