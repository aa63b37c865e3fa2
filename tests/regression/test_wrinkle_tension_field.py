#!/usr/bin/python3
"""Tension-field membrane (-membrane_wrinkling tension_field) on the scenes that have a
closed form.

(a) No wrinkle forms (Hencky's pressurized membrane; the elastic biaxial patch; the plastic
    biaxial patch stretched past both yield stresses, so taut plastic elements run the return map):
    every element is taut (wrinkle_state 0 everywhere) at every loaded step and every field of
    the -membrane_wrinkling none run is reproduced to rtol 1e-10 at every written step
    (scripts/h5compare.py; absolute floor 1e-10 of the field's loaded scale for the unloaded
    step 0, whose round-off strains may classify either way).
(b) Uniform tension field: the pure-shear patch (Eyy = -Exx, irregular mesh) wrinkles in every
    element with the wrinkles along x (angle 0): Sxx = E Exx, Syy = Sxy = 0, wrinkle_dir = (+-1, 0, 0),
    wrinkle_strain = (1 - nu) Exx, all to 1e-8 (the wrinkle angles 30/45/90 deg and the shear
    panel with pretension are checked at kernel level in tests/unit/test_wrinkling.cpp).
(b') Shear panel (-patch_mode shear: pretension 1e-3 in X and Y plus the shear g = du_x/dY on
    every edge node; interior nodes free): with g = 0.01 every element wrinkles at ~45 deg; the
    closed form of the homogeneous F = [[1+e0, g], [0, 1+e0]] (E1 and its direction n of the GL
    strain, S = E E1 n n, wrinkle_dir = F n/|F n|, wrinkle_strain = -(E2 + nu E1)) holds to 1e-8;
    with g = 0.001 the panel stays taut and carries the plane-stress law's stress.
(b'') The same pure-shear patch with the ETFE elasto-plastic law: E Exx = 16.16 MPa is above the
    13.28 MPa yield stress, so every wrinkled element flows by the uniaxial return map:
    Sxx = Sy(ep) = E (Exx - ep) (closed form on the first hardening segment), Syy = Sxy = 0,
    plastic_strain_eq = ep, plastic strain ep (1, -1/2, 0), all to 1e-8.
(c) Newton on that wrinkling problem in one increment (elements go taut -> wrinkled on the way):
    quadratic at the end, r_{k+1}/r_k^2 < 0.1 per N on the last two iterations above the 1e-8 N
    round-off floor (measured ~1e-2), estimated order log(r_{k+1}/r_k)/log(r_k/r_{k-1}) > 1.5.
"""
import math
import os
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

YOUNG, NU = 800.0, 0.43
NO_WRINKLE = {
    "hencky": ["-options_file", T.opts("hencky")],
    "patch_biaxial": ["-options_file", T.opts("patch"), "-patch_mode", "biaxial", "-patch_strain_y", "0.01"],
    "patch_biaxial_plastic": ["-options_file", T.opts("patch"), "-patch_mode", "biaxial", "-patch_strain_x",
                              "0.06", "-patch_strain_y", "0.03", "-material_type", "plastic",
                              "-load_increments", "6"],
}
WRINKLE_FIELDS = ("wrinkle_state", "wrinkle_dir", "wrinkle_strain")


def same_as_none(chk, name, tf, none):
    # Step 0 is the unloaded start, strains and stresses at round-off (~1e-13 MPa) whose sign
    # decides the state there: the absolute floor is 1e-10 of the field's loaded (last step) scale.
    last = T.read_steps(none)[-1][2]
    # The principal directions are sign-free (h5compare leaves them out; they follow from cauchy_stress).
    fields = {n: (1e-10, 1e-10 * float(np.abs(v).max())) for n, v in last.items()
              if n not in T.h5compare.DIRECTIONS}
    failures, rows = T.h5compare.compare_rows(tf, none, step="all", fields=fields, only=True,
                                              default_rtol=1e-10, default_atol=1e-13)
    worst = max((r["max_rel"] for r in rows if r["step"] not in ("", "000000") and r["max_rel"] == r["max_rel"]),
                default=float("nan"))
    print("%s: %d field/step pairs compared, largest relative difference at the loaded steps %.3e"
          % (name, len(rows), worst))
    chk.check(len(rows) >= 10, "%s: compared %d field/step pairs" % (name, len(rows)))
    chk.check(not failures, "%s: tension_field equals none (rtol 1e-10)%s" % (
        name, "" if not failures else ":\n    " + "\n    ".join(failures[:5])))
    steps = T.read_steps(tf)
    for k, (_, _, d) in enumerate(steps):
        for w in WRINKLE_FIELDS:
            chk.check(w in d, "%s step %d: field %s written" % (name, k, w))
        if "wrinkle_state" in d and k > 0:
            chk.check(np.all(d["wrinkle_state"] == 0), "%s step %d: every element taut (states %s)"
                      % (name, k, np.unique(d["wrinkle_state"])))
    if "plastic" in name:
        ep = float(steps[-1][2]["plastic_strain_eq"].min())
        chk.check(ep > 1e-3, "%s: every element yielded (smallest plastic_strain_eq %.3e)" % (name, ep))
    chk.check(all("wrinkle_state" not in d for _, _, d in T.read_steps(none)),
              "%s: the none run writes no wrinkle fields" % name)


def shear_panel(chk, etfe, tmp, e0, g, wrinkled):
    h5 = os.path.join(tmp, "shear_%g.h5" % g)
    T.run(etfe, ["-options_file", T.opts("patch"), "-patch_mode", "shear", "-patch_strain_x", e0, "-patch_shear", g,
                 "-membrane_wrinkling", "tension_field", "-load_increments", "1", "-output_file", h5,
                 "-load_monitor", "0"])
    d = T.read_steps(h5)[-1][2]
    F = np.array([[1 + e0, g], [0.0, 1 + e0]])
    E = 0.5 * (F.T @ F - np.eye(2))
    w, v = np.linalg.eigh(E)
    E2, E1, n = w[0], w[1], v[:, 1]
    label = "shear panel g = %g" % g
    if wrinkled:
        S = YOUNG * E1 * np.array([n[0] ** 2, n[1] ** 2, n[0] * n[1]])
        fn = F @ n
        fn = np.array([fn[0], fn[1], 0.0]) / np.linalg.norm(fn)
        lost = -(E2 + NU * E1)
    else:
        c = YOUNG / (1 - NU * NU)
        S = c * np.array([E[0, 0] + NU * E[1, 1], NU * E[0, 0] + E[1, 1], (1 - NU) * E[0, 1]])
    state = d["wrinkle_state"]
    print("%s: states %s, angle of n %.4f deg, S closed form %s, FE max deviation %.3e MPa" % (
        label, np.unique(state), math.degrees(math.atan2(n[1], n[0])), np.array2string(S, precision=8),
        float(np.abs(d["stress"] - S).max())))
    chk.check(np.all(state == (1 if wrinkled else 0)), "%s: every element %s" % (label, "wrinkled" if wrinkled else "taut"))
    scale = float(np.abs(S).max())
    chk.less(float(np.abs(d["stress"] - S).max()) / scale, 1e-8, "%s: PK2 stress vs closed form (relative)" % label)
    if wrinkled:
        # The direction's sign is free: compare n n^T.
        dirs = d["wrinkle_dir"]
        dev = max(float(np.abs(np.outer(x, x) - np.outer(fn, fn)).max()) for x in dirs)
        chk.less(dev, 1e-8, "%s: wrinkle_dir vs F n/|F n|" % label)
        chk.less(float(np.abs(d["wrinkle_strain"] - lost).max()) / lost, 1e-8, "%s: wrinkle_strain vs -(E2 + nu E1)" % label)


def main_test(etfe, chk):
    with T.scratch_dir("wrinkle") as tmp:
        for name, args in NO_WRINKLE.items():
            h5 = {}
            for w in ("none", "tension_field"):
                h5[w] = os.path.join(tmp, "%s_%s.h5" % (name, w))
                T.run(etfe, args + ["-membrane_wrinkling", w, "-output_file", h5[w], "-load_monitor", "0"])
            same_as_none(chk, name, h5["tension_field"], h5["none"])

        h5 = os.path.join(tmp, "pureshear.h5")
        _, out = T.run(etfe, ["-options_file", T.opts("patch"), "-patch_mode", "pureshear",
                              "-membrane_wrinkling", "tension_field", "-load_increments", "1",
                              "-snes_monitor", "-output_file", h5])
        lx = 1.0 + 0.02  # options/patch.opts: -patch_strain_x 0.02
        Exx = 0.5 * (lx * lx - 1.0)
        d = T.read_steps(h5)[-1][2]
        S, state, wd, ws = d["stress"], d["wrinkle_state"], d["wrinkle_dir"], d["wrinkle_strain"]
        sxx = YOUNG * Exx
        print("pureshear: %d elements, states %s; Sxx in [%.12e, %.12e] (closed form %.12e), |Syy|,|Sxy| <= %.2e"
              % (len(S), np.unique(state), S[:, 0].min(), S[:, 0].max(), sxx, np.abs(S[:, 1:]).max()))
        chk.check(np.all(state == 1), "pureshear: every element wrinkled")
        chk.less(float(np.abs(S[:, 0] - sxx).max() / sxx), 1e-8, "pureshear Sxx vs E Exx (relative)")
        chk.less(float(np.abs(S[:, 1:]).max() / sxx), 1e-8, "pureshear Syy, Sxy vs 0 (relative to Sxx)")
        chk.less(float(np.abs(np.abs(wd[:, 0]) - 1.0).max() + np.abs(wd[:, 1:]).max()), 1e-8,
                 "pureshear wrinkle_dir = (+-1, 0, 0)")
        chk.less(float(np.abs(ws - (1 - NU) * Exx).max() / Exx), 1e-8, "pureshear wrinkle_strain = (1-nu) Exx")

        h5p = os.path.join(tmp, "pureshear_plastic.h5")
        T.run(etfe, ["-options_file", T.opts("patch"), "-patch_mode", "pureshear", "-material_type", "plastic",
                     "-membrane_wrinkling", "tension_field", "-load_increments", "1", "-output_file", h5p,
                     "-load_monitor", "0"])
        d = T.read_steps(h5p)[-1][2]
        y0, h0 = 13.28, 80.5  # thesis Table 4.2, first segment (the plastic law's defaults)
        ep = (YOUNG * Exx - y0) / (YOUNG + h0)
        sp = y0 + h0 * ep
        print("pureshear plastic: states %s; Sxx in [%.12e, %.12e] (closed form %.12e), ep_bar in [%.10e, %.10e] "
              "(closed form %.10e)" % (np.unique(d["wrinkle_state"]), d["stress"][:, 0].min(), d["stress"][:, 0].max(),
                                       sp, d["plastic_strain_eq"].min(), d["plastic_strain_eq"].max(), ep))
        chk.check(ep > 0 and np.all(d["wrinkle_state"] == 1), "pureshear plastic: every element wrinkled and yielding")
        chk.less(float(np.abs(d["stress"][:, 0] - sp).max()) / sp, 1e-8, "pureshear plastic Sxx vs Sy(ep)")
        chk.less(float(np.abs(d["stress"][:, 1:]).max()) / sp, 1e-8, "pureshear plastic Syy, Sxy vs 0")
        chk.less(float(np.abs(d["plastic_strain_eq"] - ep).max()) / ep, 1e-8, "pureshear plastic ep_bar")
        chk.less(float(np.abs(d["plastic_strain"] - np.array([ep, -0.5 * ep, 0.0])).max()) / ep, 1e-8,
                 "pureshear plastic strain (ep, -ep/2, 0)")

        for g, wrinkled in ((0.01, True), (0.001, False)):
            shear_panel(chk, etfe, tmp, 1e-3, g, wrinkled)

        hist = T.snes_histories(out)
        chk.check(len(hist) >= 1 and len(hist[0]) >= 4, "pureshear: a Newton history was printed")
        r = [v for v in hist[0] if v > 1e-8]
        print("pureshear Newton residuals: " + ", ".join("%.3e" % v for v in hist[0]))
        if len(r) >= 3:
            c = [r[k + 1] / r[k] ** 2 for k in (len(r) - 3, len(r) - 2)]
            order = math.log(r[-1] / r[-2]) / math.log(r[-2] / r[-3])
            print("pureshear: r_{k+1}/r_k^2 = %.3e, %.3e; order %.2f" % (c[0], c[1], order))
            chk.less(max(c), 0.1, "pureshear Newton r_{k+1}/r_k^2 on the last two iterations")
            chk.check(order > 1.5, "pureshear Newton order %.2f > 1.5" % order)
            chk.less(hist[0][-1], 1e-8, "pureshear converged residual")


if __name__ == "__main__":
    T.main(main_test)
