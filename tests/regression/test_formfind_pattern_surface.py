"""Cutting patterns of any surface mesh: -analysis cutpattern -mesh_file flattens the
physical surfaces of a Gmsh file, with no scene and no form finding. Meshes are made here
(pattern_meshes.py), so the test needs no Gmsh.
  * developable strips (cylinder, cone) keep every link length to 1e-10;
  * a sphere strip's largest link error falls as the strip narrows (the rate is printed);
  * surfaces no scene makes (a four-triangle pyramid, a hypar) flatten with their errors printed;
  * two strips sharing an edge get the cutting line cut_a_b, of one length in both patterns;
  * no physical groups, a tube, a strip touching itself at a node, a non-manifold edge, a
    compressive prestress: refused with a message saying so;
  * compensation: uniform factors shrink MD/TD lengths to 1/(1 + c); a flat strip compensated
    for a uniaxial prestress S and stretched back to its design length by the patch scene
    carries S in every element to 1e-6."""
import math
import os

import pattern_meshes as pm
from etfe_testlib import Checker, cutpattern_report, etfe_path, patch_ranges, run, scratch_dir, REPO

etfe = etfe_path()
chk = Checker("formfind_pattern_surface")


def flatten(tmp, name, mesh, groups=None, extra=(), expect_fail=False):
    nodes, tris, sides = mesh
    if groups is None:
        groups = {name: (2, list(range(len(tris))))}
    path = os.path.join(tmp, name + ".msh")
    pm.write_msh(path, nodes, tris, groups)
    return run(etfe, ["-analysis", "cutpattern", "-mesh_file", path, "-output_file", os.path.join(tmp, name + ".h5")]
               + list(extra), expect_fail=expect_fail)[1]


def strips(out):
    """{strip: (max link error, rms link error)} and {strip: outline expansion %}."""
    rep = cutpattern_report(out)
    err = {k: (r["link_max"], r["link_rms"]) for k, r in rep.items() if "link_max" in r}
    outl = {k: r["outline"][2] for k, r in rep.items() if "outline" in r}
    return err, outl


def line_rows(csv_path):
    with open(csv_path) as f:
        rows = [l.strip().split(",") for l in f if l.strip()]
    head = rows[0]
    return [dict(zip(head, r)) for r in rows[1:]]


with scratch_dir() as tmp:
    # Developable strips: every link keeps its length (both strips of one mesh, one run).
    nodes, tris, groups = pm.combine([("cylinder", pm.cylinder_strip(), (0, 0, 0)),
                                      ("cone", pm.cone_strip(), (0, 0, 3000))])
    err, outl = strips(flatten(tmp, "developable", (nodes, tris, {}), groups))
    for name in ("cylinder", "cone"):
        e = err.get(name, (float("nan"),))[0]
        print("%s strip: max link error %.3e" % (name, e))
        chk.check(e < 1e-10, "%s (developable): every link keeps its length, max error %.3e < 1e-10" % (name, e))
        for ext in ("dxf", "svg", "msh"):
            p = os.path.join(tmp, "developable_%s.%s" % (name, ext))
            chk.check(os.path.exists(p) and os.path.getsize(p) > 100, "%s: the %s pattern is written" % (name, ext))
    # A doubly curved strip: the error falls as it narrows.
    widths = (400, 200, 100, 50)
    nodes, tris, groups = pm.combine([("sphere%d" % w, pm.sphere_strip(width=w), (0, 0, 3000 * k))
                                      for k, w in enumerate(widths)])
    err = strips(flatten(tmp, "sphere", (nodes, tris, {}), groups))[0]
    errs = {w: err["sphere%d" % w][0] for w in widths}
    print("sphere strip R 1000 mm, 1000 mm long, 16 x 8 cells: width -> max link error, rate")
    ws = sorted(errs, reverse=True)
    for a, b in zip(ws, ws[1:]):
        rate = math.log(errs[a] / errs[b]) / math.log(a / b)
        print("  %4d mm %.3e -> %4d mm %.3e: rate %.2f" % (a, errs[a], b, errs[b], rate))
    chk.check(all(errs[a] > errs[b] for a, b in zip(ws, ws[1:])), "sphere strip: the error falls as it narrows")
    last = math.log(errs[100] / errs[50]) / math.log(2)
    chk.check(1.7 < last < 2.3, "sphere strip: error ~ width^2 when narrow (rate %.2f)" % last)
    # Non-developable surfaces no scene makes.
    nodes, tris, groups = pm.combine([("pyramid", pm.pyramid(), (0, 0, 0)), ("hypar", pm.hypar(), (0, 0, 3000))])
    err, outl = strips(flatten(tmp, "odd", (nodes, tris, {}), groups))
    for name in ("pyramid", "hypar"):
        e = err.get(name, (float("nan"), float("nan")))
        print("%s: max link error %.3e, rms %.3e, outline expansion %.2e %%" % (name, e[0], e[1], outl.get(name)))
        chk.check(1e-3 < e[0] < 0.2, "%s: not developable, so its links stretch or shrink (max %.3e)" % (name, e[0]))
        chk.check(abs(outl.get(name, 1)) < 1e-6, "%s: the outline keeps its length (boundary weight 1e12)" % name)
    # Two strips sharing an edge: the cutting line between them.
    nodes, tris, _ = pm.cylinder_strip()
    half = len(tris) // 2
    out = flatten(tmp, "two", (nodes, tris, {}), {"a": (2, list(range(half))), "b": (2, list(range(half, len(tris))))})
    rows = [r for r in line_rows(os.path.join(tmp, "two_lines.csv")) if r["line"] == "cut_a_b"]
    chk.check(len(rows) == 2 and rows[0]["length3d_mm"] == rows[1]["length3d_mm"] and
              all(abs(float(r["expansion_pct"])) < 1e-8 for r in rows),
              "two strips: cut_a_b measured in both, same 3D length, 2D = 3D: %s" % rows)
    # Bad input.
    cyl = pm.cylinder_strip()
    for name, mesh, groups, want in (
            ("nogroups", cyl, {}, "no physical surface groups"),
            ("tube", pm.tube(), None, "is not a disc but 2 boundary loops"),
            ("bowtie", pm.bowtie(), None, "touches itself at node"),
            ("fin", pm.t_junction(), None, "non-manifold")):
        out = flatten(tmp, name, mesh, groups, expect_fail=True)
        chk.check(want in out, "%s: refused with \"%s\"" % (name, want))
    nodes, tris, groups = pm.combine([("ring", pm.tube(), (0, 0, 0)), ("flat", pm.hypar(), (0, 0, 3000))])
    out = flatten(tmp, "mixed", (nodes, tris, {}), groups, ["-cutpattern_strips", "flat"])
    chk.check("flat" in strips(out)[0] and "ring" not in strips(out)[0],
              "-cutpattern_strips: only the chosen strips must be discs (the tube beside them is left alone)")
    out = flatten(tmp, "compressed", pm.pyramid(), None, ["-cutpattern_compensation", "stress",
                                                          "-cutpattern_prestress", "2,-1"], expect_fail=True)
    chk.check("a film carries no compression" in out, "a compressive prestress is refused")
    # Compensation of a flat strip 1000 x 200 mm.
    nodes, tris, sides = pm.grid(10, 4, lambda u, v: (1000.0 * u, 200.0 * v, 0.0))
    groups = {"film": (2, list(range(len(tris))))}
    groups.update({k: (1, v) for k, v in sides.items()})
    lines = ["-cutpattern_lines", "left,right,top,bottom"]
    flatten(tmp, "uniform", (nodes, tris, sides), groups, lines + [
        "-cutpattern_compensation", "uniform", "-cutpattern_compensation_md", 0.01, "-cutpattern_compensation_td", 0.005])
    got = {r["line"]: float(r["length2d_mm"]) for r in line_rows(os.path.join(tmp, "uniform_lines.csv"))}
    chk.check(abs(got["top"] - 1000 / 1.01) < 1e-4 and abs(got["left"] - 200 / 1.005) < 1e-4,
              "uniform 1 %% / 0.5 %%: MD %.4f mm (1000/1.01), TD %.4f mm (200/1.005)" % (got["top"], got["left"]))
    S, young, nu = 5.0, 800.0, 0.43
    mat = ["-material_type", "elastic", "-material_young", young, "-material_poisson", nu]
    flatten(tmp, "stress", (nodes, tris, sides), groups, lines + mat + [
        "-cutpattern_compensation", "stress", "-cutpattern_prestress", "%g,0" % S])
    rows = {r["line"]: r for r in line_rows(os.path.join(tmp, "stress_lines.csv"))}
    print("stress compensation, S = %g MPa uniaxial: MD line %s mm (uncompensated %s, %s %%), TD line %s mm" % (
        S, rows["top"]["length2d_mm"], rows["top"]["length2d_uncompensated_mm"], rows["top"]["compensation_pct"],
        rows["left"]["length2d_mm"]))
    pattern = os.path.join(tmp, "stress_film.msh")
    pts = pm.msh41_point_groups(pattern)
    if min(p[0] for p in pts["left"]) > max(p[0] for p in pts["right"]):
        pm.msh41_turn_half(pattern, pattern)  # the pattern came out turned: left on the right
        pts = pm.msh41_point_groups(pattern)
    xs = [p[0] for p in pts["film"]]
    lx = max(xs) - min(xs)
    out = run(etfe, ["-options_file", os.path.join(REPO, "options/patch.opts"), "-mesh_file", pattern,
                     "-patch_strain_x", "%.17g" % (1000.0 / lx - 1.0), "-output", 0, "-mesh_perturb", 0] + mat)[1]
    r = patch_ranges(out)
    chk.check(r is not None, "patch run on the compensated pattern reports its stress")
    if r:
        (lo, hi), (ylo, yhi) = r["Sxx"], r["Syy"]
        rel = max(abs(lo - S), abs(hi - S)) / S
        print("compensated strip (%.6f mm long) stretched back to 1000 mm: Sxx in [%.10f, %.10f] MPa, "
              "relative error %.2e; Syy within %.1e MPa" % (lx, lo, hi, rel, max(abs(ylo), abs(yhi))))
        chk.check(rel < 1e-6, "stretched back, every element carries S = %g MPa to 1e-6 (%.2e)" % (S, rel))
        chk.check(max(abs(ylo), abs(yhi)) < 1e-6 * S, "and no lateral stress")
chk.finish()
