#!/usr/bin/python3
"""Reactions per support group and chamber pressures in the design run are enveloped over every
increment of each combination (the history CSV's rows), not its last row (scripts/design-run,
scripts/etfepy/envelope.py; docs/design-run.md).

  * On a film strip with an edge cable under its weight (tests/regression/cable_meshes.py), a
    combination that lowers the weight the base holds (5 -> 2.5 N/m over 4 increments) has its
    largest reaction at its first increment: envelope_groups.csv, envelope.h5 and the report give
    that value with its combination and increment, not the last row's smaller one.
  * A history whose chamber pressure and reaction go up and then down within the combination (a
    history CSV written here, no run): the envelope takes the peak at the middle increment and the
    chamber-pressure check fails on it, though the last row is within the range.
"""
import csv
import json
import os
import subprocess
import sys

from etfe_testlib import REPO, main, scratch_dir

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cable_meshes  # noqa: E402

sys.path.insert(0, os.path.join(REPO, "scripts"))
import h5py  # noqa: E402
import numpy as np  # noqa: E402
from etfepy import design as designmod  # noqa: E402
from etfepy import envelope as envmod  # noqa: E402

DESIGN = {
    "title": "test: a combination lowering the weight",
    "base": {"stages": 1, "loads": {"cable_cable_weight": [5]}},
    "increments_per_stage": 4,
    "load_cases": {"G": {"kind": "permanent", "in_base": True, "loads": {"cable_cable_weight": 5}}},
    "combinations": [{"name": "UNLOAD", "situation": "SLS", "factors": {"G": 0.5}}],
    "checks": [{"name": "deflection", "kind": "deflection", "situations": ["SLS"], "limit": 1000}],
}


def rows_of(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run_case(etfe, chk, tmp):
    model = cable_meshes.strip_model(tmp, "model.opts")
    dfile = os.path.join(tmp, "design.json")
    with open(dfile, "w") as f:
        json.dump(dict(DESIGN, model=model), f)
    out = os.path.join(tmp, "run")
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "design-run"), dfile, "--out", out,
                        "--etfe", etfe], capture_output=True, text=True, timeout=300)
    print(p.stdout + p.stderr)
    chk.check(p.returncode == 0, "design-run completes (exit %d)" % p.returncode)
    hist = rows_of(os.path.join(out, "UNLOAD_history.csv"))
    end = [float(r["end_RX"]) for r in hist]
    steps = [int(r["step"]) for r in hist]
    k = int(np.argmax(end))
    chk.check(len(hist) == 4 and k != len(hist) - 1 and end[k] > end[-1],
              "UNLOAD's history: end_RX %s N over increments %s, largest at increment %d, not the last"
              % (["%.6g" % v for v in end], steps, steps[k]))
    env = {r["quantity"]: r for r in rows_of(os.path.join(out, "envelope_groups.csv"))}
    e = env.get("end_RX", {})
    chk.check(e and float(e["max"]) == float("%.8g" % end[k]) and e["max_combination"] == "UNLOAD" and
              int(e["max_increment"]) == steps[k] and float(e["min"]) == float("%.8g" % min(end)) and
              int(e["min_increment"]) == steps[int(np.argmin(end))],
              "envelope_groups.csv: end_RX largest %s N at UNLOAD increment %s (the last row: %.8g N), smallest %s N "
              "at increment %s" % (e.get("max"), e.get("max_increment"), end[-1], e.get("min"), e.get("min_increment")))
    with h5py.File(os.path.join(out, "envelope.h5"), "r") as f:
        d = f["groups/end_RX"]
        chk.check(float(d[0]) == end[k] and list(d.attrs["increment"]) == [steps[k], steps[int(np.argmin(end))]],
                  "envelope.h5 groups/end_RX: [max, min] %s with their increments %s" % (list(d[()]),
                                                                                       list(d.attrs["increment"])))
    report = open(os.path.join(out, "report.html")).read()
    chk.check("max_increment" in report and "every increment" in report,
              "report.html: the reactions' table names the governing increment")


def synthetic(chk, tmp):
    """A history going up then down within the combination: the middle increment governs."""
    stem = os.path.join(tmp, "UPDOWN")
    p = [0.4, 0.55, 0.7, 0.5, 0.35]
    r = [150.0, 180.0, 260.0, 170.0, 120.0]
    with open(stem + "_history.csv", "w") as f:
        f.write("step,time,air_p_kPa,air_V_m3,rim_RX,rim_RY,rim_RZ,work,shift_work\n")
        f.write("10,1,0.3,1,0,0,100,0,0\n")  # a base row (load time 1): not the combination's
        for k in range(5):
            f.write("%d,%.10g,%g,1,0,0,%g,0,0\n" % (11 + k, 1 + 0.2 * (k + 1), p[k], r[k]))
    rows = envmod.history_rows(stem, 1)
    ext = envmod.history_extremes(rows)
    chk.check(len(rows) == 5 and ext["air_p_kPa"] == (0.7, 13, 0.35, 15) and ext["rim_RZ"][:2] == (260.0, 13),
              "history_extremes: the combination's 5 rows; chamber pressure largest 0.7 kPa at increment 13 (the "
              "middle), reaction 260 N there: %s" % {k: ext[k] for k in ("air_p_kPa", "rim_RZ")})
    groups = envmod.group_envelopes(["UPDOWN"], [ext])
    g = {x["quantity"]: x for x in groups}
    chk.check(g["air_p_kPa"]["max"] == 0.7 and g["air_p_kPa"]["max_increment"] == 13 and
              g["rim_RZ"]["max"] == 260.0 and g["rim_RZ"]["min"] == 120.0,
              "group envelopes: the peak over the increments, not the last row (0.35 kPa, 120 N)")
    d = designmod.Design.__new__(designmod.Design)
    d.checks = [{"name": "cushion pressure", "kind": "chamber_pressure", "chamber": "air", "range": [0.1, 0.6]}]
    X = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    tri = np.array([[0, 1, 2]])
    q = {"wrinkled_area_steps": []}
    rows = envmod.run_checks(d, [{"name": "UPDOWN", "situation": "SLS"}], [q], [ext], X, tri)
    chk.check(len(rows) == 1 and rows[0]["verdict"] == "FAIL" and rows[0]["value"] == 0.7 and "increment 13" in
              rows[0]["place"], "the chamber-pressure check fails on the peak 0.7 kPa at increment 13 (range 0.1 to "
                                "0.6; the last row, 0.35, is within): %s" % rows)


def test(etfe, chk):
    with scratch_dir("etfe-design-increments") as tmp:
        run_case(etfe, chk, tmp)
        synthetic(chk, tmp)


if __name__ == "__main__":
    main(test)
