"""Shared helpers of the scene tests (tests/regression/test_<label>_<name>.py).

A test is run by ctest as `/usr/bin/python3 tests/regression/test_x_y.py <path-to-etfe>` from the
repository root. It uses:
  etfe = etfe_path()                      the solver (argv[1], default build/etfe)
  rc, out = run(etfe, [...], np=2)        one run; raises TestFailure on an unexpected exit code
  scene_values(out, "patch")              {tag: {key: number}} from the scene's `key = value` lines
  with scratch_dir() as tmp: ...          a temp dir outside the repo (kept if ETFE_KEEP_TMP=1)
  chk = Checker("name"); chk.check(cond, msg); ...; chk.finish()
"""
import contextlib
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "scripts"))

import h5compare  # noqa: E402  (scripts/h5compare.py)

OPTIONS = os.path.join(REPO, "options")
MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
}
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?(?:inf|nan)"


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


def run(etfe, args, np=1, expect_fail=False, timeout=300, oversubscribe=None, echo=False):
    """Run the solver (under mpirun when np > 1) from the repository root.

    Returns (returncode, stdout + stderr). Raises TestFailure when the run succeeds although
    expect_fail is True, fails although expect_fail is False, or exceeds timeout seconds
    (expect_fail=None accepts any exit code).
    """
    env = dict(os.environ)
    env.update(MPI_ENV)
    cmd = [etfe] + [str(a) for a in args]
    if np > 1:
        if oversubscribe is None:
            oversubscribe = np > (os.cpu_count() or 1)
        cmd = ["mpirun", "-n", str(np)] + (["--oversubscribe"] if oversubscribe else []) + cmd
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout)
    except subprocess.TimeoutExpired as e:
        raise TestFailure("timed out after %g s: %s\n%s" % (timeout, " ".join(cmd),
                                                          tail(_decode(e.stdout or b""))))
    except OSError as e:
        raise TestFailure("cannot run %s: %s" % (" ".join(cmd), e))
    out = _decode(p.stdout)
    run.last_wall = time.time() - t0
    if echo:
        print(out)
    if expect_fail is True and p.returncode == 0:
        raise TestFailure("expected a failure (non-zero exit) but the run succeeded: %s\n%s"
                          % (" ".join(cmd), tail(out)))
    if expect_fail is False and p.returncode != 0:
        raise TestFailure("run failed with exit code %d: %s\n%s" % (p.returncode, " ".join(cmd), tail(out)))
    return p.returncode, out


run.last_wall = 0.0


def _decode(b):
    return b.decode("utf-8", "replace") if isinstance(b, bytes) else b


def tail(out, n=40):
    """The last n lines of a run's output without PETSc's configure-options noise."""
    lines = [l for l in out.splitlines() if "Configure options" not in l]
    return "\n".join(lines[-n:])


def error_message(out):
    """The lines of a PETSc error message that say what went wrong: no trace (#n ... or the
    concise "(raised in f() at file:line ...)"), no "Option left" warnings, no option table, no
    version/configure banner."""
    keep, in_table = [], False
    for l in out.splitlines():
        m = re.match(r"\[\d+\]PETSC ERROR: (.*)", l)
        if not m:
            continue
        t = m.group(1)
        if t.startswith("PETSc Option Table entries"):
            in_table = True
            continue
        if "End of Error Message" in t or "Error Message" in t:
            in_table = False
            continue
        if in_table or t.startswith("#") or t.startswith("Option left") or \
                t.strip().startswith("(raised in ") or \
                "Configure options" in t or t.startswith("Petsc Release") or \
                t.startswith("See https") or (" on a " in t and " named " in t) or \
                t.startswith("WARNING! There are option"):
            continue
        keep.append(t)
    return "\n".join(keep)


def numbers(text):
    """Every `key = number` pair of a line, in order: [(key, value, printed)]."""
    pairs = []
    for m in re.finditer(r"([A-Za-z_][\w]*(?:\([^)]*\))?)\s*=\s*(%s)" % NUMBER, text):
        pairs.append((m.group(1), float(m.group(2)), m.group(2)))
    return pairs


def scene_lines(out, scene):
    """The lines a scene prints (`<scene>: ...`), without the prefix."""
    pre = scene + ":"
    return [l[len(pre):].strip() for l in out.splitlines() if l.startswith(pre)]


def scene_values(out, scene, printed=False):
    """{tag: {key: value}} from the scene's lines; tag is the line's first word.

    `hencky: centre_deflection = 2.6e+01 mm, closed_form = 2.59e+01 mm, relative_error = 9.2e-04`
    gives values["centre_deflection"] = {"centre_deflection": 26.0, "closed_form": 25.9,
    "relative_error": 9.2e-4}. With printed=True the values are the printed strings.
    """
    res = {}
    for line in scene_lines(out, scene):
        m = re.match(r"(\w+)", line)
        if not m:
            continue
        d = res.setdefault(m.group(1), {})
        for k, v, s in numbers(line):
            d[k] = s if printed else v
    return res


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
    m = re.search(r"etfe: (completed|STOPPED) after (\d+) increments \(load time (%s)\), (\d+) Newton "
                  r"iterations, (\d+) cut-backs, (%s) s" % (NUMBER, NUMBER), out)
    if not m:
        raise TestFailure("no `etfe: completed/STOPPED after ...` line in the output:\n" + tail(out))
    return dict(completed=m.group(1) == "completed", increments=int(m.group(2)),
                time=float(m.group(3)), newton=int(m.group(4)), cutbacks=int(m.group(5)),
                wall=float(m.group(6)))


def increments(out):
    """Per converged increment: dict(step, t, stage, newton, residual) from the load monitor lines."""
    res = []
    for m in re.finditer(r"^step +(\d+)/\d+ +[0-9.]+%% +t +(%s) +stage (\d+)/\d+ .*? newton +(\d+) +\|R\| (%s)"
                         % (NUMBER, NUMBER), out, re.M):
        res.append(dict(step=int(m.group(1)), t=float(m.group(2)), stage=int(m.group(3)),
                        newton=int(m.group(4)), residual=float(m.group(5))))
    return res


def snes_histories(out):
    """Residual norms of every SNES solve (from -snes_monitor), one list per solve, in order."""
    hist = []
    for l in out.splitlines():
        m = re.match(r"\s*(\d+) SNES Function norm (%s)" % NUMBER, l)
        if not m:
            continue
        if int(m.group(1)) == 0:
            hist.append([])
        hist[-1].append(float(m.group(2)))
    return hist


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


def read_steps(path):
    """[(step, attrs, {dataset: array})] of a results file, in step order."""
    import h5py
    res = []
    with h5py.File(path, "r") as f:
        for k in sorted(f["steps"].keys(), key=int):
            g = f["steps"][k]
            res.append((int(k), {a: g.attrs[a] for a in g.attrs},
                        {n: d[()] for n, d in h5compare.datasets(g).items()}))
    return res


def status(path):
    return h5compare.file_status(path)


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
