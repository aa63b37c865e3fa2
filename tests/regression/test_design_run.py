#!/usr/bin/python3
"""Load combinations from one base state (scripts/design-run, -restart_branch; docs/design-run.md).

On the hypar canopy (form-found here): the base state (frame drawn in, self-weight) is solved
once and checkpointed; three combinations branch from it, two at a time:
  * a combination's results equal, bit for bit, a direct run of the same factored loads through
    the same base stages (no checkpoint);
  * the base ran once for the 3 combinations (commands.log, and each branch starts at the base's
    increment and load time);
  * the envelopes equal the element-wise and node-wise extremes of the combinations' last steps,
    with the governing combination;
  * a combination that cannot converge (Newton limited to 1 iteration, no cut-back) is reported as
    not converged, the envelopes say incomplete, its checks fail and the exit status is 1;
  * a branch stopped half-way continues with a plain -restart of its own checkpoint, bit for bit;
  * a branch whose base stages differ is refused, and a plain -restart with changed loads still is;
  * the tables are CSV, and the HTML report opens in headless Chromium (when installed: scripts/setup
    installs it) with no console error, and its verdict table is the CSV's.
On a film strip with an edge cable under its weight (every increment written): the envelopes are
the extremes over every written step of each combination's stage (a combination that lowers the
weight has its largest stresses and cable force at its first step, not its last); the largest
cable force per cable and its combination (envelope_cables.csv, envelope.h5, report) and the cable
check (force against breaking load / 1.5, the default factor) per combination; a combination of
two cases that both give structure_wind is refused.
"""
import csv
import glob
import html.parser
import json
import os
import shutil
import subprocess
import sys

import numpy as np

from etfe_testlib import REPO, main, run, scratch_dir

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cable_meshes  # noqa: E402

sys.path.insert(0, os.path.join(REPO, "scripts"))
import h5compare  # noqa: E402
import h5py  # noqa: E402
from etfepy import design as designmod  # noqa: E402
from etfepy import runner  # noqa: E402

DESIGN = {
    "title": "test: hypar canopy",
    "model": "options/design/hypar_model.opts",
    "base": {"stages": 2, "loads": {"structure_self_weight": [1, 1]}, "note": "frame drawn in, self-weight"},
    "increments_per_stage": 5,
    "load_cases": {
        "G": {"kind": "permanent", "in_base": True, "loads": {"structure_self_weight": 1}},
        "S": {"kind": "snow", "loads": {"film_all_snow": 0.75}},
        "W": {"kind": "wind", "loads": {"structure_wind": 0.5}, "options": {"film_all_wind_cp": -0.8}},
    },
    "combinations": [
        {"name": "ULS-S", "situation": "ULS", "duration": "short", "factors": {"G": "gamma_G_sup", "S": "gamma_Q"}},
        {"name": "SLS-W", "situation": "SLS", "factors": {"G": 1, "W": 1}},
        {"name": "STUCK", "situation": "ULS", "duration": "short", "factors": {"G": 1, "S": 8},
         "options": {"snes_max_it": 1, "load_max_cutbacks": 0}},
    ],
    "checks": [
        {"name": "utilisation", "kind": "utilisation", "situations": ["ULS"], "limit": 1.0},
        {"name": "deflection", "kind": "deflection", "situations": ["SLS"], "limit": 150},
        {"name": "wrinkled area", "kind": "wrinkled_area", "situations": ["SLS"], "limit": 3.0},
    ],
}


class Tables(html.parser.HTMLParser):
    """The rows of the <table id=...> elements of a page: {id: [[cell text]]}."""

    def __init__(self):
        super().__init__()
        self.tables, self.current, self.row, self.cell = {}, None, None, None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.current = dict(attrs).get("id")
            self.tables[self.current] = []
        elif tag == "tr" and self.current is not None:
            self.row = []
        elif tag in ("td", "th") and self.row is not None:
            self.cell = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self.cell is not None:
            self.row.append(self.cell.strip())
            self.cell = None
        elif tag == "tr" and self.row is not None:
            self.tables[self.current].append(self.row)
            self.row = None
        elif tag == "table":
            self.current = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data


def last_step(path):
    with h5py.File(path, "r") as f:
        g = f["steps"][sorted(f["steps"].keys())[-1]]
        return {k: g[k][()] for k in g.keys()}


def browser(chk, tmp, report, checks_csv):
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if not exe:
        print("  SKIP  the report in headless Chromium: chromium is not installed (scripts/setup installs it)")
        return
    base = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--enable-logging=stderr", "--v=0",
            "--user-data-dir=" + os.path.join(tmp, "chromium-profile")]

    def console_errors(page):
        p = subprocess.run(base + ["--dump-dom", "file://" + page], capture_output=True, text=True, timeout=180)
        errs = [l for l in p.stderr.splitlines() if "CONSOLE" in l and ("error" in l.lower() or "Uncaught" in l)]
        return p.stdout, errs

    # The detector first sees an error where there is one.
    bad = os.path.join(tmp, "bad.html")
    with open(bad, "w") as f:
        f.write("<html><body><script>console.error('deliberate'); undefined_call();</script></body></html>")
    _, errs = console_errors(bad)
    chk.check(len(errs) >= 1, "Chromium: a page with console.error and an uncaught error shows %d error lines "
                              "(the detector works)" % len(errs))
    dom, errs = console_errors(report)
    chk.check(not errs, "Chromium: the report opens with no console error%s" % ("" if not errs else ": " + errs[0]))
    shot = os.path.join(tmp, "report.png")
    subprocess.run(base + ["--screenshot=" + shot, "--window-size=1200,1800", "file://" + report],
                   capture_output=True, timeout=180)
    chk.check(os.path.exists(shot) and os.path.getsize(shot) > 10000,
              "Chromium: screenshot of the report (%d bytes)" % (os.path.getsize(shot) if os.path.exists(shot) else 0))
    t = Tables()
    t.feed(dom)
    rows = t.tables.get("verdicts", [])[1:]
    with open(checks_csv) as f:
        csv_rows = list(csv.DictReader(f))
    same = len(rows) == len(csv_rows) and all(r[0] == c["check"] and r[1] == c["combination"] and r[6] == c["verdict"]
                                              for r, c in zip(rows, csv_rows))
    chk.check(same, "Chromium: the rendered verdict table has the CSV's %d rows (check, combination, verdict)"
              % len(csv_rows))


def all_steps(path):
    with h5py.File(path, "r") as f:
        out = []
        for s in sorted(f["steps"].keys()):
            g = f["steps"][s]
            st = {k: g[k][()] for k in g.keys() if not isinstance(g[k], h5py.Group)}
            st["cable_force"] = g["cables/force"][()]
            out.append(st)
        return out


# breaking load 1080 N: limit 720 N at the default factor 1.5 (the ULS force, 766 N, is above, the others
# below: SLS 667 N, UNLOAD 523 N)
CABLE_DESIGN = {
    "title": "test: strip with an edge cable",
    "base": {"stages": 1, "loads": {"cable_cable_weight": [5]}, "note": "cable weight 5 N/m"},
    "increments_per_stage": 4,
    "load_cases": {"G": {"kind": "permanent", "in_base": True, "loads": {"cable_cable_weight": 5}},
                   "Q": {"kind": "imposed", "loads": {"cable_cable_weight": 10}}},
    "combinations": [{"name": "ULS-Q", "situation": "ULS", "factors": {"G": "gamma_G_sup", "Q": "gamma_Q"}},
                     {"name": "SLS-Q", "situation": "SLS", "duration": "short", "factors": {"G": 1, "Q": 1}},
                     {"name": "UNLOAD", "situation": "SLS", "duration": "short", "factors": {"G": 0.5}}],
    "checks": [{"name": "cable force", "kind": "cable_force", "situations": ["ULS", "SLS"],
                "breaking_load": {"cable": 1080}},
               {"name": "utilisation", "kind": "utilisation", "situations": ["SLS"]}],
}


def cable_checks(etfe, chk, tmp):
    two_winds = dict(DESIGN, load_cases=dict(DESIGN["load_cases"], WY=dict(DESIGN["load_cases"]["W"])),
                     combinations=[{"name": "XY", "factors": {"G": 1, "W": 1, "WY": 1}}])
    try:
        designmod.Design(two_winds, "two winds")
        chk.check(False, "a combination of two structure_wind cases is refused")
    except designmod.DesignError as e:
        chk.check("film_<zone>_pressure" in str(e), "a combination of two structure_wind cases is refused: %s" % e)
    zones = dict(DESIGN, load_cases=dict(DESIGN["load_cases"],
                                         WX={"kind": "wind", "loads": {"film_a_pressure": 0.35, "film_b_pressure": -0.25}},
                                         WY={"kind": "wind", "loads": {"film_a_pressure": -0.2, "film_b_pressure": -0.2}}),
                 combinations=[{"name": "XY", "duration": "short", "factors": {"G": 1, "WX": 1.5, "WY": 0.9}}])
    got = designmod.Design(zones, "zones").combination_loads(designmod.Design(zones, "zones").combinations[0])
    chk.check(abs(got["film_a_pressure"] - (1.5 * 0.35 - 0.9 * 0.2)) < 1e-15 and
              abs(got["film_b_pressure"] - (-1.5 * 0.25 - 0.9 * 0.2)) < 1e-15,
              "per-zone wind pressure cases add up in one combination: %s" % got)
    model = cable_meshes.strip_model(tmp, "cable_model.opts")
    dfile = os.path.join(tmp, "cable_design.json")
    with open(dfile, "w") as f:
        json.dump(dict(CABLE_DESIGN, model=model), f)
    out = os.path.join(tmp, "cable_run")
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "design-run"), dfile, "--out", out, "-jobs", "2",
                        "--etfe", etfe], capture_output=True, text=True, timeout=600)
    print(p.stdout + p.stderr)
    chk.check(p.returncode == 1, "cable design-run exits 1 (the ULS cable check fails), got %d" % p.returncode)
    names = [c["name"] for c in CABLE_DESIGN["combinations"]]
    steps = {n: all_steps(os.path.join(out, n + ".h5")) for n in names}
    chk.check(all(len(v) == 4 for v in steps.values()), "each branch wrote its 4 increments (%s)"
              % {n: len(v) for n, v in steps.items()})

    # Field envelopes over every written step, not the last only.
    every = np.max([st["principal_stress"][:, 0] for n in names for st in steps[n]], axis=0)
    last = np.max([steps[n][-1]["principal_stress"][:, 0] for n in names], axis=0)
    low = np.min([st["principal_stress"][:, 0] for n in names for st in steps[n]], axis=0)
    with h5py.File(os.path.join(out, "envelope.h5"), "r") as f:
        e = f["envelope/max_principal_stress"][()]
        chk.check(np.array_equal(e, every), "envelope of the largest principal stress = element-wise max over every "
                                            "written step (%d of %d elements above the last steps' max)"
                  % (int(np.sum(every > last)), len(e)))
        chk.check(np.array_equal(f["envelope/lowest_major_stress"][()], low),
                  "envelope of the smallest major stress = element-wise min over every written step")
        fmax = {n: max(float(st["cable_force"].max()) for st in steps[n]) for n in names}
        gov = max(names, key=lambda n: fmax[n])
        d = f["cables/cable_force_max"]
        chk.check(float(d[0]) == fmax[gov] and d.attrs["governing"] == gov,
                  "envelope.h5: largest cable force %.6g N from %s = the largest segment force over every step and "
                  "combination" % (float(d[0]), d.attrs["governing"]))
    first, lastf = float(steps["UNLOAD"][0]["cable_force"].max()), float(steps["UNLOAD"][-1]["cable_force"].max())
    chk.check(first > lastf, "UNLOAD (weight 5 -> 2.5 N/m): its largest cable force is at its first step, %.6g N > "
                             "%.6g N at its last" % (first, lastf))
    rows = list(csv.DictReader(open(os.path.join(out, "checks.csv"))))
    u = [float(r["value"]) for r in rows if r["check"] == "utilisation" and r["combination"] == "UNLOAD"]
    fd = 21.0 * 1.0 / 1.2
    u_every = max(float(st["cauchy_mises"].max()) for st in steps["UNLOAD"]) / fd
    u_last = float(steps["UNLOAD"][-1]["cauchy_mises"].max()) / fd
    chk.check(len(u) == 1 and abs(u[0] - u_every) <= 1e-7 * u_every and u_every > u_last * (1 + 1e-6),
              "UNLOAD's utilisation check %s = its largest over every written step %.8g (its last step's: %.8g)"
              % (u[0] if u else "?", u_every, u_last))
    env = list(csv.DictReader(open(os.path.join(out, "envelope_cables.csv"))))
    chk.check(len(env) == 1 and env[0]["cable"] == "cable" and env[0]["combination"] == gov and
              float(env[0]["max_force [N]"]) == float("%.8g" % fmax[gov]),
              "envelope_cables.csv: cable, %s N, %s" % (env[0]["max_force [N]"] if env else "?", gov))
    rows = [r for r in rows if r["check"] == "cable force"]
    want = {n: "pass" if fmax[n] <= 720.0 else "FAIL" for n in names}
    got = {r["combination"]: r["verdict"] for r in rows}
    chk.check(got == want and set(want.values()) == {"pass", "FAIL"} and
              all(float(r["value"]) == float("%.8g" % fmax[r["combination"]]) and float(r["limit"]) == 720.0
                  for r in rows),
              "cable check per combination: largest force over its steps against 1080 N / 1.5 = 720 N: %s (forces %s)"
              % (got, {n: round(v, 1) for n, v in fmax.items()}))
    combs = list(csv.DictReader(open(os.path.join(out, "combinations.csv"))))
    chk.check(all(c["cable_forces [N]"].startswith("cable ") and c["steps [1]"] == "4" for c in combs),
              "combinations.csv: the largest force per cable and the steps the envelope covers")
    t = Tables()
    t.feed(open(os.path.join(out, "report.html")).read())
    chk.check(len(t.tables.get("cables", [])) == 2, "report.html: the table of the largest cable force per cable")


def test(etfe, chk):
    with scratch_dir("etfe-design-run") as tmp:
        cable_checks(etfe, chk, tmp)
        checks(etfe, chk, tmp)


def checks(etfe, chk, tmp):
    # EN 1990 generation (no run): snow leading and wind leading with G favourable.
    gen = dict(DESIGN, combinations=[], generate=["ULS", "SLS"])
    gen["load_cases"] = dict(DESIGN["load_cases"], W=dict(DESIGN["load_cases"]["W"], G_favourable=True, duration="short"),
                             S=dict(DESIGN["load_cases"]["S"], duration="medium"))
    got = {c["name"]: c["factors"] for c in designmod.Design(gen, "gen").combinations}
    want = {"ULS-S": {"G": 1.35, "S": 1.5, "W": 1.5 * 0.6}, "ULS-W": {"G": 1.0, "W": 1.5, "S": 1.5 * 0.5},
            "SLS-S": {"G": 1.0, "S": 1.0, "W": 0.6}, "SLS-W": {"G": 1.0, "W": 1.0, "S": 0.5}}
    chk.check(got == want, "generated EN 1990 combinations (recommended factors): %s" % got)
    ff = os.path.join(tmp, "hypar_ff.msh")
    run(etfe, ["-options_file", os.path.join(REPO, "options/structure/hypar_formfind.opts"), "-formfind_monitor", 0,
               "-output", 0, "-formfind_mesh_out", ff, "-output_file", os.path.join(tmp, "ff.h5")])
    design = dict(DESIGN, options={"mesh_file": ff})
    dfile = os.path.join(tmp, "design.json")
    with open(dfile, "w") as f:
        json.dump(design, f)
    out = os.path.join(tmp, "run")
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "design-run"), dfile, "--out", out, "-jobs", "2",
                        "--etfe", etfe], capture_output=True, text=True, timeout=900)
    print(p.stdout + p.stderr)
    chk.check(p.returncode == 1, "design-run exits 1 (a combination did not converge), got %d" % p.returncode)
    res = json.load(open(os.path.join(out, "design-run.json")))
    chk.check(res["missing"] == ["STUCK"], "the non-converging combination is reported: missing = %s" % res["missing"])

    # Base once.
    cmds = [l.split("\t") for l in open(os.path.join(out, "commands.log")).read().splitlines()]
    bases = [c for c in cmds if c[0] == "base"]
    branches = [c for c in cmds if c[0] == "combination"]
    chk.check(len(bases) == 1 and len(branches) == 3 and all("-restart_branch" in c[2] for c in branches)
              and "-restart_branch" not in bases[0][2],
              "the base state was solved once (%d base runs) for %d combinations, each a -restart_branch of it"
              % (len(bases), len(branches)))
    for name in ("ULS-S", "SLS-W"):
        log = open(os.path.join(out, name + ".log")).read()
        chk.check("restart (branch): from %s at increment 10, load time 2" % os.path.join(out, "base.checkpoint.h5")
                  in log, "%s starts from the base checkpoint at increment 10, load time 2" % name)

    # Branch == direct run, bit for bit.
    d = designmod.Design(design, dfile)
    comb = d.combinations[0]
    direct_dir = os.path.join(tmp, "direct")
    os.makedirs(direct_dir, exist_ok=True)
    args = d.combination_args(comb, direct_dir, branch=False)
    r = runner.run(args, etfe=etfe, timeout=600)
    chk.check(r.returncode == 0, "the direct run of ULS-S (base stages and the combination in one history) completes")
    fails = h5compare.compare(os.path.join(out, "ULS-S.h5"), os.path.join(direct_dir, "ULS-S.h5"), step="last",
                              default_rtol=0.0, default_atol=0.0)
    chk.check(not fails, "ULS-S from the base checkpoint equals the direct run bit for bit (every field of the last "
                         "step)%s" % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))

    # A branch stopped half-way continues with a plain -restart from its own checkpoint.
    stop_dir = os.path.join(tmp, "stop")
    args = d.combination_args(comb, stop_dir)
    args[args.index("-restart_branch") + 1] = os.path.join(out, "base.checkpoint.h5")
    r1 = runner.run(args + ["-load_stop_after", 12], etfe=etfe, timeout=600)
    args = [a for a in args if a not in ("-restart_branch", os.path.join(out, "base.checkpoint.h5"))]
    r2 = runner.run(args + ["-restart", os.path.join(stop_dir, "ULS-S.checkpoint.h5")], etfe=etfe, timeout=600)
    fails = h5compare.compare(os.path.join(stop_dir, "ULS-S.h5"), os.path.join(out, "ULS-S.h5"), step="last",
                              default_rtol=0.0, default_atol=0.0)
    chk.check(r1.returncode == 0 and r2.returncode == 0 and not fails,
              "ULS-S stopped at increment 12 and continued with -restart equals the uninterrupted branch bit for bit")

    # Envelopes: element-wise extremes.
    s1, s2 = last_step(os.path.join(out, "ULS-S.h5")), last_step(os.path.join(out, "SLS-W.h5"))
    with h5py.File(os.path.join(out, "envelope.h5"), "r") as f:
        chk.check(f.attrs["complete"] == 0 and "STUCK" in str(f.attrs["missing"]),
                  "the envelope file says incomplete (missing STUCK)")
        e = f["envelope/max_principal_stress"][()]
        g = f["envelope/max_principal_stress_governing"][()]
        ref = np.maximum(s1["principal_stress"][:, 0], s2["principal_stress"][:, 0])
        gref = np.where(s2["principal_stress"][:, 0] > s1["principal_stress"][:, 0], 1, 0)
        chk.check(np.array_equal(e, ref) and np.array_equal(g, gref),
                  "envelope of the largest principal stress = element-wise max of the combinations, governing "
                  "index right (%d elements governed by SLS-W)" % int(np.sum(gref)))
        m = f["envelope/cauchy_mises"][()]
        chk.check(np.array_equal(m, np.maximum(s1["cauchy_mises"], s2["cauchy_mises"])),
                  "envelope of the Mises stress = element-wise max")
        u = f["envelope/displacement_magnitude"][()]
        ur = np.maximum(np.linalg.norm(s1["displacement"], axis=1), np.linalg.norm(s2["displacement"], axis=1))
        chk.check(np.array_equal(u, ur), "envelope of |u| = node-wise max")
        w = f["envelope/wrinkle_state"][()]
        chk.check(np.array_equal(w, np.maximum(s1["wrinkle_state"], s2["wrinkle_state"])),
                  "envelope of the wrinkle state = element-wise max")
    xmf = open(os.path.join(out, "envelope.xmf")).read()
    chk.check("max_principal_stress_governing" in xmf and "envelope.h5:/envelope/utilisation" in xmf,
              "envelope.xmf lists the envelopes and their governing combination for ParaView")

    pv = shutil.which("pvpython")
    if pv:
        script = os.path.join(tmp, "pv.py")
        with open(script, "w") as f:
            f.write("import sys\nfrom paraview.simple import *\nr = Xdmf3ReaderS(FileName=[sys.argv[1]])\n"
                    "r.UpdatePipeline()\nd = servermanager.Fetch(r)\nc = d.GetCellData()\n"
                    "print('CELLS', d.GetNumberOfCells(), 'ARRAYS', ' '.join(c.GetArrayName(i) for i in "
                    "range(c.GetNumberOfArrays())))\n")
        p = subprocess.run([pv, script, os.path.join(out, "envelope.xmf")], capture_output=True, text=True,
                           timeout=300)
        got = [l for l in p.stdout.splitlines() if l.startswith("CELLS")]
        chk.check(got and "utilisation_governing" in got[0] and got[0].split()[1] == str(len(e)),
                  "ParaView (pvpython, Xdmf3ReaderS) opens envelope.xmf: %s" % (got[0][:80] if got else p.stderr[-200:]))
    else:
        print("  SKIP  envelope.xmf in ParaView: pvpython is not installed")

    # Checks and tables.
    rows = list(csv.DictReader(open(os.path.join(out, "checks.csv"))))
    stuck = [r for r in rows if r["combination"] == "STUCK"]
    chk.check(stuck and all(r["verdict"] == "not converged" for r in stuck),
              "the non-converging combination's checks say 'not converged' (%d rows)" % len(stuck))
    util = [r for r in rows if r["combination"] == "ULS-S" and r["check"] == "utilisation"]
    fd = 21.0 * 1.0 / 1.2
    umax = float(np.max(s1["cauchy_mises"])) / fd
    chk.check(util and abs(float(util[0]["value"]) - umax) <= 1e-7 * umax,
              "ULS-S utilisation %s = max Cauchy Mises / (f_k k_mod / gamma_M) = %.8f" % (util[0]["value"] if util else
                                                                                            "?", umax))
    combs = list(csv.DictReader(open(os.path.join(out, "combinations.csv"))))
    chk.check([c["combination"] for c in combs] == ["ULS-S", "SLS-W", "STUCK"] and
              combs[2]["status"].startswith("NOT CONVERGED") and int(combs[0]["newton_iterations [1]"]) > 0,
              "combinations.csv: one row per combination, Newton effort, STUCK not converged")
    report = os.path.join(out, "report.html")
    text = open(report).read()
    chk.check("<script" not in text and "http://" not in text.replace("http://www.w3.org/2000/svg", "") and
              "https://" not in text and "<svg" in text, "report.html is self-contained (no script, nothing fetched, "
                                                         "pictures inline SVG)")
    browser(chk, tmp, report, os.path.join(out, "checks.csv"))

    # Refusals.
    bad = designmod.Design(design, dfile)
    bad.base_loads["structure_self_weight"] = [1, 1.1]
    r = runner.run(bad.combination_args(comb, os.path.join(tmp, "bad")) [:-2] +
                   ["-restart_branch", os.path.join(out, "base.checkpoint.h5")], etfe=etfe, timeout=300)
    chk.check(r.returncode != 0 and "what they resolve to up to load time 2 does not" in r.output,
              "a branch whose base stages carry other loads (self-weight 1.1 in stage 2) is refused")
    r = runner.run(d.combination_args(comb, os.path.join(tmp, "bad"), branch=False) +
                   ["-restart", os.path.join(out, "base.checkpoint.h5")], etfe=etfe, timeout=300)
    chk.check(r.returncode != 0 and "this run's physics differs" in r.output,
              "a plain -restart with the combination's loads is still refused (a restart continues one history)")
    chk.check(not glob.glob(os.path.join(tmp, "bad", "*.h5")), "the refusals wrote no results")


if __name__ == "__main__":
    main(test)
