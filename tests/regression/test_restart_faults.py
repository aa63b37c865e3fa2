"""Fault campaign, fast subset: scripts/study-faults --fast kills runs (twice on purpose
while a checkpoint is being written) and resumes them to the uninterrupted answer bit for bit,
corrupts checkpoints (truncated, flipped bytes in the file and in a dataset, an edited attribute
and value), restarts with changed physics and into another run's results, feeds bad meshes
(tests/regression/badmesh_cases.py), fills a small disk (1 and 2 ranks, results and checkpoint),
makes MUMPS fail, and signals runs (SIGTERM at random, SIGUSR1 within Newton, SIGINT while a
checkpoint is written, SIGUSR1 to mpirun of 2 ranks, a second signal during the stop, SIGKILL of
one rank of two): each stops with status "interrupted ..." that etfe -results_status and
etfepy.status agree on, and resumes to the uninterrupted run.
Every row of its table must pass: refused runs leave every file byte-identical, failed runs
record `failed: ...` in their results status."""
import os
import re
import subprocess
import sys

from etfe_testlib import REPO, Checker, etfe_path, scratch_dir

etfe = etfe_path()
chk = Checker("restart_faults")
with scratch_dir() as tmp:
    table = os.path.join(tmp, "faults.md")
    p = subprocess.run(["/usr/bin/python3", os.path.join(REPO, "scripts", "study-faults"), "--fast", "--etfe", etfe,
                        "--out", table], cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=600)
    out = p.stdout.decode("utf-8", "replace")
    print(out)
    rows = []
    if os.path.exists(table):
        for line in open(table):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 5 and cells[4] in ("yes", "**NO**"):
                rows.append(cells)
    groups = {r[0] for r in rows}
    chk.check(p.returncode == 0, "study-faults --fast exits 0 (rc %d)" % p.returncode)
    for g in ("kill", "corrupt", "physics", "other run", "disk full", "error exit", "signal"):
        chk.check(g in groups, "the table has %s cases" % g)
    chk.check(rows and all(r[4] == "yes" for r in rows), "every one of the %d rows passes%s" % (
        len(rows), "" if all(r[4] == "yes" for r in rows) else ": " + "; ".join(r[1] for r in rows if r[4] != "yes")))
    m = re.search(r"lost or silently wrong: (\d+)", out)
    chk.check(m and m.group(1) == "0", "nothing lost or silently wrong")
    chk.check(any("during a checkpoint write" in r[1] for r in rows), "a run was killed during a checkpoint write")
    stops = [r for r in rows if r[0] == "signal" and "rc 75" in r[3]]
    chk.check(len(stops) >= 1, "at least one run stopped by a signal with exit status 75 (%d)" % len(stops))
chk.finish()
