#!/usr/bin/python3
"""Patch scene on 1, 2 and 3 MPI ranks (3 with --oversubscribe on a 2-core machine), a 16 x 8
irregular mesh: an elastic uniaxial stretch and a plastic biaxial load/unload (history in
parallel). Final displacements agree with the 1-rank run to 1e-10 relative (h5compare), every
field of every written step to 1e-8 (absolute floor 1e-9 for round-off fields), and the scene
lines agree: the same numbers where they are data, and below 1e-9 where they are round-off
(stress_spread, relative_error, Syy/Sxy of a uniaxial stretch)."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

MESH = ["-mesh_nx", "16", "-mesh_ny", "8"]
CASES = {
    "elastic_uniaxial": [],
    "plastic_biaxial": ["-material_type", "plastic", "-patch_mode", "biaxial", "-patch_strain_x", "0.04",
                        "-patch_strain_y", "0.02", "-patch_schedule", "1,0.5", "-load_increments", "8"],
}
RANKS = (1, 2, 3)
# Printed numbers that are round-off (compared only against a bound), by (tag, key).
NOISE = {("stress_spread", "stress_spread"), ("closed_form", "relative_error")}


def main_test(etfe, chk):
    with T.scratch_dir("par-patch") as tmp:
        for case, extra in CASES.items():
            res = {}
            for np_ in RANKS:
                h5 = os.path.join(tmp, "%s_np%d.h5" % (case, np_))
                rc, out = T.run(etfe, ["-options_file", T.opts("patch"), "-output_file", h5, "-load_monitor", "0"]
                                + MESH + extra, np=np_, oversubscribe=np_ > (os.cpu_count() or 1))
                ranks = T.lines.header(out).get("ranks")
                chk.check(ranks == np_, "%s: run reports %s rank(s), expected %d" % (case, ranks, np_))
                chk.check(T.status(h5) == "complete", "%s np=%d: results status 'complete'" % (case, np_))
                res[np_] = (h5, out)
                print("%s np=%d: %d Newton iterations, %.2f s wall" % (case, np_, T.summary(out)["newton"], T.run.last_wall))
            h1, o1 = res[1]
            v1 = T.scene_values(o1, "patch", printed=True)
            for np_ in RANKS[1:]:
                h, o = res[np_]
                f, rows = T.h5compare.compare_rows(h, h1, step="last", fields={"displacement": (1e-10, 0.0)}, only=True)
                chk.check(not f and rows, "%s: final displacement np=%d vs np=1 within 1e-10 relative (%.3e)%s"
                          % (case, np_, rows[0]["max_rel"] if rows else float("nan"), "" if not f else ": " + "; ".join(f)))
                f, rows = T.h5compare.compare_rows(h, h1, step="all", default_rtol=1e-8, default_atol=1e-9)
                chk.check(not f, "%s: all fields, all steps np=%d vs np=1 within rtol 1e-8%s" % (case, np_, "" if not f else ": " + "; ".join(f)))
                v = T.scene_values(o, "patch", printed=True)
                chk.check(set(v) == set(v1) and "stress_spread" in v, "%s np=%d: same patch lines (%s)" % (case, np_, sorted(v)))
                for tag in v1:
                    for key, a in v1[tag].items():
                        b = v.get(tag, {}).get(key)
                        if b is None:
                            chk.check(False, "%s np=%d: %s.%s not printed" % (case, np_, tag, key))
                        elif (tag, key) in NOISE:
                            chk.check(float(a) < 1e-9 and float(b) < 1e-9, "%s %s.%s round-off: np=1 %s, np=%d %s (< 1e-9)" % (case, tag, key, a, np_, b))
                        else:
                            chk.check(T.printed_agree(a, b), "%s %s.%s: np=1 %s, np=%d %s" % (case, tag, key, a, np_, b))
                # The `Sxx in [lo, hi], Syy in [...], Sxy in [...]` line: Sxx is data, Syy/Sxy round-off
                # in uniaxial tension.
                r1, r = ranges(o1), ranges(o)
                for comp in ("Sxx", "Syy", "Sxy"):
                    for a, b in zip(r1[comp], r[comp]):
                        scale = max(abs(float(x)) for x in r1["Sxx"])
                        chk.check(abs(float(a) - float(b)) <= 1e-9 * scale or T.printed_agree(a, b),
                                  "%s %s range: np=1 %s, np=%d %s" % (case, comp, a, np_, b))


def ranges(out):
    r = T.lines.patch_ranges(out, printed=True)
    if r is None:
        raise T.TestFailure("no `patch: Sxx in [...]` line:\n" + T.tail(out))
    return r


if __name__ == "__main__":
    T.main(main_test)
