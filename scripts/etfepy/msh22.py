"""One writer of ASCII Gmsh MSH 2.2 files for the meshes made by script (meshes/*.py,
scripts/cushion-mesh, scripts/surface2msh) and by the regression tests (tests/regression/
cable_meshes.py, group_meshes.py, pattern_meshes.py, balloon_mesh.py), and the structured grid of
triangles several of them cut (grid_triangles()).

write_elements() writes the sections as given; write() names one physical group a name, tags
1, 2, ... in the order points, lines, surfaces (each in its dict's order), and writes the
elements in that same order, so a mesh writes the same bytes as long as its groups are given in
the same order.
"""


def grid_triangles(nx, ny):
    """The squares of an nx x ny grid (node j (nx + 1) + i at column i, row j), row by row, each cut
    into two counterclockwise triangles, the diagonals alternating (no preferred shear direction)."""
    idx = lambda i, j: j * (nx + 1) + i  # noqa: E731
    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            tris += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    return tris


GMSH_TYPE = {0: 15, 1: 1, 2: 2}  # a group's dimension -> Gmsh element type: point, 2-node line, triangle


def write_elements(path, nodes, names, elements):
    """nodes: [(x, y, z), ...]; names: [(dim, tag, name), ...] ($PhysicalNames, left out when
    empty); elements: [(gmsh type, physical tag, elementary tag, (node, ...)), ...]. Nodes are
    0-based indices (the file's node tags are index + 1); coordinates are written with 17
    significant digits, so they read back exactly."""
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        if names:
            f.write("$PhysicalNames\n%d\n" % len(names))
            for dim, tag, name in names:
                f.write('%d %d "%s"\n' % (dim, tag, name))
            f.write("$EndPhysicalNames\n")
        f.write("$Nodes\n%d\n" % len(nodes))
        for k, p in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (k + 1, p[0], p[1], p[2]))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elements))
        for k, (etype, phys, geom, vs) in enumerate(elements):
            f.write("%d %d 2 %d %d %s\n" % (k + 1, etype, phys, geom, " ".join("%d" % (v + 1) for v in vs)))
        f.write("$EndElements\n")


def write(path, nodes, points=None, lines=None, surfaces=None):
    """points {name: [node, ...]} (point elements), lines {name: [(a, b), ...]} (2-node lines),
    surfaces {name: [(a, b, c), ...]} (3-node triangles), all 0-based node indices."""
    groups = [(0, points or {}), (1, lines or {}), (2, surfaces or {})]
    names = [(dim, name) for dim, g in groups for name in g]
    tag = {name: k + 1 for k, (_, name) in enumerate(names)}
    elements = [(GMSH_TYPE[dim], tag[name], tag[name], e if dim else (e,))
                for dim, g in groups for name, es in g.items() for e in es]
    write_elements(path, nodes, [(dim, tag[name], name) for dim, name in names], elements)
