"""One writer of ASCII Gmsh MSH 2.2 files for the meshes made by script (meshes/*.py) and by the
regression tests (tests/regression/cable_meshes.py, group_meshes.py): the nodes, then one physical
group a name, each name's elements tagged with its group.

Physical tags are 1, 2, ... in the order points, lines, surfaces (each in its dict's order), and the
elements stand in that same order, so a mesh writes the same bytes as long as its groups are given
in the same order.
"""


def write(path, nodes, points=None, lines=None, surfaces=None):
    """nodes: [(x, y, z), ...]; points {name: [node, ...]} (point elements), lines {name: [(a, b), ...]}
    (2-node lines), surfaces {name: [(a, b, c), ...]} (3-node triangles), all 0-based node indices
    (the file's node tags are index + 1). Coordinates are written with 17 significant digits, so
    they read back exactly."""
    groups = [(0, 15, points or {}), (1, 1, lines or {}), (2, 2, surfaces or {})]
    names = [(dim, name) for dim, _, g in groups for name in g]
    tag = {name: k + 1 for k, (_, name) in enumerate(names)}
    elems = ["%d 2 %d %d %s" % (etype, tag[name], tag[name], " ".join("%d" % (v + 1) for v in (e if dim else (e,))))
             for dim, etype, g in groups for name, es in g.items() for e in es]
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n" % len(names))
        for dim, name in names:
            f.write('%d %d "%s"\n' % (dim, tag[name], name))
        f.write("$EndPhysicalNames\n$Nodes\n%d\n" % len(nodes))
        for k, (x, y, z) in enumerate(nodes):
            f.write("%d %.17g %.17g %.17g\n" % (k + 1, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % len(elems))
        for k, e in enumerate(elems):
            f.write("%d %s\n" % (k + 1, e))
        f.write("$EndElements\n")
