"""Surfaces from elsewhere into -analysis cutpattern: scripts/surface2msh turns OBJ
groups and STL solids into physical surfaces (STL's repeated vertices merged, so neighbouring
facets share edges), and the strips flatten as the same mesh written directly does: the same
link errors and the cutting line between the two strips."""
import os
import struct
import subprocess

import pattern_meshes as pm
from etfe_testlib import Checker, cutpattern_report, etfe_path, run, scratch_dir, REPO

etfe = etfe_path()
chk = Checker("formfind_pattern_import")
conv = os.path.join(REPO, "scripts", "surface2msh")


def errors(out):
    return {k: r["link_max"] for k, r in cutpattern_report(out, printed=True).items() if "link_max" in r}


def cutpattern(tmp, name, msh):
    return run(etfe, ["-analysis", "cutpattern", "-mesh_file", msh, "-output_file", os.path.join(tmp, name + ".h5")])[1]


with scratch_dir() as tmp:
    nodes, tris, _ = pm.hypar()
    half = len(tris) // 2
    direct = os.path.join(tmp, "direct.msh")
    pm.write_msh(direct, nodes, tris, {"left": (2, list(range(half))), "right": (2, list(range(half, len(tris))))})
    want = errors(cutpattern(tmp, "direct", direct))
    # OBJ: two groups, quads split as fans are not needed here (triangles).
    obj = os.path.join(tmp, "h.obj")
    with open(obj, "w") as f:
        f.write("# hypar\n")
        for p in nodes:
            f.write("v %r %r %r\n" % p)
        for k, t in enumerate(tris):
            if k in (0, half):
                f.write("g %s\n" % ("left" if k == 0 else "right"))
            f.write("f %d/1 %d %d\n" % tuple(i + 1 for i in t))
    # ASCII STL with two solids, binary STL of the left half (one unnamed strip).
    stl = os.path.join(tmp, "h.stl")
    with open(stl, "w") as f:
        for name, part in (("left", tris[:half]), ("right", tris[half:])):
            f.write("solid %s\n" % name)
            for t in part:
                f.write(" facet normal 0 0 1\n  outer loop\n")
                for i in t:
                    f.write("   vertex %.17g %.17g %.17g\n" % nodes[i])
                f.write("  endloop\n endfacet\n")
            f.write("endsolid %s\n" % name)
    bstl = os.path.join(tmp, "b.stl")
    with open(bstl, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", half))
        for t in tris[:half]:
            f.write(struct.pack("<12fH", 0, 0, 1, *[c for i in t for c in nodes[i]], 0))
    for name, src in (("obj", obj), ("stl", stl), ("bstl", bstl)):
        msh = os.path.join(tmp, name + ".msh")
        p = subprocess.run([conv, src, msh, "--strip", "left"], capture_output=True, text=True)
        print(p.stdout.strip() + p.stderr.strip())
        chk.check(p.returncode == 0, "%s converted" % name)
        got = errors(cutpattern(tmp, name, msh))
        print("%s: strips %s, direct %s" % (name, got, want))
        if name == "bstl":
            chk.check(set(got) == {"left"}, "binary STL: one strip (named by --strip)")
        else:
            chk.check(got == want, "%s: the strips flatten as the mesh written directly (max link errors %s)"
                      % (name, got))
            with open(os.path.join(tmp, name + "_lines.csv")) as f:
                chk.check(sum(1 for l in f if ",cut_left_right," in l) == 2, "%s: the cutting line between the strips"
                          % name)
    p = subprocess.run([conv, os.path.join(tmp, "h.ply"), os.path.join(tmp, "x.msh")], capture_output=True, text=True)
    chk.check(p.returncode != 0 and "give an .obj or .stl" in p.stderr, "other formats refused with the way out")
chk.finish()
