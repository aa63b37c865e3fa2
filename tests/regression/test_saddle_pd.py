"""Plane-strip (PD) stretch cases (thesis ch. 3-4): the film starts stress free on the
cylinder (the arch extruded) and must sag into a saddle in its first increment, a slack start.
PD10a, PD15a and PD15b complete; the middle part stays free of wrinkles at elements I and II for the
10 % rise and wrinkles (minimum principal strain < 0) for 15 % at both final d/c = 2.0 (PD15a) and
1.5 (PD15b), as the thesis's experiments and its own prediction found (L1753, L888)."""
import os

from etfe_testlib import Checker, etfe_path, run, saddle_report, summary, REPO

etfe = etfe_path()
chk = Checker("saddle_pd")
emin = {}
for case in ("pd10a", "pd15a", "pd15b"):
    rc, out = run(etfe, ["-options_file", os.path.join(REPO, "options/saddle/%s.opts" % case), "-load_increments", 60,
                         "-load_monitor", 0, "-output", 0], expect_fail=None)
    chk.check(rc == 0, "%s completes (60 increments)" % case)
    if rc != 0:
        continue
    rep = saddle_report(out)
    emin[case] = (rep["I_emin"], rep["II_emin"])
    s = summary(out)
    print("%s: emin I %.3e, II %.3e; %d Newton iterations, %.2f s" % (case, emin[case][0], emin[case][1], s["newton"],
                                                                       s["wall"]))
if len(emin) == 3:
    chk.check(min(emin["pd10a"]) > 0, "PD10a: no wrinkle at elements I and II")
    chk.check(min(emin["pd15a"]) < 0, "PD15a (d/c = 2.0): wrinkles at element I or II")
    chk.check(min(emin["pd15b"]) < 0, "PD15b (d/c = 1.5): wrinkles at element I or II")
chk.finish()
