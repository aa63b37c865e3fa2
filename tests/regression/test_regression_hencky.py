#!/usr/bin/python3
"""Hencky's clamped circular membrane (options/hencky.opts) at -mesh_rings 8, 16, 32 against the
closed form: centre deflection and centre stress errors, printed as a table (docs/verification.md).

Asserted: deflection error < 2% at 16 and 32 rings, < 0.5% at 32 rings, and decreasing from 8 to
16 to 32 rings; centre stress error < 1% at every resolution and < 0.5% at 16 and 32 rings.

Why the stress error is not asserted to decrease (measured, 5 increments, nu = 0.3):
    rings           4        8        16       24       32       48       64
    deflection   +0.99%   +0.32%   +0.13%   +0.092%  +0.077%  +0.067%  +0.063%
    centre S     -3.5%    -0.81%   -0.036%  +0.12%   +0.18%   +0.22%   +0.24%
The FE model is the full large-rotation membrane while the closed form is Foppl's moderate-
rotation theory (w0/a ~ 0.05 here), so both errors tend to a model-error floor of a few 1e-4
(deflection ~ +0.06%, centre stress ~ +0.25%) instead of zero. The scene's centre stress is the
mean over the elements touching the centre node, which sits below the true centre value by a
discretisation error that shrinks with the mesh; the two effects have opposite signs, so the
signed stress error crosses zero between 16 and 24 rings and |error| is smallest at 16 rings
(8.1e-3, 3.6e-4, 1.8e-3 at 8, 16, 32 rings). What does hold, and is asserted, is that the
signed stress error increases monotonically with the mesh (discretisation error shrinking towards
the model floor) and stays within 0.5% from 16 rings on.
"""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

RINGS = (8, 16, 32)


def main_test(etfe, chk):
    rows = []
    with T.scratch_dir("hencky") as tmp:
        for n in RINGS:
            h5 = os.path.join(tmp, "hencky_%d.h5" % n)
            rc, out = T.run(etfe, ["-options_file", T.opts("hencky"), "-mesh_rings", n,
                                   "-output_file", h5, "-load_monitor", "0"])
            wall = T.run.last_wall
            v = T.scene_values(out, "hencky")
            for tag in ("centre_deflection", "centre_stress"):
                if tag not in v or "relative_error" not in v[tag]:
                    raise T.TestFailure("no `hencky: %s = ... relative_error = ...` line:\n%s" % (tag, T.tail(out)))
            tri = T.lines.header(out).get("triangles", -1)
            w, w_ref = v["centre_deflection"]["centre_deflection"], v["centre_deflection"]["closed_form"]
            s, s_ref = v["centre_stress"]["centre_stress"], v["centre_stress"]["closed_form"]
            rows.append(dict(rings=n, tri=tri, w=w, w_ref=w_ref, ew=v["centre_deflection"]["relative_error"],
                             sw=(w - w_ref) / w_ref, s=s, s_ref=s_ref,
                             es=v["centre_stress"]["relative_error"], ss=(s - s_ref) / s_ref,
                             newton=T.summary(out)["newton"], wall=wall))
            chk.check(T.status(h5) == "complete", "%d rings: results status 'complete'" % n)
            chk.check(rows[-1]["tri"] == 6 * n * n, "%d rings: %d triangles (6 rings^2)" % (n, rows[-1]["tri"]))

    print("\n| rings | triangles | w0 FE [mm] | w0 error | centre S FE [MPa] | S error | Newton its | wall [s] |")
    print("|------:|----------:|-----------:|---------:|------------------:|--------:|-----------:|---------:|")
    for r in rows:
        print("| %5d | %9d | %10.4f | %8.2e | %17.4f | %7.2e | %10d | %8.2f |" % (
            r["rings"], r["tri"], r["w"], r["ew"], r["s"], r["es"], r["newton"], r["wall"]))
    print("closed form: w0 = %.4f mm, centre S = %.4f MPa; signed errors: deflection %s, stress %s\n" % (
        rows[0]["w_ref"], rows[0]["s_ref"], ", ".join("%+.2e" % r["sw"] for r in rows),
        ", ".join("%+.2e" % r["ss"] for r in rows)))

    by = {r["rings"]: r for r in rows}
    chk.less(by[16]["ew"], 0.02, "deflection relative error at 16 rings")
    chk.less(by[32]["ew"], 0.02, "deflection relative error at 32 rings")
    chk.less(by[32]["ew"], 0.005, "deflection relative error at 32 rings")
    chk.check(by[8]["ew"] > by[16]["ew"] > by[32]["ew"],
              "deflection error decreases 8 -> 16 -> 32 rings (%.3e > %.3e > %.3e)"
              % (by[8]["ew"], by[16]["ew"], by[32]["ew"]))
    for n in RINGS:
        chk.less(by[n]["es"], 0.01, "centre stress relative error at %d rings" % n)
    chk.less(by[16]["es"], 0.005, "centre stress relative error at 16 rings")
    chk.less(by[32]["es"], 0.005, "centre stress relative error at 32 rings")
    chk.check(by[8]["ss"] < by[16]["ss"] < by[32]["ss"],
              "signed centre stress error increases with the mesh (%+.3e < %+.3e < %+.3e)"
              % (by[8]["ss"], by[16]["ss"], by[32]["ss"]))


if __name__ == "__main__":
    T.main(main_test)
