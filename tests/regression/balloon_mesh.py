"""An octant of a sphere as a Gmsh 2.2 mesh for the sealed-balloon check (test_cushion_chambers):
the spherical triangle x, y, z >= 0 cut into n^2 triangles (a barycentric grid projected onto the
sphere), normals out, surface group "skin", point groups "sym_x", "sym_y", "sym_z" on the three
symmetry planes. write() returns the faceted octant's volume (mm^3) at its nodes' radius."""
import math

import etfe_testlib  # noqa: F401  (puts <repo>/scripts on sys.path)
from etfepy import msh22  # scripts/etfepy/msh22.py


def write(path, n, R):
    pts, idx = [], {}
    for i in range(n + 1):
        for j in range(n + 1 - i):
            v = (i / n, j / n, (n - i - j) / n)
            l = math.sqrt(sum(c * c for c in v))
            idx[(i, j)] = len(pts)
            pts.append(tuple(R * c / l for c in v))
    tris = []
    for i in range(n):
        for j in range(n - i):
            tris.append((idx[(i, j)], idx[(i + 1, j)], idx[(i, j + 1)]))
            if j + 1 <= n - i - 1:
                tris.append((idx[(i + 1, j)], idx[(i + 1, j + 1)], idx[(i, j + 1)]))

    def signed(t):
        a, b, c = (pts[x] for x in t)
        return (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
    tris = [t if signed(t) > 0 else (t[0], t[2], t[1]) for t in tris]
    groups = [("sym_%s" % "xyz"[d], [m for m, p in enumerate(pts) if abs(p[d]) < 1e-9 * R]) for d in range(3)]
    names = [(2, 1, "skin")] + [(0, k + 2, g) for k, (g, _) in enumerate(groups)]
    els = [(2, 1, 1, t) for t in tris] + [(15, k + 2, k + 2, (m,)) for k, (_, ms) in enumerate(groups) for m in ms]
    msh22.write_elements(path, pts, names, els)
    return sum(signed(t) for t in tris)


def closed_form(E, nu, h, R, p1, q, patm, kappa):
    """A sealed spherical balloon of a St. Venant-Kirchhoff membrane (equibiaxial stretch lam:
    membrane force S h0 = E h0 (lam^2 - 1) / (2 (1 - nu)), equilibrium S h0 = p r / 2 with
    r = lam R): inflated to the gauge pressure p1, sealed (p_abs V^kappa = C), then loaded by an
    external pressure q. Returns (lam1, lam2, gauge pressure at the end), pressures in MPa."""
    def bisect(f, lo, hi):
        for _ in range(200):
            m = 0.5 * (lo + hi)
            lo, hi = (m, hi) if f(m) > 0 else (lo, m)
        return lo
    membrane = lambda lam: E * h * (lam * lam - 1) / ((1 - nu) * lam * R)
    lam1 = bisect(lambda lam: p1 - membrane(lam), 1.0, 1.5)
    V = lambda lam: 4.0 / 3.0 * math.pi * (lam * R) ** 3
    C = (p1 + patm) * V(lam1) ** kappa
    gauge = lambda lam: C / V(lam) ** kappa - patm
    lam2 = bisect(lambda lam: gauge(lam) - q - membrane(lam), 1.0, 1.5)
    return lam1, lam2, gauge(lam2)
