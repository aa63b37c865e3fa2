"""Cutting patterns of the form-found saddle (docs/theory.md §9): the middle and corner strips are
flattened and written as DXF, SVG and Gmsh; with the thesis's weights (boundary 1e12) the
boundary and cutting lines keep their 3D length; with uniform weights the doubly curved strips
come out shorter in 2D along the weld line over the arch, by more as the rise grows; compensated
for the form-finding stress, the isotropic middle part shrinks by the closed form."""
import os

from etfe_testlib import Checker, cutpattern_report, etfe_path, run, scratch_dir, REPO

etfe = etfe_path()
chk = Checker("formfind_cutpattern")


def lines(out):
    return {(k, name): v for k, r in cutpattern_report(out).items() for name, v in r["lines"].items()}


with scratch_dir() as tmp:
    msh = os.path.join(tmp, "s31.msh")
    rc, out = run(etfe, ["-options_file", os.path.join(REPO, "options/saddle/ff_r15_s31.opts"), "-formfind_monitor", 0,
                         "-output", 0, "-formfind_mesh_out", msh, "-cutpattern", "-cutpattern_lines", "frame"])
    got = lines(out)
    for strip in ("middle", "corner"):
        for ext in ("dxf", "svg", "msh"):
            p = os.path.join(tmp, "s31_%s.%s" % (strip, ext))
            chk.check(os.path.exists(p) and os.path.getsize(p) > 100, "strip %s: %s written" % (strip, ext))
    chk.check(os.path.exists(os.path.join(tmp, "s31_lines.csv")), "line table written")
    with open(os.path.join(tmp, "s31_middle.dxf")) as f:
        dxf = f.read()
    chk.check("ENTITIES" in dxf and dxf.rstrip().endswith("EOF"), "DXF has an ENTITIES section and ends with EOF")
    with open(os.path.join(tmp, "s31_middle.msh")) as f:
        txt = f.read()
    chk.check("$Nodes" in txt and "$Elements" in txt, "the 2D strip mesh is a Gmsh file")
    for key in (("middle", "cut_middle"), ("middle", "weld_arch"), ("corner", "weld_arch"), ("middle", "frame")):
        chk.check(key in got and abs(got[key][2]) < 1e-6, "boundary weight 1e12: %s/%s keeps its length (%s %%)"
                  % (key + (got.get(key, (0, 0, float("nan")))[2],)))
    weld = {}
    for r in (10, 15, 20):
        rc, out = run(etfe, ["-options_file", os.path.join(REPO, "options/saddle/ff_r%d_s11.opts" % r),
                             "-formfind_monitor", 0, "-output", 0, "-formfind_mesh_out", os.path.join(tmp, "r%d.msh" % r),
                             "-cutpattern", "-cutpattern_boundary_weight", 1])
        weld[r] = lines(out)[("middle", "weld_arch")][2]
        print("r = %d %%, middle weld line over the arch: expansion %.4f %%" % (r, weld[r]))
    chk.check(weld[10] < 0 and weld[15] < 0 and weld[20] < 0, "uniform weights: the weld line is shorter in 2D")
    chk.check(weld[10] > weld[15] > weld[20], "and more so as the rise grows")
    # Stress compensation from the form-finding stress: the middle part carries 1 MPa
    # isotropically, so every one of its lines is cut 1/sqrt(1 + 2 (1 - nu) S / E) of its length
    # (elastic defaults E = 800 MPa, nu = 0.43); the corner part's 3:1 stress shrinks MD lines more.
    rc, out = run(etfe, ["-options_file", os.path.join(REPO, "options/saddle/ff_r15_s11.opts"), "-formfind_monitor", 0,
                         "-output", 0, "-formfind_mesh_out", os.path.join(tmp, "c11.msh"), "-cutpattern",
                         "-cutpattern_lines", "frame", "-cutpattern_compensation", "stress"])
    with open(os.path.join(tmp, "c11_lines.csv")) as f:
        rows = [l.strip().split(",") for l in f if l.strip()]
    rows = [dict(zip(rows[0], r)) for r in rows[1:]]
    want = (1.0 / (1.0 + 2 * (1 - 0.43) * 1.0 / 800.0) ** 0.5 - 1) * 100
    mid = [float(r["compensation_pct"]) for r in rows if r["strip"] == "middle"]
    print("stress compensation, middle part (1 MPa isotropic): %s %% per line, closed form %.6f %%" % (mid, want))
    chk.check(len(mid) == 4 and all(abs(c - want) < 1e-4 * abs(want) for c in mid),
              "middle part: every line compensated by the closed form %.6f %%" % want)
    corner = {r["line"]: float(r["compensation_pct"]) for r in rows if r["strip"] == "corner"}
    print("corner part (MD:TD = 3:1): %s" % corner)
    chk.check(corner.get("frame", 0) < want < 0 < corner.get("weld_arch", -1),
              "corner part: the frame line shrinks more, the weld line (across the 3 MPa) grows (Poisson)")
chk.finish()
