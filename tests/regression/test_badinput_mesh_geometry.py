#!/usr/bin/python3
"""Mesh files whose geometry, not their syntax, is wrong, each refused at read with a message that
points to the real problem:
  * a strip folded back through itself: the two crossing triangles by their file tags, a point of
    the crossing and the way out (-mesh_check_intersections false, which lets it through);
  * a two-layer cushion whose foils are both oriented up (an even split of orientations over the
    closed surface they form): refused as an even split naming the groups, not "repaired" by
    turning one foil inside out; a cushion of 3:1 foils is still repaired, the note naming the group;
  * garbage CAD files (random bytes as .igs/.step/.brep, text renamed .step/.brep, an IGES-like
    line without the section letter): refused naming the file, what was expected and what was found.
A real IGES file (OpenCASCADE's sample hammer.iges, if installed) is meshed, not refused with
Gmsh's "Could not set OpenCASCADE target unit". A lens cushion with the foils oriented out of it, and the same flat (foils on each other, two
groups), pass the read."""
import os
import random
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402
import pattern_meshes as PM  # noqa: E402

PATCH = os.path.join("options", "patch.opts")
HAMMER = "/usr/share/opencascade/data/iges/hammer.iges"
BEARING = "/usr/share/opencascade/data/iges/bearing.iges"


def folded_strip(nx=10, width=200.0):
    """A strip along x (0..1000 mm), then folded back at x = 1000 into a part that rises and comes
    down through the first part near x = 400 (no node on the crossing line)."""
    nodes, tris = [], []
    for i in range(nx + 1):
        for y in (0.0, width):
            nodes.append((100.0 * i, y, 0.0))
    for k in range(1, nx + 1):  # s = 80 k back from the fold line
        s = 80.0 * k
        for y in (0.0, width):
            nodes.append((1000.0 - s, y, 0.4 * s * (1.0 - s / 600.0)))

    def col(i):  # the two nodes of column i: 0..nx the first part, nx+1.. the folded part
        if i <= nx:
            return 2 * i, 2 * i + 1
        b = 2 * (nx + 1) + 2 * (i - nx - 1)
        return b, b + 1
    for i in range(2 * nx):
        a, b = col(i)
        c, d = col(i + 1)
        tris += [(a, c, d), (a, d, b)] if i < nx else [(a, d, c), (a, b, d)]
    return nodes, tris


def cushion(n=6, span=1000.0, rise=50.0, bottom_up=False):
    """Two square foils sharing the rim nodes, the top lifted and the bottom lowered by `rise` in
    the middle; the top's normals point up, the bottom's down (out of the cushion) unless
    bottom_up. rise 0: both flat on each other."""
    nodes, idx = [], {}

    def cell(i, j, a, b, c, d):  # the other diagonal at two corners: no triangle of rim nodes only
        return [(a, b, d), (b, c, d)] if (i, j) in ((n - 1, 0), (0, n - 1)) else [(a, b, c), (a, c, d)]
    h = span / n
    for j in range(n + 1):
        for i in range(n + 1):
            idx[(i, j)] = len(nodes)
            u, v = i / n, j / n
            nodes.append((h * i, h * j, 16 * rise * u * (1 - u) * v * (1 - v)))
    top = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = idx[(i, j)], idx[(i + 1, j)], idx[(i + 1, j + 1)], idx[(i, j + 1)]
            top += cell(i, j, a, b, c, d)
    bot_ids = {}
    for (i, j), k in idx.items():
        rim = i in (0, n) or j in (0, n)
        if rim:
            bot_ids[(i, j)] = k
        else:
            x, y, z = nodes[k]
            bot_ids[(i, j)] = len(nodes)
            nodes.append((x, y, -z))
    bottom = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = bot_ids[(i, j)], bot_ids[(i + 1, j)], bot_ids[(i + 1, j + 1)], bot_ids[(i, j + 1)]
            pair = cell(i, j, a, b, c, d)
            bottom += pair if bottom_up else [(t[0], t[2], t[1]) for t in pair]
    tris = top + bottom
    groups = {"top": (2, list(range(len(top)))), "bottom": (2, list(range(len(top), len(tris))))}
    return nodes, tris, groups


def run_read(etfe, path, tmp, extra=()):
    h5 = os.path.join(tmp, os.path.basename(path) + ".h5")
    return T.run(etfe, ["-options_file", PATCH, "-mesh_file", path, "-output_file", h5, "-load_monitor", "0"] +
                 list(extra), expect_fail=None, timeout=60)


def refused(chk, name, rc, out, path, *parts):
    msg = T.error_message(out) if rc != 0 else ""
    ok = chk.check(rc != 0, "%s: refused (exit %d)" % (name, rc))
    ok = chk.check(path in msg, "%s: the message names the file" % name) and ok
    for p in parts:
        ok = chk.check(p in msg, "%s: the message says %r" % (name, p)) and ok
    if not ok:
        print("    output tail:\n" + T.tail(out, 6))


def main_test(etfe, chk):
    with T.scratch_dir("badmesh_geometry") as tmp:
        # A strip folded through itself.
        p = os.path.join(tmp, "folded_strip.msh")
        nodes, tris = folded_strip()
        PM.write_msh(p, nodes, tris, {"film": (2, list(range(len(tris))))})
        rc, out = run_read(etfe, p, tmp)
        refused(chk, "folded strip", rc, out, p, "cross each other at", "(tag ", "-mesh_check_intersections false")
        rc, out = run_read(etfe, p, tmp, ["-mesh_check_intersections", "false"])
        chk.check("cross each other" not in out, "folded strip, -mesh_check_intersections false: not refused for it")

        # Two foils both facing up: an even split, refused naming the groups.
        p = os.path.join(tmp, "cushion_both_up.msh")
        nodes, tris, groups = cushion(bottom_up=True)
        PM.write_msh(p, nodes, tris, groups)
        rc, out = run_read(etfe, p, tmp)
        refused(chk, "foils both up", rc, out, p, "split evenly", "72 triangles oriented like that one",
                "are all of group top", "72 the other way",
                "are all of group bottom", "Reverse Surface")
        # Foils oriented out of the cushion: read, nothing flipped (the patch scene then wants its
        # edge groups: a refusal of the scene, after the read). Flat on each other in two groups:
        # not refused as overlapping (the coincident-node check refuses their separate nodes).
        p = os.path.join(tmp, "cushion_lens.msh")
        nodes, tris, groups = cushion()
        PM.write_msh(p, nodes, tris, groups)
        rc, out = run_read(etfe, p, tmp)
        chk.check("patch scene needs a physical group" in out and "flipped" not in out,
                  "lens: passes the read, nothing flipped (%s)" % T.error_message(out)[:160])
        p = os.path.join(tmp, "cushion_flat.msh")
        nodes, tris, groups = cushion(rise=0.0)
        PM.write_msh(p, nodes, tris, groups)
        rc, out = run_read(etfe, p, tmp)
        chk.check("coincide" in out and "coplanar, in one group" not in out,
                  "flat foils in two groups: not refused as overlapping (%s)" % T.error_message(out)[:160])

        # Garbage CAD files.
        rnd = random.Random(7)
        junk = bytes(rnd.randrange(256) for _ in range(3000))
        text = b"hello, this is a text file renamed\n"
        cases = [("random.igs", junk, "expected an IGES file", "binary data"),
                 ("random.step", junk, "expected a STEP file", "binary data"),
                 ("random.brep", junk, "expected an OpenCASCADE BREP file", "binary data"),
                 ("text.step", text, "starts with \"ISO-10303-21;\"", "hello, this is a text file"),
                 ("text.brep", text, "\"DBRep_DrawableShape\"", "hello, this is a text file"),
                 ("short.iges", b"A" * 60 + b"\n", "section letter S, G, D, P or T in column 73",
                  "a first line of 60 characters")]
        for name, data, expected, found in cases:
            p = os.path.join(tmp, name)
            with open(p, "wb") as f:
                f.write(data)
            rc, out = run_read(etfe, p, tmp)
            if "no Gmsh API" in out:
                chk.check(rc != 0, "%s: refused by a build without the Gmsh API" % name)
                continue
            refused(chk, name, rc, out, p, expected, found)
            chk.check("target unit" not in out, "%s: not Gmsh's words about a target unit" % name)

        # A real IGES file (OpenCASCADE's sample, when installed): Gmsh 4.8 refused every IGES file
        # with "Could not set OpenCASCADE target unit". Now it is meshed, and then refused by the
        # mesh checks for what the model is, a solid, not a film (its faces cross at 200 and 827 mm,
        # its shells meet at 400 mm with opposite orientations): a message naming its elements.
        if os.path.exists(HAMMER) and "no Gmsh API" not in out:
            rc, out = run_read(etfe, HAMMER, tmp, ["-mesh_cad_size", "400"])
            chk.check("target unit" not in out and "(tag " in T.error_message(out),
                      "hammer.iges: meshed, then refused naming its elements (%s)" % T.error_message(out)[:200])
        # bearing.iges makes Gmsh 4.8 throw inside its OpenMP face meshing, beyond any catch: the
        # process still ends with the file named and the way out, not a bare abort.
        if os.path.exists(BEARING) and "no Gmsh API" not in out:
            rc, out = run_read(etfe, BEARING, tmp)
            chk.check(rc == 2 and "bearing.iges" in out and "gmsh -2" in out and "Signal: Aborted" not in out,
                      "bearing.iges: ends with exit 2 naming the file and the way out (exit %d)%s"
                      % (rc, "" if rc == 2 else ": " + T.tail(out)))


if __name__ == "__main__":
    T.main(main_test)
