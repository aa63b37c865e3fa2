#!/usr/bin/python3
"""ETFE elasto-plasticity on the patch (options/patch.opts: irregular 8x4 mesh, every element must
carry the same state) against closed forms. Material: -material_type plastic, the thesis law
E = 800 MPa, nu = 0.43, yield 13.28 MPa with H' = 80.5 MPa, then 23.04 MPa with H' = 3 MPa.
Strains are Green-Lagrange, stresses 2nd Piola-Kirchhoff (what the law is written in).

(a) Uniaxial (free lateral edge): load to Exx = 0.2 (stretch sqrt(1.4)), unload past zero stress
    (schedule 0.8, Sxx ~ -11 MPa, inside the elastic range) and reload beyond the first peak
    (schedule 1.5), 60 increments. Closed form: Sxx = mono(Exx) while loading, with slopes E up to
    13.28 MPa, E H1/(E+H1) up to 23.04 MPa, then E H2/(E+H2); unloading elastic with slope E,
    Sxx = E (Exx - ep1); reloading elastic up to the previous peak, then back on mono:
    Sxx = min(E (Exx - ep1), mono(Exx)). Also ep_bar, plastic strain (ep, -ep/2, 0).
(b) Equibiaxial (Exx = Eyy = e): s = E/(1-nu) (e - ep/2) = Sy(ep); pure shear (Exx = -Eyy = e):
    Sxx = -Syy = tau = E/(1+nu) (e - sqrt(3)/2 ep), sqrt(3) tau = Sy(ep); ep by bisection.
    -patch_mode pureshear imposes Eyy = -Exx only at stage ends (the Y stretch is interpolated
    linearly inside a stage), so the pure-shear run uses ten stages of one increment each.
(c) Load-unload cycles: after a plastic peak the residual plastic strain and the zero-stress
    strain (intercept of the elastic unloading line, Exx - Sxx/E) are > 0 and equal the closed
    form; with an elastic peak the plastic strain is exactly 0 at every step and the zero-stress
    strain is 0 to round-off (< 1e-12).
(d) Newton on plastic increments (no extrapolated predictor, 4 increments to Exx = 0.2): the
    residual history shows quadratic convergence at the end: r_{k+1}/r_k^2 bounded (< 1e-2 per N;
    measured 4e-4 to 2e-3) on the last two iterations above the 1e-8 N round-off floor, the last
    one reducing the residual by more than 1e3, and an estimated order log(r_{k+1}/r_k)/log(r_k/r_{k-1}) > 1.5.
All closed-form comparisons: |FE - closed form| <= 1e-8 max(|closed form|, 1 MPa) for stresses,
1e-8 max(|value|, 1e-3) for strains.
"""
import math
import os
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

E, NU = 800.0, 0.43
YIELD, HARD = (13.28, 23.04), (80.5, 3.0)
EP1 = (YIELD[1] - YIELD[0]) / HARD[0]  # equivalent plastic strain where segment 2 starts
RTOL = 1e-8
S_FLOOR, E_FLOOR = 1.0, 1e-3


def sy(ep):
    """Yield stress after equivalent plastic strain ep (piecewise linear)."""
    return YIELD[0] + HARD[0] * ep if ep < EP1 else YIELD[1] + HARD[1] * (ep - EP1)


def mono(e):
    """Uniaxial monotonic loading curve S(E) written with the three slopes."""
    e0 = YIELD[0] / E                 # end of the elastic range
    e1 = YIELD[1] / E + EP1           # where segment 2 starts
    if e <= e0:
        return E * e
    if e <= e1:
        return YIELD[0] + E * HARD[0] / (E + HARD[0]) * (e - e0)
    return YIELD[1] + E * HARD[1] / (E + HARD[1]) * (e - e1)


def bisect(f, lo, hi, n=200):
    """Root of a decreasing f on [lo, hi]."""
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        if f(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def equibiaxial(e):
    """(s, ep): Sxx = Syy = s, equivalent plastic strain ep, for Exx = Eyy = e (monotonic)."""
    k = E / (1.0 - NU)
    if k * e <= YIELD[0]:
        return k * e, 0.0
    ep = bisect(lambda ep: k * (e - ep / 2) - sy(ep), 0.0, 2 * e)
    return sy(ep), ep


def pureshear(e):
    """(tau, ep): Sxx = -Syy = tau for Exx = -Eyy = e (monotonic)."""
    g = E / (1.0 + NU)
    if math.sqrt(3) * g * e <= YIELD[0]:
        return g * e, 0.0
    ep = bisect(lambda ep: math.sqrt(3) * g * (e - math.sqrt(3) / 2 * ep) - sy(ep), 0.0, 2 / math.sqrt(3) * e)
    return sy(ep) / math.sqrt(3), ep


def relerr(fe, cf, floor):
    return abs(fe - cf) / max(abs(cf), floor)


def uniform(chk, what, steps):
    """Max spread over elements (relative to the field's scale) of stress, strain, plastic strain."""
    worst = 0.0
    for _, _, d in steps:
        for name in ("stress", "strain", "plastic_strain", "plastic_strain_eq"):
            a = d[name].reshape(len(d[name]), -1)
            scale = max(np.abs(a).max(), 1e-3 if name != "stress" else 1.0)
            worst = max(worst, float((a.max(axis=0) - a.min(axis=0)).max() / scale))
    chk.less(worst, 1e-9, "%s: every element carries the same state (largest spread over elements)" % what)


def run_patch(etfe, tmp, name, args):
    h5 = os.path.join(tmp, name + ".h5")
    rc, out = T.run(etfe, ["-options_file", T.opts("patch"), "-material_type", "plastic", "-output_file", h5] + args)
    return out, T.read_steps(h5), T.status(h5)


def part_a(etfe, chk, tmp):
    ex = math.sqrt(1.4) - 1.0  # GL strain 0.2 at schedule value 1
    sched = (1.0, 0.8, 1.5)
    out, steps, st = run_patch(etfe, tmp, "uniaxial_cycle", ["-patch_mode", "uniaxial", "-patch_strain_x", repr(ex),
                                                             "-patch_schedule", "1,0.8,1.5", "-load_increments", "60"])
    chk.check(st == "complete", "(a) status complete")
    uniform(chk, "(a)", steps)
    e_max = 0.5 * ((1 + ex) ** 2 - 1)
    s_max = mono(e_max)
    ep1 = e_max - s_max / E
    e_un = 0.5 * ((1 + ex * sched[1]) ** 2 - 1)
    chk.check(abs(E * (e_un - ep1)) < sy(ep1),
              "(a) unloading stays elastic (S = %.3f MPa at the end of unloading, yield %.3f)" % (E * (e_un - ep1), sy(ep1)))
    print("(a) peak: Exx = %.6f, Sxx = %.6f MPa, ep = %.6f; zero stress at Exx = ep" % (e_max, s_max, ep1))
    worst = dict(S=0.0, ep=0.0, Ekin=0.0, Syy=0.0)
    table = []
    for k, at, d in steps:
        t = float(at["time"])
        stage = min(int(math.floor(t + 1e-12)), 2)
        frac = t - stage
        start = 0.0 if stage == 0 else sched[stage - 1]
        lam = 1 + ex * (start + frac * (sched[stage] - start))
        e_presc = 0.5 * (lam * lam - 1)
        e = float(d["strain"][0, 0])
        S = float(d["stress"][0, 0])
        if t <= 1 + 1e-12:
            S_cf = mono(e)
            ep_cf = e - S_cf / E
        elif t <= 2 + 1e-12:
            S_cf, ep_cf = E * (e - ep1), ep1
        else:
            S_cf = min(E * (e - ep1), mono(e))
            ep_cf = max(ep1, e - S_cf / E)
        worst["Ekin"] = max(worst["Ekin"], relerr(e, e_presc, E_FLOOR))
        worst["S"] = max(worst["S"], relerr(S, S_cf, S_FLOOR))
        worst["Syy"] = max(worst["Syy"], abs(float(d["stress"][0, 1])) / s_max, abs(float(d["stress"][0, 2])) / s_max)
        pe = d["plastic_strain"][0]
        worst["ep"] = max(worst["ep"], relerr(float(d["plastic_strain_eq"][0]), ep_cf, E_FLOOR),
                          relerr(float(pe[0]), ep_cf, E_FLOOR), relerr(float(pe[1]), -ep_cf / 2, E_FLOOR),
                          abs(float(pe[2])) / E_FLOOR)
        table.append((k, t, e, S, S_cf, float(d["plastic_strain_eq"][0])))
    print("(a) step   time     Exx (GL)    Sxx FE [MPa]   closed form    ep_bar")
    for k, t, e, S, S_cf, ep in table[::5] + ([table[-1]] if (len(table) - 1) % 5 else []):
        print("    %4d  %6.3f  %10.6f  %13.8f  %13.8f  %9.6f" % (k, t, e, S, S_cf, ep))
    chk.check(len(steps) == 61, "(a) 61 steps written (initial + 60 increments)")
    chk.less(worst["Ekin"], 1e-12, "(a) GL Exx = ((1 + ex s(t))^2 - 1)/2 at every step (relative)")
    chk.less(worst["S"], RTOL, "(a) uniaxial load/unload/reload Sxx vs closed form (relative, every step)")
    chk.less(worst["Syy"], RTOL, "(a) Syy, Sxy vanish (uniaxial stress): max |Syy|, |Sxy| / peak Sxx")
    chk.less(worst["ep"], RTOL, "(a) ep_bar and plastic strain (ep, -ep/2, 0) vs closed form")
    # The three loading slopes and the unloading slope, from consecutive steps inside each branch.
    slopes = {"elastic E": [], "E H1/(E+H1)": [], "E H2/(E+H2)": [], "unloading E": []}
    e0, e1 = YIELD[0] / E, YIELD[1] / E + EP1
    for (k0, a0, d0), (k1, a1, d1) in zip(steps, steps[1:]):
        ea, eb = float(d0["strain"][0, 0]), float(d1["strain"][0, 0])
        sa, sb = float(d0["stress"][0, 0]), float(d1["stress"][0, 0])
        slope = (sb - sa) / (eb - ea)
        t1 = float(a1["time"])
        if t1 <= 1 + 1e-12:
            key = "elastic E" if eb <= e0 else "E H1/(E+H1)" if ea >= e0 and eb <= e1 else "E H2/(E+H2)" if ea >= e1 else None
        elif t1 <= 2 + 1e-12:
            key = "unloading E"
        else:
            key = None
        if key:
            slopes[key].append(slope)
    want = {"elastic E": E, "E H1/(E+H1)": E * HARD[0] / (E + HARD[0]), "E H2/(E+H2)": E * HARD[1] / (E + HARD[1]),
            "unloading E": E}
    for key, vals in slopes.items():
        err = max(abs(v - want[key]) / want[key] for v in vals) if vals else float("nan")
        print("(a) slope %-12s = %.8f MPa (closed form %.8f) from %d step pairs, worst relative error %.2e"
              % (key, vals[-1] if vals else float("nan"), want[key], len(vals), err))
        chk.check(len(vals) >= 1 and err < 1e-6, "(a) slope %s matches (%d pairs, error %.2e)" % (key, len(vals), err))
    return out


def part_b(etfe, chk, tmp):
    res = {}
    # Pure shear: the scene imposes Eyy = -Exx exactly only at stage ends (inside a stage the Y
    # stretch is interpolated linearly, see src/scenes/patch.cpp), so the pure-shear path is one
    # stage per increment: 10 stages 0.1, 0.2, ..., 1.0 with one increment each. (Backward Euler
    # sees only the end-of-increment strains, so the discrete path is then exactly pure shear.)
    stages = ",".join("%.1f" % (0.1 * k) for k in range(1, 11))
    for mode, args, cf in (("equibiaxial", ["-patch_mode", "biaxial", "-patch_strain_x", "0.1", "-patch_strain_y", "0.1"], equibiaxial),
                           ("pureshear", ["-patch_mode", "pureshear", "-patch_strain_x", "0.1", "-patch_schedule", stages], pureshear)):
        out, steps, st = run_patch(etfe, tmp, mode, args + ["-load_increments", "10"])
        chk.check(st == "complete", "(b) %s: status complete" % mode)
        uniform(chk, "(b) %s" % mode, steps)
        worst_s = worst_e = worst_kin = 0.0
        for k, at, d in steps:
            e, eyy = float(d["strain"][0, 0]), float(d["strain"][0, 1])
            s, ep = cf(e)
            S, pe = d["stress"][0], d["plastic_strain"][0]
            if mode == "equibiaxial":
                worst_kin = max(worst_kin, relerr(eyy, e, E_FLOOR))
                want_S, want_p = (s, s, 0.0), (ep / 2, ep / 2, 0.0)
            else:
                worst_kin = max(worst_kin, relerr(eyy, -e, E_FLOOR))
                c = math.sqrt(3) / 2 * ep
                want_S, want_p = (s, -s, 0.0), (c, -c, 0.0)
            worst_s = max([worst_s] + [relerr(float(S[i]), want_S[i], S_FLOOR) for i in range(3)])
            worst_e = max([worst_e, relerr(float(d["plastic_strain_eq"][0]), ep, E_FLOOR)]
                          + [relerr(float(pe[i]), want_p[i], E_FLOOR) for i in range(3)])
        e, S, ep = float(steps[-1][2]["strain"][0, 0]), float(steps[-1][2]["stress"][0, 0]), float(steps[-1][2]["plastic_strain_eq"][0])
        print("(b) %s end: Exx = %.6f, Sxx = %.8f MPa (closed form %.8f), ep = %.8f (closed form %.8f); worst stress error %.2e, plastic strain error %.2e"
              % (mode, e, S, cf(e)[0], ep, cf(e)[1], worst_s, worst_e))
        chk.check(ep > 0.01, "(b) %s: the run goes well into the plastic range (ep = %.4f)" % (mode, ep))
        chk.less(worst_kin, 1e-11, "(b) %s: Eyy = %sExx" % (mode, "" if mode == "equibiaxial" else "-"))
        chk.less(worst_s, RTOL, "(b) %s: stresses vs closed form (every step)" % mode)
        chk.less(worst_e, RTOL, "(b) %s: ep_bar and plastic strain vs closed form (every step)" % mode)
        res[mode] = out
    return res


def part_c(etfe, chk, tmp):
    outs = {}
    for name, ex in (("plastic_peak", 0.05), ("elastic_peak", 0.01)):
        out, steps, st = run_patch(etfe, tmp, "cycle_" + name, ["-patch_strain_x", repr(ex), "-patch_schedule", "1,0.5",
                                                                 "-load_increments", "10"])
        chk.check(st == "complete", "(c) %s: status complete" % name)
        d = steps[-1][2]
        e, S = float(d["strain"][0, 0]), float(d["stress"][0, 0])
        e_res = e - S / E                      # zero-stress strain of the elastic unloading line
        p_res = float(d["plastic_strain"][0, 0])
        ep_bar = float(d["plastic_strain_eq"][0])
        e_max = 0.5 * ((1 + ex) ** 2 - 1)
        ep_cf = e_max - mono(e_max) / E
        print("(c) %s: peak Exx %.6f (Sxx %.4f MPa); unloaded Exx %.6f, Sxx %.6f MPa; zero-stress strain %.10f, "
              "plastic strain %.10f, ep_bar %.10f (closed form %.10f)" % (name, e_max, mono(e_max), e, S, e_res, p_res, ep_bar, ep_cf))
        if name == "plastic_peak":
            chk.check(e_res > 0 and p_res > 0 and ep_bar > 0, "(c) after yielding: residual strain %.3e, plastic strain %.3e > 0" % (e_res, p_res))
            chk.less(relerr(e_res, ep_cf, E_FLOOR), RTOL, "(c) zero-stress strain vs closed form ep(peak)")
            chk.less(relerr(p_res, ep_cf, E_FLOOR), RTOL, "(c) residual plastic strain vs closed form")
            chk.less(relerr(ep_bar, ep_cf, E_FLOOR), RTOL, "(c) ep_bar unchanged by elastic unloading")
        else:
            all_zero = all(float(np.abs(s[2]["plastic_strain"]).max()) == 0.0 and float(np.abs(s[2]["plastic_strain_eq"]).max()) == 0.0
                           for s in steps)
            chk.check(all_zero, "(c) elastic peak (%.3f MPa < 13.28): plastic strain exactly 0 at every step" % mono(e_max))
            chk.less(abs(e_res), 1e-12, "(c) elastic peak: zero-stress strain |Exx - Sxx/E|")
        outs[name] = out
    return outs


def quadratic(hist, floor=1e-8):
    """(ok, detail) for one Newton history: the last two steps above the round-off floor."""
    pairs = [(hist[i], hist[i + 1]) for i in range(len(hist) - 1) if hist[i + 1] >= floor]
    if len(pairs) < 2:
        return None, "too few iterations above the floor %g" % floor
    (r0, r1), (_, r2) = pairs[-2], pairs[-1]
    c = [r1 / r0 ** 2, r2 / r1 ** 2]
    order = math.log(r2 / r1) / math.log(r1 / r0)
    # Two-point order estimates are noisy before the asymptotic range: bounded r_{k+1}/r_k^2 is
    # the quadratic criterion; the order only has to be clearly superlinear.
    ok = max(c) < 1e-2 and r2 < 1e-3 * r1 and order > 1.5
    return ok, "r_{k+1}/r_k^2 = %.2e, %.2e; last reduction %.1e; order %.2f" % (c[0], c[1], r2 / r1, order)


def part_d(etfe, chk, tmp):
    cases = (("uniaxial 8x4", ["-patch_mode", "uniaxial"]),
             ("biaxial 16x8", ["-patch_mode", "biaxial", "-patch_strain_y", repr(math.sqrt(1.4) - 1.0), "-mesh_nx", "16", "-mesh_ny", "8"]))
    for name, args in cases:
        out, steps, st = run_patch(etfe, tmp, "newton_" + name.split()[0],
                                   args + ["-patch_strain_x", repr(math.sqrt(1.4) - 1.0), "-load_increments", "4",
                                           "-load_extrapolate", "0", "-snes_monitor"])
        hists, incs = T.snes_histories(out), T.increments(out)
        chk.check(len(hists) == len(incs) == 4, "(d) %s: 4 increments, 4 Newton solves (%d, %d)" % (name, len(incs), len(hists)))
        checked = 0
        for h, inc, (k, at, d) in zip(hists, incs, steps[1:]):
            plastic = float(d["plastic_strain_eq"].min()) > 0
            ok, detail = quadratic(h)
            print("(d) %s increment %d (%s): %d Newton iterations; residuals %s" % (
                name, inc["step"], "plastic" if plastic else "elastic", inc["newton"], " ".join("%.3e" % r for r in h)))
            print("      %s" % detail)
            if plastic and ok is not None:
                checked += 1
                chk.check(ok, "(d) %s increment %d: quadratic convergence at the end (%s)" % (name, inc["step"], detail))
        chk.check(checked >= 3, "(d) %s: %d plastic increments checked" % (name, checked))


def main_test(etfe, chk):
    with T.scratch_dir("plasticity") as tmp:
        out_a = part_a(etfe, chk, tmp)
        out_b = part_b(etfe, chk, tmp)
        out_c = part_c(etfe, chk, tmp)
        part_d(etfe, chk, tmp)
    print("\nNewton iterations per increment:")
    for name, out in [("(a) uniaxial load/unload/reload, 60 increments", out_a)] + \
            [("(b) %s, 10 increments" % k, v) for k, v in out_b.items()] + \
            [("(c) cycle %s, 10 increments" % k, v) for k, v in out_c.items()]:
        incs = T.increments(out)
        print("  %s: %s (total %d)" % (name, " ".join(str(i["newton"]) for i in incs), sum(i["newton"] for i in incs)))


if __name__ == "__main__":
    T.main(main_test)
