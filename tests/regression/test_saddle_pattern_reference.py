"""-saddle_reference pattern: DD1511 whose stress-free state is the flat cutting pattern
of its strips, laid on during the first drawing step (40 increments, thesis density).

* the flat strips keep their outline length (the thesis's 1e12 boundary weight): 2D = 3D;
* at load time 0 the film is unstrained (the blend starts at the surface), and the laid-on film
  ends strained differently from the surface start (the pattern's misfit is loaded);
* an element's strain invariants at the end of the lay-on step follow from its flat triangle
  (read from the pattern's own .msh files) and its current 3D triangle;
* a restart in the middle of the lay-on step equals the uninterrupted run bit for bit;
* 2 ranks agree with 1 (each rank flattens the same strips);
* the PD start's middle strip (a cylinder) flattens exactly: the plane strip of the experiments.
"""
import os
import re

import h5py
import numpy as np

from etfe_testlib import Checker, etfe_path, form_found_saddle, run, scene_values, scratch_dir, summary, REPO
import h5compare

etfe = etfe_path()
chk = Checker("saddle_pattern_reference")


def read_msh_2d(path):
    """Nodes (id -> xy) and triangles (node ids) of a Gmsh 4.1 ASCII file."""
    lines = open(path).read().split("\n")
    nodes, tris = {}, []
    i = lines.index("$Nodes") + 1
    nblocks = int(lines[i].split()[0])
    i += 1
    for _ in range(nblocks):
        n = int(lines[i].split()[3])
        ids = [int(x) for x in lines[i + 1:i + 1 + n]]
        for k, nid in enumerate(ids):
            nodes[nid] = [float(x) for x in lines[i + 1 + n + k].split()[:2]]
        i += 1 + 2 * n
    i = lines.index("$Elements") + 1
    nblocks = int(lines[i].split()[0])
    i += 1
    for _ in range(nblocks):
        etype, n = int(lines[i].split()[2]), int(lines[i].split()[3])
        for k in range(n):
            if etype == 2:
                tris.append([int(x) for x in lines[i + 1 + k].split()[1:4]])
        i += 1 + n
    return nodes, tris


def invariants(ref2d, cur3d):
    """trace and determinant of the Green-Lagrange strain of a triangle from its reference (3x2)
    and current (3x3) corners."""
    Dr = np.array([ref2d[1] - ref2d[0], ref2d[2] - ref2d[0]]).T
    Dc = np.array([cur3d[1] - cur3d[0], cur3d[2] - cur3d[0]]).T
    F = Dc @ np.linalg.inv(Dr)
    E = 0.5 * (F.T @ F - np.eye(2))
    return np.trace(E), np.linalg.det(E)


with scratch_dir() as tmp:
    msh = form_found_saddle(etfe, tmp)
    base = ["-options_file", os.path.join(REPO, "options/saddle/dd1511.opts"), "-mesh_file", msh,
            "-load_increments", 40, "-load_monitor", 0, "-output_every", 1]

    def case(extra, name, np=1):
        out_file = os.path.join(tmp, name + ".h5")
        rc, out = run(etfe, base + extra + ["-output_file", out_file], np=np)
        return out, out_file

    out_s, f_surface = case([], "surface")
    out_p, f_pattern = case(["-saddle_reference", "pattern"], "pattern")
    s = summary(out_p)
    print("pattern reference: Newton %d in %.2f s (surface start: %d)" % (s["newton"], s["wall"],
                                                                         summary(out_s)["newton"]))
    outlines = re.findall(r"reference = flat pattern of strip (\w+) \(\d+ elements, outline 3D (\S+) mm, 2D (\S+) mm",
                          out_p)
    chk.check(len(outlines) == 2, "both strips flattened (middle, corner)")
    for name, l3, l2 in outlines:
        chk.check(abs(float(l2) - float(l3)) <= 1e-6 * float(l3), "strip %s keeps its outline length: 3D %s, 2D %s mm"
                  % (name, l3, l2))
    with h5py.File(f_pattern, "r") as fp, h5py.File(f_surface, "r") as fs:
        steps = sorted(fp["steps"].keys())
        e0 = np.abs(fp["steps"][steps[0]]["strain"][:]).max()
        chk.check(fp["steps"][steps[0]].attrs["time"] == 0.0 and e0 < 1e-14, "unstrained at load time 0 (max |E| %g)" % e0)
        last = steps[-1]
        d = np.abs(fp["steps"][last]["strain"][:] - fs["steps"][last]["strain"][:]).max()
        chk.check(d > 1e-3, "the laid-on film ends strained unlike the surface start (max strain difference %.2e)" % d)
        # End of the lay-on step: the first step at load time 1.
        k1 = [k for k in steps if abs(fp["steps"][k].attrs["time"] - 1.0) < 1e-12][0]
        X = fp["mesh/coordinates"][:]
        tri = fp["mesh/triangles"][:]
        x = X + fp["steps"][k1]["displacement"][:]
        E1 = fp["steps"][k1]["strain"][:]

    # The pattern's own strips (-cutpattern writes them as 2D meshes, element order = the set's).
    rc, out_c = run(etfe, ["-options_file", os.path.join(REPO, "options/saddle/ff_r15_s11_n19.opts"),
                           "-formfind_monitor", 0, "-cutpattern", "-output_file", os.path.join(tmp, "ffc.h5"),
                           "-formfind_mesh_out", os.path.join(tmp, "ffc.msh")])
    checked, worst = 0, 0.0
    # The saddle's strips: middle X < 1000 (the arch), corner beyond; a set lists its elements in
    # ascending order, and the pattern's triangles follow the set.
    cx = X[tri][:, :, 0].mean(axis=1)
    sets = {"middle": np.nonzero(cx < 1000.0)[0], "corner": np.nonzero(cx > 1000.0)[0]}
    for strip in ("middle", "corner"):
        path = os.path.join(tmp, "ffc_%s.msh" % strip)
        if not os.path.exists(path):
            chk.check(False, "the cutting pattern wrote %s" % path)
            continue
        nodes, tris2d = read_msh_2d(path)
        for k, e in enumerate(sets[strip]):
            ref = np.array([nodes[n] for n in tris2d[k]])
            tr, det = invariants(ref, x[tri[e]])
            exx, eyy, exy = E1[e]
            worst = max(worst, abs(tr - (exx + eyy)) / 1e-2, abs(det - (exx * eyy - exy * exy)) / 1e-4)
            checked += 1
    chk.check(checked == len(tri) and worst < 1e-6,
              "strain invariants of all %d elements at the end of the lay-on step follow from the flat pattern "
              "(worst mismatch %.1e of 1e-2 / 1e-4)" % (checked, worst))

    # Restart in the middle of the lay-on step (increment 5 of 10).
    part, ck = os.path.join(tmp, "part.h5"), os.path.join(tmp, "ck.h5")
    extra = ["-saddle_reference", "pattern", "-output_file", part]
    rc, out1 = run(etfe, base + extra + ["-load_stop_after", 5, "-checkpoint_file", ck])
    rc, out2 = run(etfe, base + extra + ["-restart", ck])
    fails = h5compare.compare(f_pattern, part, step="all", default_rtol=0.0, default_atol=0.0)
    chk.check(not fails, "restart in the lay-on step equals the uninterrupted run bit for bit%s" %
              ("" if not fails else ": %s" % fails[:2]))

    out2r, f2 = case(["-saddle_reference", "pattern"], "pattern_np2", np=2)
    fails = h5compare.compare(f_pattern, f2, step="last", default_rtol=1e-9, default_atol=1e-12, family_scale=True)
    chk.check(not fails, "2 ranks agree with 1 (1e-9 of each field family)%s" % ("" if not fails else ": %s" % fails[:2]))

    # The PD start: its middle strip is the arch extruded (a cylinder), developable, so its pattern
    # is the plane strip of the experiments, exact to round-off.
    rc, out = run(etfe, ["-options_file", os.path.join(REPO, "options/saddle/pd15a.opts"), "-saddle_reference",
                         "pattern", "-output", 0, "-load_increments", 40, "-load_stop_after", 2, "-checkpoint_file",
                         os.path.join(tmp, "pd_ck.h5")])
    m = re.search(r"flat pattern of strip middle .*largest link error (\S+)\)", out)
    chk.check(m and float(m.group(1)) < 1e-10 and "stopped as asked" in out,
              "PD15a: the cylindrical middle strip flattens exactly (link error %s) and the run proceeds"
              % (m.group(1) if m else "?"))
chk.finish()
