"""Fault campaign, fast subset (issue 14): scripts/study-faults --fast kills runs (also during a
checkpoint write) and resumes them (bit-identical results and probe CSVs), corrupts checkpoints
(refused, results untouched), restarts with each physics option changed (refused, naming it),
feeds the bad meshes of badmesh_cases.py and fills a small tmpfs (status "failed: ..."). Every
row of its table must pass."""
import os
import subprocess
import sys

from etfe_testlib import REPO, Checker, etfe_path, scratch_dir

etfe = etfe_path()
chk = Checker("restart_faults")
with scratch_dir() as tmp:
    p = subprocess.run(["/usr/bin/python3", os.path.join(REPO, "scripts", "study-faults"), "--fast", "--etfe", etfe,
                        "--out", tmp], cwd=REPO, capture_output=True, text=True, timeout=900)
    out = p.stdout + p.stderr
    sys.stdout.write(out)
    rows = [l for l in out.splitlines() if l.startswith(("ok ", "FAIL"))]
    chk.check(len(rows) >= 20, "the campaign ran its cases (%d rows)" % len(rows))
    chk.check(p.returncode == 0 and not any(l.startswith("FAIL") for l in rows),
              "every fault case behaves as expected (see the table above)")
    chk.check(os.path.exists(os.path.join(tmp, "faults.md")), "the table faults.md is written")
chk.finish()
