"""Flat meshes (MSH 2.2) for the tests of per-group film properties and per-support friction.

halves(path, L, W, nx, ny, split): the rectangle [0, L] x [0, W] on an nx x ny grid of squares,
each cut into two triangles; split "x" makes the surface groups "left" (x < L/2) and "right",
split "y" the groups "bottom" (y < W/2) and "top" (nx, ny even). Node groups: "x0" (x = 0),
"x1" (x = L) and "all" (every node). Node tags are the node indices + 1.
"""


def halves(path, L, W, nx, ny, split):
    idx = lambda i, j: j * (nx + 1) + i  # noqa: E731
    nodes = [(L * i / nx, W * j / ny, 0.0) for j in range(ny + 1) for i in range(nx + 1)]
    groups = ("left", "right") if split == "x" else ("bottom", "top")
    tris = {g: [] for g in groups}
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            first = (i < nx // 2) if split == "x" else (j < ny // 2)
            tris[groups[0] if first else groups[1]] += [(a, b, c), (a, c, d)]
    points = {"x0": [idx(0, j) for j in range(ny + 1)], "x1": [idx(nx, j) for j in range(ny + 1)],
              "all": list(range(len(nodes)))}
    names = list(points) + list(groups)
    tag = {n: k + 1 for k, n in enumerate(names)}
    elems = []
    for n, ps in points.items():
        elems += ["15 2 %d %d %d" % (tag[n], tag[n], p + 1) for p in ps]
    for g in groups:
        elems += ["2 2 %d %d %d %d %d" % (tag[g], tag[g], a + 1, b + 1, c + 1) for a, b, c in tris[g]]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(names))
        for n in names:
            f.write('%d %d "%s"\n' % (0 if n in points else 2, tag[n], n))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % len(nodes))
        for k, (x, y, z) in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (k + 1, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elems))
        for k, e in enumerate(elems):
            f.write("%d %s\n" % (k + 1, e))
        f.write("$EndElements\n")


def two_sheets(path, L, W, nx, ny, gap):
    """Two flat sheets L x W side by side in one mesh, a gap apart in x: surface groups "sheet_a"
    ([0, L] x [0, W]) and "sheet_b" (from x = L + gap); node groups "a_nodes", "b_nodes" (each
    sheet's nodes) and "a_right", "b_right" (each sheet's edge at its largest x)."""
    nodes, tris, groups = [], {"sheet_a": [], "sheet_b": []}, {}
    for s, x0 in (("a", 0.0), ("b", L + gap)):
        base = len(nodes)
        idx = lambda i, j: base + j * (nx + 1) + i  # noqa: E731
        nodes += [(x0 + L * i / nx, W * j / ny, 0.0) for j in range(ny + 1) for i in range(nx + 1)]
        for j in range(ny):
            for i in range(nx):
                a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
                tris["sheet_" + s] += [(a, b, c), (a, c, d)]
        groups[s + "_nodes"] = list(range(base, len(nodes)))
        groups[s + "_right"] = [idx(nx, j) for j in range(ny + 1)]
    names = list(groups) + list(tris)
    tag = {n: k + 1 for k, n in enumerate(names)}
    elems = []
    for n, ps in groups.items():
        elems += ["15 2 %d %d %d" % (tag[n], tag[n], p + 1) for p in ps]
    for g, ts in tris.items():
        elems += ["2 2 %d %d %d %d %d" % (tag[g], tag[g], a + 1, b + 1, c + 1) for a, b, c in ts]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(names))
        for n in names:
            f.write('%d %d "%s"\n' % (0 if n in groups else 2, tag[n], n))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % len(nodes))
        for k, (x, y, z) in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (k + 1, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elems))
        for k, e in enumerate(elems):
            f.write("%d %s\n" % (k + 1, e))
        f.write("$EndElements\n")
