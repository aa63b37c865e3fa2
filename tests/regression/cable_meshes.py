"""Small Gmsh (MSH 2.2) meshes for the cable tests: a film whose edges carry 1-D groups.

strip(): a strip of film one element wide, x in [0, L], y in [0, W]; the row y = 0 is the 1-D
group "cable" (n segments), the row y = W the 1-D group "far", the first and last node of the
cable the point groups "anchor" and "end". square(): a flat film [0, L]^2 on an n x n grid, its
edges the 1-D groups "south" (y = 0), "north", "west" (x = 0) and "east". Node tags are the
node indices + 1; the film is the surface group "film".
"""


def _write(path, nodes, tris, lines, points):
    """lines: {name: [(a, b), ...]}, points: {name: [node, ...]} (0-based node indices)."""
    names = list(points) + list(lines) + ["film"]
    dims = {n: 0 for n in points}
    dims.update({n: 1 for n in lines})
    dims["film"] = 2
    tag = {n: i + 1 for i, n in enumerate(names)}
    elems = []
    for n, ps in points.items():
        elems += ["15 2 %d %d %d" % (tag[n], tag[n], p + 1) for p in ps]
    for n, ls in lines.items():
        elems += ["1 2 %d %d %d %d" % (tag[n], tag[n], a + 1, b + 1) for a, b in ls]
    elems += ["2 2 %d %d %d %d %d" % (tag["film"], tag["film"], a + 1, b + 1, c + 1) for a, b, c in tris]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(names))
        for n in names:
            f.write('%d %d "%s"\n' % (dims[n], tag[n], n))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % len(nodes))
        for i, (x, y, z) in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elems))
        for i, e in enumerate(elems):
            f.write("%d %s\n" % (i + 1, e))
        f.write("$EndElements\n")


def strip(path, L, W, n, points=None, lines=None, z=None):
    """points / lines: further point groups {name: [node, ...]} and 1-D groups {name: [(a, b), ...]};
    z: the height of each of the n + 1 columns (both rows; default flat)."""
    h = z or [0.0] * (n + 1)
    nodes = [(L * i / n, 0.0, h[i]) for i in range(n + 1)] + [(L * i / n, W, h[i]) for i in range(n + 1)]
    tris = []
    for i in range(n):
        a, b, c, d = i, i + 1, n + 2 + i, n + 1 + i
        tris += [(a, b, c), (a, c, d)]
    groups = {"cable": [(i, i + 1) for i in range(n)], "far": [(n + 1 + i, n + 2 + i) for i in range(n)]}
    groups.update(lines or {})
    pts = {"anchor": [0], "end": [n]}
    pts.update(points or {})
    _write(path, nodes, tris, groups, pts)
    return nodes


def square(path, L, n):
    idx = lambda i, j: j * (n + 1) + i  # noqa: E731
    nodes = [(L * i / n, L * j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
    tris = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            tris += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    lines = {"south": [(idx(i, 0), idx(i + 1, 0)) for i in range(n)],
             "north": [(idx(i, n), idx(i + 1, n)) for i in range(n)],
             "west": [(idx(0, j), idx(0, j + 1)) for j in range(n)],
             "east": [(idx(n, j), idx(n, j + 1)) for j in range(n)]}
    _write(path, nodes, tris, lines, {})
    return nodes
