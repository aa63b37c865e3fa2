#!/usr/bin/python3
"""Hencky scene (options/hencky.opts, 24 rings) on 1 and 2 MPI ranks: the final displacements
must agree to 1e-10 relative (h5compare), every other field of the final step to 1e-8, and the
scene's printed numbers to their printed precision (one unit in the last printed digit)."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

# Fields of the final step other than the displacement: rtol 1e-8 of the field's largest value
# (the reactions of a 2-rank run sum element contributions in a different order).
OTHER_RTOL, OTHER_ATOL = 1e-8, 1e-12


def main_test(etfe, chk):
    with T.scratch_dir("par-hencky") as tmp:
        res = {}
        for np_ in (1, 2):
            h5 = os.path.join(tmp, "hencky_np%d.h5" % np_)
            rc, out = T.run(etfe, ["-options_file", T.opts("hencky"), "-output_file", h5], np=np_)
            ranks = T.lines.header(out).get("ranks")
            chk.check(ranks == np_, "run reports %s rank(s), expected %d" % (ranks, np_))
            chk.check(T.status(h5) == "complete", "np=%d: results status 'complete'" % np_)
            res[np_] = (h5, out)
            s = T.summary(out)
            print("np=%d: %d increments, %d Newton iterations, %.2f s wall" % (np_, s["increments"], s["newton"], T.run.last_wall))
        (h1, o1), (h2, o2) = res[1], res[2]
        f, rows = T.h5compare.compare_rows(h2, h1, step="last", fields={"displacement": (1e-10, 0.0)}, only=True)
        print(T.h5compare.format_table(rows))
        chk.check(not f and rows, "final displacement np=2 vs np=1 within 1e-10 relative%s" % ("" if not f else ": " + "; ".join(f)))
        f, rows = T.h5compare.compare_rows(h2, h1, step="all", default_rtol=OTHER_RTOL, default_atol=OTHER_ATOL)
        worst = max(rows, key=lambda r: r["max_rel"] if r["max_rel"] == r["max_rel"] else 1e300)
        print("all steps, all fields: worst relative difference %.3e (%s, step %s)" % (worst["max_rel"], worst["field"], worst["step"]))
        chk.check(not f, "every field of every written step np=2 vs np=1 within rtol 1e-8%s" % ("" if not f else ": " + "; ".join(f)))
        v1, v2 = T.scene_values(o1, "hencky", printed=True), T.scene_values(o2, "hencky", printed=True)
        chk.check(set(v1) == set(v2) and v1, "same hencky lines printed (%s)" % sorted(v1))
        for tag in v1:
            for key, a in v1[tag].items():
                b = v2.get(tag, {}).get(key)
                chk.check(b is not None and T.printed_agree(a, b),
                          "hencky %s.%s: np=1 %s, np=2 %s" % (tag, key, a, b))


if __name__ == "__main__":
    T.main(main_test)
