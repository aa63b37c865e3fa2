"""The drawing planner (-analysis plan) on DD1511 at the thesis density, on a short
history (40 increments) and a small budget of stretch runs:

* the search improves on the case's own schedule (Table 5.5): a lower objective;
* the written schedule is an options file that runs: run after the case it gives the film the
  planner reported (Mises extremes, wrinkled elements, equivalent plastic strain, read from the
  ordinary saddle report of an independent run), and every criterion the planner says is met holds;
* the schedule keeps the case's staging (each stage the same fraction of the final value as in
  Table 5.5), lies within the bounds and is rounded to the frame's 0.1 mm;
* bad input gets a message naming the option.
"""
import os
import re

from etfe_testlib import REPO, error_message, form_found_saddle, main, run, saddle_report, scene_values, scratch_dir

TARGET, BAND = 13.28, 0.10
TABLE_5_5 = {"saddle_draw_a": [10, 20, 30, 40], "saddle_draw_b": [10, 15, 20, 30],
             "saddle_draw_c": [10, 20, 30, 40], "saddle_draw_d": [10, 20, 30, 40]}
LINE = re.compile(r"plan: (case's own|planned) schedule, final ([^:]+): objective (\S+); Mises (\S+)\.\.(\S+) MPa "
                  r"\((\d+) below, (\d+) above the band\), [es]min (\S+) \((\d+) below \S+\), eq\. plastic strain (\S+) "
                  r"\((\d+) at or above \S+\); criteria (met|NOT met)")


def parse(out):
    res = {}
    for m in LINE.finditer(out):
        res[m.group(1)] = dict(x=[float(v) for v in m.group(2).split(",")], objective=float(m.group(3)),
                               mises_min=float(m.group(4)), mises_max=float(m.group(5)), below=int(m.group(6)),
                               above=int(m.group(7)), emin=float(m.group(8)), wrinkled=int(m.group(9)),
                               eq=float(m.group(10)), eq_over=int(m.group(11)), met=m.group(12) == "met")
    return res


def test(etfe, chk):
    with scratch_dir() as tmp:
        msh = form_found_saddle(etfe, tmp)
        case = ["-options_file", os.path.join(REPO, "options/saddle/dd1511.opts"), "-mesh_file", msh,
                "-load_increments", 40, "-load_monitor", 0]
        plan_file = os.path.join(tmp, "plan.opts")
        rc, out = run(etfe, case + ["-analysis", "plan", "-plan_max_runs", 8, "-plan_output", plan_file,
                                    "-output_file", os.path.join(tmp, "dd.h5")], timeout=600)
        p = parse(out)
        runs = re.search(r"plan: (\d+) stretch runs, (\S+) s", out)
        chk.check("case's own" in p and "planned" in p and runs, "the planner reports both schedules and its cost")
        if not ("case's own" in p and "planned" in p and runs):
            print(out[-3000:])
            return
        start, plan = p["case's own"], p["planned"]
        print("plan: %s stretch runs, %s s; start %s objective %.4e -> planned %s objective %.4e"
              % (runs.group(1), runs.group(2), start["x"], start["objective"], plan["x"], plan["objective"]))
        chk.check(start["x"] == [40, 30, 40, 40], "the search starts from the case's Table 5.5 values (%s)" % start["x"])
        chk.check(plan["objective"] < 0.5 * start["objective"],
                  "the planned schedule halves the objective at least (%.4e -> %.4e)"
                  % (start["objective"], plan["objective"]))

        # The written schedule: bounds, resolution, the case's staging.
        written = {}
        for line in open(plan_file):
            if line.startswith("-"):
                name, values = line.split()
                written[name[1:]] = [float(v) for v in values.split(",")]
        chk.check(sorted(written) == sorted(TABLE_5_5), "the file sets -saddle_draw_a..d (%s)" % sorted(written))
        for k, (name, stages) in enumerate(sorted(written.items())):
            final = stages[-1]
            chk.check(0 <= final <= 80 and abs(final * 10 - round(final * 10)) < 1e-9,
                      "%s final %.10g within [0, 80] mm and on the 0.1 mm grid" % (name, final))
            ref = TABLE_5_5.get(name, [1])
            chk.check(len(stages) == len(ref) and
                      all(abs(s - final * r / ref[-1]) <= 1e-9 * max(1, final) for s, r in zip(stages, ref)),
                      "%s keeps Table 5.5's staging: %s" % (name, stages))

        # Run it as a user would: after the case, an ordinary stretch run with its report.
        rc, out2 = run(etfe, case + ["-options_file", plan_file, "-output", 0])
        v = scene_values(out2, "saddle")
        mmin, mmax = v["mises_min"]["mises_min"], v["mises_min"]["mises_max"]
        rep = saddle_report(out2)
        wr, eq = int(rep["wrinkled_strain"]), rep["max_plastic_strain_eq"]
        chk.check(abs(mmin - plan["mises_min"]) <= 1e-4 and abs(mmax - plan["mises_max"]) <= 1e-4,
                  "the run of the file gives the Mises range the planner reported (%.4f..%.4f vs %.4f..%.4f)"
                  % (mmin, mmax, plan["mises_min"], plan["mises_max"]))
        chk.check(int(wr) == plan["wrinkled"] and abs(eq - plan["eq"]) <= 1e-4,
                  "... and its wrinkled elements (%d vs %d) and equivalent plastic strain (%.5f vs %.4f)"
                  % (wr, plan["wrinkled"], eq, plan["eq"]))
        lo, hi = TARGET * (1 - BAND), TARGET * (1 + BAND)
        if plan["below"] == 0:
            chk.check(mmin >= lo - 1e-4, "claimed: no element below the band; the run's minimum %.4f >= %.3f" % (mmin, lo))
        if plan["above"] == 0:
            chk.check(mmax <= hi + 1e-4, "claimed: no element above the band; the run's maximum %.4f <= %.3f" % (mmax, hi))
        if plan["wrinkled"] == 0:
            chk.check(wr == 0, "claimed: no wrinkled element; the run has %d" % wr)
        chk.check(plan["eq_over"] > 0 or eq < 0.10, "claimed eq. strain < 10 %%: the run's %.5f" % eq)

        # The tension-field wrinkle test: the minor principal stress; its count is the report's
        # stress-based one for the same schedule (the case's own).
        rc, out4 = run(etfe, case + ["-analysis", "plan", "-plan_max_runs", 1, "-plan_wrinkle_test", "stress",
                                     "-plan_output", os.path.join(tmp, "plan_s.opts"), "-output", 0])
        p4 = parse(out4).get("case's own")
        rc, out5 = run(etfe, case + ["-output", 0])
        rep = saddle_report(out5, printed=True)
        chk.check(p4 is not None and "smin" in out4 and rep and p4["wrinkled"] == int(rep["wrinkled_stress"]),
                  "-plan_wrinkle_test stress counts the report's stress-based wrinkles (%s vs %s; strain-based %s)"
                  % (p4 and p4["wrinkled"], rep.get("wrinkled_stress"), rep.get("wrinkled_strain")))

        # Bad input.
        for extra, words in ((["-plan_bounds", "5"], "-plan_bounds"),
                             (["-plan_variables", "saddle_draw_x"], "-saddle_draw_x"),
                             (["-plan_mises_band", "0"], "-plan_mises_band"),
                             (["-plan_wrinkle_test", "shape"], "-plan_wrinkle_test")):
            rc, out3 = run(etfe, case + ["-analysis", "plan", "-output", 0] + extra, expect_fail=True)
            msg = error_message(out3)
            chk.check(rc != 0 and words in msg, "%s: refused naming %s (%s)" % (" ".join(extra), words, msg[:160]))


if __name__ == "__main__":
    main(test)
