#!/usr/bin/python3
"""The design run's resistance per surface group and per load duration and temperature
(scripts/design-run, scripts/etfepy/resistance.py; docs/design-run.md).

On the shipped hypar canopy mesh (meshes/hypar_canopy.msh, surface groups strip_1 and strip_2; not
form-found, which does not matter here) under snow, the two strips are two foils with their own
resistance (A and B, B weaker), and the same loads run as two combinations: short at 23 C and long
at 40 C (between the tabulated 23 and 50 C):
  * each element's utilisation is its design stress over its own group's f_d = f_k(duration, T) /
    gamma_M (element-wise, from the combination's results and the mesh's groups), so where the
    stresses of the two strips are alike the weaker strip's utilisation is the higher;
  * the long, warm combination has the lower f_d (f_k interpolated linearly at 40 C) and its
    utilisation is the short, cool one's times their ratio, per strip;
  * a duration or temperature stated by the load cases is taken when the combination states none
    (the shortest duration, the highest temperature);
  * refusals name what is wrong: a surface group not in the mesh (before any run), a material not
    defined, a duration class a material has no strength for, a combination checked for utilisation
    with no duration class, a non-positive strength or material factor, a temperature above a
    material's table.
"""
import csv
import json
import os
import subprocess
import sys

import numpy as np

from etfe_testlib import REPO, main, scratch_dir

sys.path.insert(0, os.path.join(REPO, "scripts"))
import h5py  # noqa: E402
from etfepy import design as designmod  # noqa: E402
from etfepy import mesh_groups  # noqa: E402

A = {"gamma_M": 1.2, "f_k": {"short": {"23": 21.0, "50": 15.0}, "long": {"23": 16.0, "50": 11.0}}}
B = {"gamma_M": 1.25, "f_k": {"short": {"23": 14.0, "50": 10.0}, "long": {"23": 11.0, "50": 8.0}}}
DESIGN = {
    "title": "test: two foils, two durations and temperatures",
    "model": "options/design/hypar_model.opts",
    "options": {"mesh_file": "meshes/hypar_canopy.msh"},
    "base": {"stages": 2, "loads": {"structure_self_weight": [1, 1]}},
    "increments_per_stage": 5,
    "load_cases": {"S": {"kind": "snow", "loads": {"film_all_snow": 0.75}}},
    "resistance": {"materials": {"A": A, "B": B}, "groups": {"strip_1": "A", "strip_2": "B"},
                   "source": "test values"},
    "combinations": [
        {"name": "COOL-SHORT", "situation": "ULS", "duration": "short", "factors": {"S": 1.5}},
        {"name": "WARM-LONG", "situation": "ULS", "duration": "long", "temperature": 40, "factors": {"S": 1.5}}],
    "checks": [{"name": "utilisation", "kind": "utilisation", "situations": ["ULS"], "limit": 10.0}],
}


def fd(mat, duration, t):
    tab = sorted((float(k), v) for k, v in mat["f_k"][duration].items())
    return float(np.interp(t, [k for k, _ in tab], [v for _, v in tab])) / mat["gamma_M"]


def refused(chk, data, words, what):
    try:
        designmod.Design(data, "test")
        chk.check(False, "refused: %s (it was accepted)" % what)
    except designmod.DesignError as e:
        chk.check(all(w in str(e) for w in words), "refused: %s: %s" % (what, e))


def with_resistance(**changes):
    r = json.loads(json.dumps(DESIGN["resistance"]))
    r.update(changes)
    return dict(DESIGN, resistance=r)


def refusals(etfe, chk, tmp):
    refused(chk, with_resistance(groups={"strip_1": "A", "strip_2": "C"}), ["strip_2", "'C'", "materials"],
            "a group given a material not defined")
    bad = json.loads(json.dumps(DESIGN["resistance"]))
    del bad["materials"]["B"]["f_k"]["long"]
    refused(chk, dict(DESIGN, resistance=bad), ["WARM-LONG", "material B", "'long'"],
            "a duration class a material has no strength for")
    refused(chk, dict(DESIGN, combinations=[dict(DESIGN["combinations"][0], duration=None)]),
            ["COOL-SHORT", "no duration class"], "a combination checked for utilisation with no duration class")
    for value, where in ((0, "f_k"), (-3.0, "f_k"), ("x", "f_k")):
        bad = json.loads(json.dumps(DESIGN["resistance"]))
        bad["materials"]["A"]["f_k"]["short"]["23"] = value
        refused(chk, dict(DESIGN, resistance=bad), ["material A", "f_k short at 23"],
                "a strength of %r" % (value,))
    for value in (0, -1.2):
        bad = json.loads(json.dumps(DESIGN["resistance"]))
        bad["materials"]["B"]["gamma_M"] = value
        refused(chk, dict(DESIGN, resistance=bad), ["material B", "gamma_M", "positive"],
                "a material factor of %r" % value)
    refused(chk, dict(DESIGN, combinations=[dict(DESIGN["combinations"][1], temperature=60)]),
            ["WARM-LONG", "60 C", "above"], "a temperature above a material's table")
    # An unknown surface group: refused by name before anything runs.
    dfile = os.path.join(tmp, "unknown_group.json")
    with open(dfile, "w") as f:
        json.dump(with_resistance(groups={"strip_1": "A", "strip_9": "B"}), f)
    out = os.path.join(tmp, "unknown_group")
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "design-run"), dfile, "--out", out,
                        "--etfe", etfe], capture_output=True, text=True, timeout=120)
    chk.check(p.returncode == 2 and "strip_9" in p.stderr and "strip_1" in p.stderr and not os.path.exists(out),
              "refused: a surface group not in the mesh, before any run (exit %d): %s" % (p.returncode,
                                                                                           p.stderr.strip()[-200:]))
    # Duration and temperature from the load cases.
    cases = {"S": {"kind": "snow", "duration": "long", "temperature": 30, "loads": {"film_all_snow": 0.75}},
             "W": {"kind": "wind", "duration": "short", "temperature": 10, "loads": {"structure_wind": 0.5}}}
    d = designmod.Design(dict(DESIGN, load_cases=cases, combinations=[
        {"name": "SW", "situation": "ULS", "factors": {"S": 1.5, "W": 0.9}},
        {"name": "S", "situation": "ULS", "factors": {"S": 1.5, "W": 0}}]), "cases")
    got = [d.strength_class(c)[:2] for c in d.combinations]
    chk.check(got == [("short", 30.0), ("long", 30.0)],
              "duration and temperature from the load cases (shortest duration, highest temperature; a case at "
              "factor 0 takes no part): %s" % got)


def test(etfe, chk):
    with scratch_dir("etfe-design-resistance") as tmp:
        refusals(etfe, chk, tmp)
        dfile = os.path.join(tmp, "design.json")
        with open(dfile, "w") as f:
            json.dump(DESIGN, f)
        out = os.path.join(tmp, "run")
        p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "design-run"), dfile, "--out", out,
                            "-jobs", "2", "--etfe", etfe], capture_output=True, text=True, timeout=600)
        print(p.stdout + p.stderr)
        chk.check(p.returncode == 0, "design-run completes and every check passes (exit %d)" % p.returncode)
        with h5py.File(os.path.join(out, "envelope.h5"), "r") as f:
            X, tri = f["mesh/coordinates"][()], f["mesh/triangles"][()]
            env_u = f["envelope/utilisation"][()]
        groups = mesh_groups.element_groups(os.path.join(REPO, "meshes/hypar_canopy.msh"), X, tri)
        west, east = groups["strip_1"], groups["strip_2"]
        chk.check(west.sum() + east.sum() == len(tri) and not np.any(west & east) and west.sum() == east.sum(),
                  "the mesh's groups: strip_1 %d and strip_2 %d of %d elements" % (west.sum(), east.sum(), len(tri)))
        expect = {"COOL-SHORT": (fd(A, "short", 23), fd(B, "short", 23)),
                  "WARM-LONG": (fd(A, "long", 40), fd(B, "long", 40))}
        rows = {r["combination"]: r for r in csv.DictReader(open(os.path.join(out, "combinations.csv")))}
        checks = {r["combination"]: float(r["value"]) for r in csv.DictReader(open(os.path.join(out, "checks.csv")))}
        util = {}
        for name, (fa, fb) in expect.items():
            with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
                sigma = np.max([f["steps"][s]["cauchy_mises"][()] for s in f["steps"]], axis=0)
            util[name] = np.where(west, sigma / fa, sigma / fb)
            chk.check(rows[name]["design_resistance [MPa]"] == "A %.4g; B %.4g" % (fa, fb),
                      "%s: f_d per material %s (A %.6g, B %.6g MPa expected)"
                      % (name, rows[name]["design_resistance [MPa]"], fa, fb))
            chk.check(abs(checks[name] - util[name].max()) <= 1e-7 * util[name].max(),
                      "%s: the utilisation check %.8g = max over the elements of sigma / its group's f_d %.8g"
                      % (name, checks[name], util[name].max()))
        chk.check(np.array_equal(env_u, np.maximum(util["COOL-SHORT"], util["WARM-LONG"])),
                  "envelope utilisation per element = its Mises stress / its own group's f_d (A on strip_1, B on "
                  "strip_2), element-wise")
        # The strips' stresses alike (the hypar's symmetry): the weaker strip's utilisation is the higher.
        s_west = np.sort(util["COOL-SHORT"][west] * expect["COOL-SHORT"][0])
        s_east = np.sort(util["COOL-SHORT"][east] * expect["COOL-SHORT"][1])
        ua, ub = util["COOL-SHORT"][west].max(), util["COOL-SHORT"][east].max()
        want = expect["COOL-SHORT"][0] / expect["COOL-SHORT"][1]
        chk.check(abs(s_west[-1] / s_east[-1] - 1) < 0.01 and abs(ub / ua / want - 1) < 0.01,
                  "largest stress of strip_1 %.4f and strip_2 %.4f MPa alike; their utilisations %.4f (A) and %.4f "
                  "(B): the ratio %.4f follows the resistances' %.4f"
                  % (s_west[-1], s_east[-1], ua, ub, ub / ua, want))
        for k, (g, label) in enumerate(((west, "A"), (east, "B"))):
            ratio = util["WARM-LONG"][g] / util["COOL-SHORT"][g]
            scale = expect["COOL-SHORT"][k] / expect["WARM-LONG"][k]
            chk.check(expect["WARM-LONG"][k] < expect["COOL-SHORT"][k] and np.allclose(ratio, scale, rtol=1e-12, atol=0),
                      "material %s: long at 40 C f_d %.5g < short at 23 C %.5g MPa; utilisation ratio %.6f = %.6f "
                      "element-wise" % (label, expect["WARM-LONG"][k], expect["COOL-SHORT"][k], ratio.mean(), scale))
        report = open(os.path.join(out, "report.html")).read()
        chk.check('id="resistance"' in report and "strip_2" in report and "test values" in report,
                  "report.html: the resistance table (materials, their groups, the source)")


if __name__ == "__main__":
    main(test)
