"""Bad mesh files for the solver's mesh input (-mesh_file), one per defect the reader and the mesh
check must catch: cases(tmpdir) writes them into tmpdir and returns a list of
(name, extra_argv, expected_substring, expected_exit_zero). extra_argv is what follows
build/etfe (run from the repository root); expected_substring must appear in the run's output;
expected_exit_zero says whether the run must succeed (a repaired mesh) or be refused.

Used by tests/regression/test_badinput_mesh.py and by the fault campaign (scripts/study-faults).
Every mesh is the 1000 x 1000 mm square of the patch scene on a 2 x 2 grid of cells (nodes 1..9,
tag 1 + i + 3 j at (500 i, 500 j)), with the physical groups the patch scene needs.
"""
import os

PATCH_OPTS = os.path.join("options", "patch.opts")


def grid_nodes(size=1000.0):
    """Tag -> (x, y, z) of the 3 x 3 nodes of a square of the given size."""
    h = size / 2
    return {1 + i + 3 * j: (h * i, h * j, 0.0) for j in range(3) for i in range(3)}


def grid_triangles():
    """The 8 counter-clockwise triangles of the 2 x 2 cells: (a, b, c) and (a, c, d) per cell."""
    tris = []
    for j in range(2):
        for i in range(2):
            a, b = 1 + i + 3 * j, 2 + i + 3 * j
            c, d = b + 3, a + 3
            tris += [(a, b, c), (a, c, d)]
    return tris


EDGES = {"bottom": [(1, 2), (2, 3)], "right": [(3, 6), (6, 9)], "top": [(9, 8), (8, 7)],
         "left": [(7, 4), (4, 1)]}


def write_msh(path, nodes, triangles, quads=(), others=()):
    """An ASCII MSH 4.1 file: the nodes on one surface entity, boundary lines on four curves
    (physical groups bottom/right/top/left), the triangles (type 2) and quadrangles (type 3) on the
    surface (physical group film), and others = [(type, (node tags...)), ...] on the surface too."""
    groups = ["bottom", "right", "top", "left"]
    s = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "5"]
    s += ['1 %d "%s"' % (k + 1, g) for k, g in enumerate(groups)] + ['2 5 "film"', "$EndPhysicalNames"]
    s += ["$Entities", "0 4 1 0"]
    s += ["%d 0 0 0 1000 1000 0 1 %d 0" % (k + 1, k + 1) for k in range(4)]
    s += ["1 0 0 0 1000 1000 0 1 5 0", "$EndEntities"]
    tags = sorted(nodes)
    s += ["$Nodes", "1 %d %d %d" % (len(tags), tags[0], tags[-1]), "2 1 0 %d" % len(tags)]
    s += [str(t) for t in tags] + ["%r %r %r" % nodes[t] for t in tags] + ["$EndNodes"]
    blocks = [(1, k + 1, 1, EDGES[g]) for k, g in enumerate(groups)]
    blocks += [(2, 1, 2, list(triangles))]
    if quads:
        blocks.append((2, 1, 3, list(quads)))
    for etype, conn in others:
        blocks.append((2, 1, etype, [conn]))
    nel = sum(len(b[3]) for b in blocks)
    s += ["$Elements", "%d %d 1 %d" % (len(blocks), nel, nel)]
    tag = 1
    for dim, entity, etype, els in blocks:
        s.append("%d %d %d %d" % (dim, entity, etype, len(els)))
        for e in els:
            s.append(" ".join(str(v) for v in (tag,) + tuple(e)))
            tag += 1
    s.append("$EndElements")
    with open(path, "w") as f:
        f.write("\n".join(s) + "\n")


def _mesh(tmpdir, name):
    return os.path.join(tmpdir, name + ".msh")


def cases(tmpdir):
    """Writes the bad meshes into tmpdir; returns [(name, extra_argv, expected_substring,
    expected_exit_zero), ...]."""
    out = []

    def add(name, path, expect, ok):
        out.append((name, ["-options_file", PATCH_OPTS, "-mesh_file", path], expect, ok))

    nodes, tris = grid_nodes(), grid_triangles()

    # A crack: node 10 sits on node 5, and the right column of cells uses it instead of node 5.
    p = _mesh(tmpdir, "duplicate_nodes")
    n = dict(nodes)
    n[10] = nodes[5]
    right = [tuple(10 if v == 5 else v for v in t) if t[0] in (2, 5) else t for t in tris]
    write_msh(p, n, right)
    add("duplicate nodes (crack)", p, "coincide (at 500, 500, 0", False)

    p = _mesh(tmpdir, "duplicate_triangle")
    write_msh(p, nodes, tris + [tris[3]])
    add("duplicated triangle", p, "are the same triangle", False)

    # A fin: a third triangle on the edge 2-5 (shared by two grid triangles already).
    p = _mesh(tmpdir, "nonmanifold_edge")
    n = dict(nodes)
    n[10] = (250.0, 250.0, 300.0)
    write_msh(p, n, tris + [(2, 5, 10)])
    add("non-manifold edge", p, "belongs to three or more triangles (3: ", False)

    # Three of the eight triangles run clockwise: repaired (flipped back) and reported.
    p = _mesh(tmpdir, "mixed_orientation")
    mixed = [(t[0], t[2], t[1]) if k in (1, 4, 6) else t for k, t in enumerate(tris)]
    write_msh(p, nodes, mixed)
    add("mixed orientation (repaired)", p, "flipped 3 of 8 triangles", True)

    # The left column as two quadrangles, the right column as four triangles.
    p = _mesh(tmpdir, "quads_and_triangles")
    write_msh(p, nodes, [t for t in tris if t[0] in (2, 5)], quads=[(1, 2, 5, 4), (4, 5, 8, 7)])
    add("quadrangles with triangles (split)", p, "split 2 quadrangles", True)

    p = _mesh(tmpdir, "tetrahedron")
    n = dict(nodes)
    n[10] = (250.0, 250.0, 300.0)
    write_msh(p, n, tris, others=[(4, (1, 2, 5, 10))])
    add("tetrahedron among triangles", p, "is of type 4 (4-node tetrahedron)", False)

    add("/dev/zero", "/dev/zero", "not a regular file", False)

    p = os.path.join(tmpdir, "fifo.msh")
    if os.path.exists(p):
        os.remove(p)
    os.mkfifo(p)
    add("FIFO", p, "not a regular file (a FIFO)", False)

    # The header claims 10^12 nodes; the file holds a few hundred bytes.
    p = _mesh(tmpdir, "huge_count")
    with open(p, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1000000000000 1 1000000000000\n"
                "2 1 0 1000000000000\n" + "1\n" * 100)
    add("header claiming 10^12 nodes", p, "bytes of the file can hold", False)

    # A valid file cut before its $EndElements line.
    p = _mesh(tmpdir, "truncated")
    write_msh(p, nodes, tris)
    with open(p) as f:
        text = f.read()
    cut = text.index("$EndElements")
    with open(p, "w") as f:
        f.write(text[:cut])
    add("truncated file", p, "unexpected end of file", False)
    return out

