#!/usr/bin/python3
"""scripts/bench-scaling at the thesis density (1 444 triangles on 1 and 2 ranks, 2 916 on 2 for
the weak pair, 2 increments): the study runs end to end on the etfe under test and what it reads
from etfe's logs is there - Newton iterations per increment equal on 1 and 2 ranks, an efficiency,
MPI bytes per Newton iteration with one ghost exchange (2 messages) per residual, MUMPS's flop count,
peak memory per rank - the answer does not move between 1 and 2 ranks (part A/B Mises and slides
of the history CSV equal, displacements to 1e-9 relative), and the model prints its 64 and
1024-rank rows. Guards the script against changes of etfe's progress line, -log_view or -ksp_view."""
import csv
import math
import os
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main_test(etfe, chk):
    with T.scratch_dir("scaling") as tmp:
        cmd = ["/usr/bin/python3", os.path.join(ROOT, "scripts", "bench-scaling"), "--strong", "1444",
               "--weak", "1444", "--ranks", "1,2", "--increments", "2", "--exe", os.path.abspath(etfe),
               "--out", tmp, "--timeout", "300"]
        r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=600)
        print(r.stdout[-3000:], r.stderr[-2000:])
        chk.check(r.returncode == 0, "bench-scaling exits 0 (%d)" % r.returncode)
        path = os.path.join(tmp, "scaling.csv")
        if not chk.check(os.path.isfile(path), "scaling.csv written"):
            return
        rows = {(int(x["triangles"]), int(x["ranks"])): x for x in csv.DictReader(open(path))}
        chk.check(set(rows) == {(1444, 1), (1444, 2), (2916, 2)}, "the three cases: %s" % sorted(rows))
        for key, x in sorted(rows.items()):
            chk.check(x["ok"] == "True", "%s finished (%s)" % (key, x["error"]))
            chk.check(float(x["newton_per_inc"]) > 0 and float(x["s_per_inc"]) > 0,
                      "%s: Newton/inc %s, s/inc %s" % (key, x["newton_per_inc"], x["s_per_inc"]))
            chk.check(float(x["mem_max"]) > 10, "%s: peak memory per rank %s MB" % (key, x["mem_max"]))
            chk.check(float(x["flops"]) > 0, "%s: MUMPS flops %s (-ksp_view RINFOG(1))" % (key, x["flops"]))
        one, two, weak = rows.get((1444, 1)), rows.get((1444, 2)), rows.get((2916, 2))
        if not (one and two and weak):
            return
        chk.check(one["newton_by_inc"] == two["newton_by_inc"],
                  "same Newton iterations per increment on 1 and 2 ranks (%s / %s)" % (one["newton_by_inc"], two["newton_by_inc"]))
        e = float(two["E"])
        chk.check(0 < e < 2, "strong efficiency E = %.2f" % e)
        chk.check(0 < float(weak["E_weak"]) < 2, "weak efficiency %s" % weak["E_weak"])
        chk.check(float(one["bytes_per_newton"]) == 0 and float(two["bytes_per_newton"]) > 0,
                  "MPI bytes per Newton: 1 rank %s, 2 ranks %s" % (one["bytes_per_newton"], two["bytes_per_newton"]))
        # One ghost exchange per residual: a message each way between the 2 ranks (-log_view's Mess column).
        m = float(two["SNESFunctionEval_mess"]) / float(two["SNESFunctionEval_count"])
        chk.check(m == 2, "ghost exchange: %.2f messages per residual evaluation on 2 ranks" % m)
        g = float(two["ghost"])
        c = g / math.sqrt(1444)
        chk.check(1 < c < 10, "ghost nodes %d = %.2f sqrt(triangles)" % (g, c))
        chk.less(float(two["agree_mises"]), 1e-9, "part A/B Mises, 2 vs 1 rank")
        chk.less(float(two["agree_slide"]), 1e-9, "slides, 2 vs 1 rank")
        chk.less(float(two["agree_u_committed"]), 1e-9, "displacements, 2 vs 1 rank")
        md = open(os.path.join(tmp, "scaling.md")).read()
        for p in (64, 1024):
            chk.check(any(l.startswith("| strong | 1.44e+03 | %d |" % p) for l in md.splitlines()),
                      "model row: strong, %d ranks" % p)
        chk.check("A direct solver will not scale to 1024 ranks" in md, "the model's verdict is printed")


if __name__ == "__main__":
    T.main(main_test)
