"""Figure 4.13's matrix, a fast subset through scripts/study-friction (thesis L1496-1500): PD10a at 40
increments fixed and under mu = 0, 0.3 and 1.0 (implicit law) and DD1511 at 40 increments fixed and
at mu = 0. Every run completes (PD10a fixed only through the stabilized increments, whose force
stays a small part of the work done on the film); part A von Mises falls as mu grows (PD10a:
mu 0 > 0.3 > 1.0) and is smallest with the film fixed to the arch (PD10a and DD1511: fixed below
every mu); part B stays within 5 % of its mean; the script's table has one row per case and says
the trend holds."""
import csv
import os
import subprocess
import sys

from etfe_testlib import REPO, TestFailure, main, scratch_dir, tail

SCRIPT = os.path.join(REPO, "scripts", "study-friction")


def study(etfe, tmp, name, args):
    """Runs the study into tmp/<name> and tmp/<name>.md: (runs.csv rows by condition, table text)."""
    out, table = os.path.join(tmp, name), os.path.join(tmp, name + ".md")
    cmd = [sys.executable, SCRIPT, "--etfe", etfe, "--jobs", "1", "--algorithms", "implicit",
           "--extra", "-load_increments 40", "--out", out, "--table", table, "--surface-dir", tmp] + args
    p = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    if p.returncode != 0 or not os.path.exists(table):
        raise TestFailure("%s exited %d without its table:\n%s" % (" ".join(cmd), p.returncode, tail(p.stdout)))
    with open(os.path.join(out, "runs.csv")) as f:
        rows = {r["condition"]: r for r in csv.DictReader(f)}
    with open(table) as f:
        return rows, f.read()


def table_rows(text, case):
    """The first table's rows of a case (`| case | algorithm | ...`)."""
    return [l for l in text.splitlines() if l.startswith("| %s | implicit |" % case)]


def test(etfe, chk):
    with scratch_dir("friction-matrix") as tmp:
        pd, pd_table = study(etfe, tmp, "pd10a", ["--cases", "pd10a", "--conditions", "fixed,none,0.3,1.0"])
        dd, dd_table = study(etfe, tmp, "dd1511", ["--cases", "dd1511", "--conditions", "fixed,none"])
    for case, rows, conds in (("pd10a", pd, ("fixed", "none", "0.3", "1.0")), ("dd1511", dd, ("fixed", "none"))):
        for c in conds:
            r = rows.get(c)
            chk.check(r is not None and r["status"] == "completed",
                      "%s %s completes (%s)" % (case, c, r and (r["reason"] or r["status"])))
    if not chk.failures:
        a = {c: float(pd[c]["part_a"]) for c in pd}
        print("pd10a part A: mu 0 %.4f, 0.3 %.4f, 1.0 %.4f MPa" % (a["none"], a["0.3"], a["1.0"]))
        chk.check(a["none"] > a["0.3"] > a["1.0"], "PD10a: part A Mises falls as mu grows (0 > 0.3 > 1.0)")
        chk.check(a["fixed"] < a["1.0"], "PD10a: part A fixed %.4f < mu 1.0 %.4f MPa" % (a["fixed"], a["1.0"]))
        work = pd["fixed"]["stabilized_work"]
        chk.check(int(pd["fixed"]["stabilized"]) > 0 and 0 < float(work) < 0.05,
                  "PD10a fixed: %s increments stabilized, their force's work %s of the film's"
                  % (pd["fixed"]["stabilized"], work))
        fixed, none = float(dd["fixed"]["part_a"]), float(dd["none"]["part_a"])
        chk.check(fixed < none, "DD1511: part A fixed %.4f < mu 0 %.4f MPa" % (fixed, none))
        for case, rows in (("pd10a", pd), ("dd1511", dd)):
            b = [float(r["part_b"]) for r in rows.values()]
            mean = sum(b) / len(b)
            chk.less(max(abs(x - mean) for x in b) / mean, 0.05, "%s: part B's largest deviation from its mean" % case)
    for case, text in (("pd10a", pd_table), ("dd1511", dd_table)):
        rows = table_rows(text, case)
        chk.check(len(rows) == 1, "%s: the table has one row for the case (%d)" % (case, len(rows)))
        chk.check(len(rows) == 1 and "| holds: " in rows[0] and "(holds) |" in rows[0],
                  "%s: the table's trend A and B spread say holds" % case)


main(test)
