"""A law per surface group (-film_<group>_material_*) in the general scene.

A flat rectangle 200 x 100 mm, 0.2 mm thick, in two halves of different elastic constants, held at
x = 0, its y and z displacements held everywhere (so each half is in a homogeneous state of
E_yy = 0: S_xx = E' E_xx with E' = E / (1 - nu^2) and E_xx = (lambda^2 - 1) / 2), and pulled at
x = L by d = 2 mm:
* in series (halves left | right along the pull): both carry the same nominal stress
  P = lambda_i E'_i E_xx,i and their elongations add up to d; the pull F = P W h;
* in parallel (halves bottom / top): both have the stretch lambda = 1 + d / L and
  F = (W / 2) h lambda E_xx (E'_1 + E'_2);
the reaction at x = L against these closed forms (solved to round-off here), within 1e-6. A group's
law equal to the film's changes no history value. Each option falls back to the film's: only the
right half's Young's modulus given, its Poisson's ratio is the film's.
A plastic half beside an elastic one, pulled past yield in two stages: only the plastic half yields,
and a restart from the end of the first stage equals the uninterrupted run bit for bit; 2 ranks
agree with 1. The
viscoelastic-plastic law (relaxing in a 1 h hold) given to the group "all" equals it given to the
film in every history value; on the left half only, a restart in the hold is bit for bit.
Refused by name: a group the mesh does not have, a negative modulus, an unknown law, mismatched
hardening arrays, two groups giving one element a law each, a closed-form check (-structure_check)
and a group's law in form finding.
"""
import os
import re

from etfe_testlib import Checker, etfe_path, read_history, run, scratch_dir
import group_meshes
import h5compare

etfe = etfe_path()
chk = Checker("structure_group_materials")
L, W, H, D = 200.0, 100.0, 0.2, 2.0
E1, NU1, E2, NU2 = 800.0, 0.43, 1600.0, 0.3


def stretch(msh, tmp, name, args, expect_fail=False, extra_stages=None, np=1):
    hist = os.path.join(tmp, name + ".csv")
    rc, out = run(etfe, ["-scene", "structure", "-mesh_file", msh, "-membrane_thickness", H, "-material_young", E1,
                         "-material_poisson", NU1, "-bc_x0_fix", "x", "-bc_all_fix", "yz", "-bc_x1_ux",
                         extra_stages or D, "-load_increments", 4, "-load_monitor", 0, "-output_file",
                         os.path.join(tmp, name + ".h5"), "-structure_history", hist] + list(args),
                  expect_fail=expect_fail, np=np)
    return out, (read_history(hist) if rc == 0 and os.path.exists(hist) else [])


def nominal(e_plane, lam):
    return lam * e_plane * 0.5 * (lam * lam - 1.0)


def series_force(ea, eb):
    # Bisection on the left half's stretch: the right half's from equal nominal stress, until the
    # elongations add up to D.
    def right(p):
        lo, hi = 1.0, 2.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if nominal(eb, mid) < p else (lo, mid)
        return 0.5 * (lo + hi)
    lo, hi = 1.0, 1.0 + D / (L / 2)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        total = L / 2 * (mid - 1.0) + L / 2 * (right(nominal(ea, mid)) - 1.0)
        lo, hi = (mid, hi) if total < D else (lo, mid)
    return nominal(ea, 0.5 * (lo + hi)) * W * H


ep1, ep2 = E1 / (1 - NU1 ** 2), E2 / (1 - NU2 ** 2)
with scratch_dir() as tmp:
    series, parallel = os.path.join(tmp, "series.msh"), os.path.join(tmp, "parallel.msh")
    group_meshes.halves(series, L, W, 8, 4, "x")
    group_meshes.halves(parallel, L, W, 8, 4, "y")
    right = ["-film_right_material_young", E2, "-film_right_material_poisson", NU2]

    out, h = stretch(series, tmp, "series", right)
    f, expect = float(h[-1]["x1_RX"]), series_force(ep1, ep2)
    chk.check("surface group right (-film_right_material_*)" in out and "E = 1600" in out,
              "series: the header shows the right half's own law")
    chk.less(abs(f - expect) / expect, 1e-6, "series: pull %.6f N against the closed form %.6f N (E' %.1f | %.1f "
                                             "MPa), relative difference" % (f, expect, ep1, ep2))

    _, h = stretch(parallel, tmp, "parallel", ["-film_top_material_young", E2, "-film_top_material_poisson", NU2])
    lam = 1.0 + D / L
    f, expect = float(h[-1]["x1_RX"]), (W / 2) * H * lam * 0.5 * (lam * lam - 1.0) * (ep1 + ep2)
    chk.less(abs(f - expect) / expect, 1e-6, "parallel: pull %.6f N against the closed form %.6f N, relative "
                                             "difference" % (f, expect))

    # Each option falls back to the film's: the right half's modulus alone, its Poisson's ratio the film's.
    _, h = stretch(series, tmp, "series_young", ["-film_right_material_young", E2])
    f, expect = float(h[-1]["x1_RX"]), series_force(ep1, E2 / (1 - NU1 ** 2))
    chk.less(abs(f - expect) / expect, 1e-6, "series, right half's -film_right_material_young only (its nu the "
                                             "film's %.2f): pull %.6f N against %.6f N, relative difference"
                                             % (NU1, f, expect))

    _, h0 = stretch(series, tmp, "plain", [])
    _, hs = stretch(series, tmp, "same", ["-film_left_material_type", "elastic", "-film_left_material_young", E1])
    chk.check(h0 and hs == h0, "a law of the left half's own equal to the film's changes no history value (%d rows)"
              % len(h0))

    # A plastic half beside an elastic one, past yield; a restart from the end of stage 1.
    mixed = ["-film_left_material_type", "plastic", "-structure_stages", 2]
    _, hm = stretch(series, tmp, "mixed", mixed, extra_stages="3,6")
    last = hm[-1] if hm else {}
    chk.check(hm and float(last["left_ep_max"]) > 1e-3 and float(last["right_ep_max"]) == 0.0,
              "plastic left half beside the elastic right: the left yields (largest plastic strain %s), the right "
              "does not (%s)" % (last.get("left_ep_max"), last.get("right_ep_max")))
    _, h2 = stretch(series, tmp, "mixed_np2", mixed, extra_stages="3,6", np=2)
    worst = max((abs(float(a[k]) - float(b[k])) / max(abs(float(a[k])), 1.0) for a, b in zip(hm, h2)
                 for k in ("x1_RX", "left_ep_max", "left_mises", "right_mises")), default=1.0)
    chk.check(len(h2) == len(hm) and worst < 1e-10, "plastic | elastic halves on 2 ranks agree with 1 (largest "
                                                    "difference %.1e in the pull, plastic strain and Mises)" % worst)
    ck, part = os.path.join(tmp, "mixed_ck.h5"), os.path.join(tmp, "mixed_part.h5")
    common = ["-scene", "structure", "-mesh_file", series, "-membrane_thickness", H, "-material_young", E1,
              "-material_poisson", NU1, "-bc_x0_fix", "x", "-bc_all_fix", "yz", "-bc_x1_ux", "3,6",
              "-load_increments", 4, "-load_monitor", 0, "-output_file", part, "-structure_history",
              os.path.join(tmp, "mixed_part.csv")] + mixed
    run(etfe, common + ["-load_stop_after", 2, "-checkpoint_file", ck])
    run(etfe, common + ["-restart", ck])
    fails = h5compare.compare(os.path.join(tmp, "mixed.h5"), part, step="all", default_rtol=0.0, default_atol=0.0)
    chk.check(not fails, "plastic | elastic halves: stopped at the end of stage 1 and restarted, the results equal "
                         "the uninterrupted run bit for bit%s" % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))
    hp = read_history(os.path.join(tmp, "mixed_part.csv"))
    chk.check(hp == hm, "plastic | elastic halves: the restarted history CSV equals the uninterrupted one (%d rows "
                        "against %d)" % (len(hp), len(hm)))

    # A law with time: the viscoelastic-plastic law given to the surface group "all" (the whole film)
    # equals the same law given to the film, every increment's time step reaching the group's law;
    # with it on the left half only, a restart in the hold equals the uninterrupted run bit for bit.
    visco = ["-material_type", "viscoelastic_plastic", "-material_prony_tau", "10,1000",
             "-material_prony_g", "0.3,0.2"]
    timed = ["-load_stage_duration", 10, "-load_hold_after", 1, "-load_hold_duration", 3600,
             "-load_increments", 8]
    _, hf = stretch(series, tmp, "visco_film", visco + timed)
    _, hg = stretch(series, tmp, "visco_group", [a.replace("-material_", "-film_all_material_", 1) if
                                                 str(a).startswith("-material_") else a for a in visco] + timed)
    chk.check(hf and hg == hf and float(hf[-1]["x1_RX"]) < float(hf[len(hf) // 2 - 1]["x1_RX"]),
              "viscoelastic-plastic law of the group all = the film's law, every history value (%d rows; the "
              "pull relaxes from %s to %s N in the hold)" % (len(hf), hf[len(hf) // 2 - 1]["x1_RX"] if hf else "?",
                                                          hf[-1]["x1_RX"] if hf else "?"))
    left_visco = [a.replace("-material_", "-film_left_material_", 1) if str(a).startswith("-material_") else a
                  for a in visco]
    _, hv = stretch(series, tmp, "visco_left", left_visco + timed)
    ckv, partv = os.path.join(tmp, "visco_ck.h5"), os.path.join(tmp, "visco_part.h5")
    commonv = ["-scene", "structure", "-mesh_file", series, "-membrane_thickness", H, "-material_young", E1,
               "-material_poisson", NU1, "-bc_x0_fix", "x", "-bc_all_fix", "yz", "-bc_x1_ux", D, "-load_monitor", 0,
               "-output_file", partv, "-structure_history", os.path.join(tmp, "visco_part.csv")] + left_visco + timed
    run(etfe, commonv + ["-load_stop_after", 6, "-checkpoint_file", ckv])
    run(etfe, commonv + ["-restart", ckv])
    fails = h5compare.compare(os.path.join(tmp, "visco_left.h5"), partv, step="all", default_rtol=0.0,
                              default_atol=0.0)
    hpv = read_history(os.path.join(tmp, "visco_part.csv"))
    chk.check(hv and not fails and hpv == hv, "viscoelastic left | elastic right halves: stopped in the hold and "
                                              "restarted, results and history equal the uninterrupted run bit for bit%s"
              % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))

    # Refusals by name, before the run.
    refusals = [
        (["-film_roof_material_young", 900], r"-film_roof_material_young: no such group.*left, right"),
        (["-film_right_material_young", -5], r"-film_right_material_young -5\.?: Young's modulus must be positive"),
        (["-film_right_material_type", "rubber"], r"-film_right_material_type rubber is unknown"),
        (["-film_right_material_type", "plastic", "-film_right_material_yield", "13,20,25"],
         r"-film_right_material_yield has 3 values but -film_right_material_hardening has 2"),
        (["-film_all_material_young", 900, "-film_right_material_young", 1600],
         r"surface groups all and right, which both give it a law of their own"),
        (["-structure_check", "patch", "-film_right_material_young", 1600],
         r"-structure_check patch compares against a closed form for a film of one law; drop -film_right_material_\*"),
    ]
    for args, pattern in refusals:
        out, _ = stretch(series, tmp, "refused", args, expect_fail=True)
        chk.check(re.search(pattern, out, re.S) is not None, "refused: %s -> /%s/" % (" ".join(map(str, args)), pattern))
    rc, out = run(etfe, ["-scene", "structure", "-mesh_file", series, "-analysis", "formfind", "-bc_all_fix", "xyz", "-film_right_material_young", E2, "-output", 0], expect_fail=True)
    chk.check("-film_right_material_*: form finding prescribes the stress" in out,
              "refused: a group's own law in form finding")
chk.finish()
