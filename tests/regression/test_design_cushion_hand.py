#!/usr/bin/python3
"""Hand check of a cushion foil in the design run (scripts/design-run; docs/design-run.md).

A hexagonal two-layer cushion (scripts/cushion-mesh --hexagon 1000: circumradius 1 m) is inflated
to 0.3 kPa in the base state and one combination raises the supply to 0.5 kPa. At the top foil's centre the stress is
equibiaxial by the six-fold symmetry, so membrane equilibrium gives the hand check

    sigma = p R / (2 t),   utilisation = sigma / f_d,

p the chamber's gauge pressure (chambers/gauge_pressure of the combination's results, equal to its
history CSV's), R the foil's radius of curvature at its centre (z = c0 + c1 r^2 + c2 r^4 fitted to
the deformed top-foil nodes within 0.3 of the circumradius, R = -1 / (2 c1): the hexagon departs
from a surface of revolution only at r^6), t the current thickness t0 / (a / A0) of the centre
elements (the design run's Cauchy stress takes the film incompressible, stress_measures.h),
f_d = f_k k_mod / gamma_M. The
design run's utilisation and Cauchy von Mises stress at the centre elements (envelope.h5, the
elements around the top foil's centre node; checks.csv) must match it within the mesh error, which
is measured on two meshes (the centre stress and the difference change less than the bounds below
when the mesh is halved). The hexagon, not the circle: cushion-mesh cuts a circle into 48 sectors,
whose 48 slivers at the centre node make it a spike (its ring-1 curvature does not converge).
"""
import csv
import json
import os
import subprocess
import sys

import numpy as np

from etfe_testlib import REPO, main, scratch_dir

import h5py  # noqa: E402

A = 1000.0          # the hexagon's circumradius (mm)
T0 = 0.25           # foil thickness (mm)
PLANFORM = ["--hexagon", str(A)]
FIT = 0.3 * A       # the curvature fit takes the top foil's nodes within this plan radius
SIZES = (125.0, 62.5)  # cushion-mesh --size: 8 and 16 rings of triangles from the centre to a corner
# Measured 2026-11-27 (docs/design-run.md "Hand check of a cushion foil"): design run / hand check
# - 1 = +0.15 % (size 125), -0.06 % (62.5), -0.03 % (31.25); the centre's Cauchy stress 6.104,
# 6.148, 6.158 MPa (mesh error at 62.5 about 0.2 %, O(h^2)), the fitted R 6043, 6098, 6107 mm.
# 0.5 % on the finer mesh holds the mesh errors of both sides and fails PK2 for Cauchy (-0.9 % here)
# or the unstrained thickness t0 for the current one (+0.8 %).
TOL_FINE = 0.005
TOL_MESH = 0.01     # the centre stress changes by less than this from size 125 to 62.5 (measured 0.72 %)

DESIGN = {
    "title": "test: round cushion, hand check at the top foil's centre",
    "model": "options/design/cushion_model.opts",
    "base": {"stages": 1, "loads": {"chamber_air_pressure": [0.3]}, "note": "inflated to 0.3 kPa"},
    "increments_per_stage": 10,
    "load_cases": {"P": {"kind": "imposed", "description": "supply up by 0.2 kPa",
                         "loads": {"chamber_air_pressure": 0.2}}},
    "combinations": [{"name": "ULS-P", "situation": "ULS", "duration": "short", "factors": {"P": 1}}],
    "checks": [{"name": "stress utilisation", "kind": "utilisation", "situations": ["ULS"], "limit": 1.0}],
}


def one_mesh(etfe, tmp, size):
    msh = os.path.join(tmp, "round_%d.msh" % size)
    subprocess.run([sys.executable, os.path.join(REPO, "scripts", "cushion-mesh"), msh] + PLANFORM + [
                    "--size", str(size)], check=True, capture_output=True)
    dfile = os.path.join(tmp, "design_%d.json" % size)
    with open(dfile, "w") as f:
        json.dump(dict(DESIGN, options={"mesh_file": msh}), f)
    out = os.path.join(tmp, "run_%d" % size)
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "design-run"), dfile, "--out", out,
                        "-jobs", "1", "--etfe", etfe], capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        print(p.stdout + p.stderr)
    with h5py.File(os.path.join(out, "envelope.h5"), "r") as f:
        X, tri = f["mesh/coordinates"][()], f["mesh/triangles"][()]
        util = f["envelope/utilisation"][()].ravel()
        mises = f["envelope/cauchy_mises"][()].ravel()
    with h5py.File(os.path.join(out, "ULS-P.h5"), "r") as f:
        g = f["steps"][sorted(f["steps"].keys())[-1]]
        u, area_ratio = g["displacement"][()], g["area_ratio"][()].ravel()
        p_mpa = float(g["chambers/gauge_pressure"][0])   # MPa, the chamber's gauge pressure
    with open(os.path.join(out, "ULS-P_history.csv")) as f:
        p_kpa = float(list(csv.DictReader(f))[-1]["air_p_kPa"])
    with open(os.path.join(out, "checks.csv")) as f:
        util_check = [float(r["value"]) for r in csv.DictReader(f) if r["combination"] == "ULS-P"][0]
    x = X + u
    r0 = np.hypot(X[:, 0], X[:, 1])
    top = X[:, 2] > 1e-9                       # the top foil's nodes (the lens lifts them), rim excluded
    centre = int(np.argmax(np.where(top, x[:, 2], -np.inf)))
    around = np.where((tri == centre).any(axis=1))[0]
    near = top & (r0 < FIT)
    r = np.hypot(x[near, 0], x[near, 1])
    c = np.polyfit(r ** 2, x[near, 2], 2)       # z = c[0] r^4 + c[1] r^2 + c[2]
    R = -1.0 / (2.0 * c[1])
    t = T0 / area_ratio[around].mean()
    fd = 21.0 * 1.0 / 1.2                        # the example resistance, k_mod short
    sigma_hand = p_mpa * R / (2.0 * t)
    rise = x[centre, 2]
    return dict(n_tri=len(tri), p=p_mpa * 1e3, p_csv=p_kpa, R=R, t=t, rise=rise,
                sigma_hand=sigma_hand, util_hand=sigma_hand / fd, mises=mises[around].mean(),
                mises_spread=np.ptp(mises[around]), util=util[around].mean(), util_max=util.max(),
                util_check=util_check, rc=p.returncode)


def test(etfe, chk):
    res = {}
    with scratch_dir("etfe-design-hand") as tmp:
        for h in SIZES:
            q = res[h] = one_mesh(etfe, tmp, h)
            q["rel"] = q["util"] / q["util_hand"] - 1.0
            print("  size %g mm (%d triangles): p %.4f kPa, rise %.2f mm, R fit %.1f mm, "
                  "t %.5f mm; hand sigma %.4f MPa, utilisation %.5f; design run Cauchy Mises %.4f MPa "
                  "(spread %.2e over the centre elements), utilisation %.5f (largest %.5f, checks.csv %.5f); "
                  "difference %+.4f" % (h, q["n_tri"], q["p"], q["rise"], q["R"], q["t"],
                                         q["sigma_hand"], q["util_hand"], q["mises"], q["mises_spread"],
                                         q["util"], q["util_max"], q["util_check"], q["rel"]))
            chk.check(abs(q["p"] - q["p_csv"]) < 1e-6 and abs(q["p"] - 0.5) < 1e-9,
                      "size %g: gauge pressure %.6f kPa (results) = %.6f kPa (history CSV) = the supply 0.5 kPa"
                      % (h, q["p"], q["p_csv"]))
            chk.check(abs(q["util_check"] - q["util_max"]) < 1e-6 * q["util_max"],
                      "size %g: checks.csv's utilisation = the envelope's largest" % h)
            chk.check(q["rc"] == 0, "size %g: design-run exits 0 (every check passes)" % h)
            chk.check(abs(q["util"] * 17.5 - q["mises"]) < 1e-9 * q["mises"],
                      "size %g: utilisation = Cauchy von Mises / f_d (17.5 MPa) at the centre elements" % h)
    coarse, fine = res[SIZES[0]], res[SIZES[1]]
    chk.less(abs(fine["rel"]), TOL_FINE, "size %g: |design-run utilisation / hand check - 1| at the centre" % SIZES[1])
    chk.check(abs(fine["rel"]) < abs(coarse["rel"]),
              "the difference shrinks with the mesh: %.4f (size %g) -> %.4f (size %g)"
              % (coarse["rel"], SIZES[0], fine["rel"], SIZES[1]))
    chk.less(abs(fine["mises"] / coarse["mises"] - 1.0), TOL_MESH,
             "the centre's Cauchy stress from size %g to %g (%.4f -> %.4f MPa): the mesh error"
             % (SIZES[0], SIZES[1], coarse["mises"], fine["mises"]))


if __name__ == "__main__":
    main(test)
