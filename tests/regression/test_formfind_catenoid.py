"""Form finding against closed forms.

* catenoid (options/catenoid.opts): the neck radius within 1 % of c with R = c cosh(H/2c) at
  the documented density (48 x 16), and the error shrinks under refinement;
* the found surface has zero mean curvature: the discrete (cotangent) mean curvature at interior
  nodes is small against that of the starting cylinder, 1/(2R);
* beyond the Goldschmidt limit (H/R = 1.4) the run ends with an error, not a shape.
"""
import os

import h5py
import numpy as np

from etfe_testlib import Checker, etfe_path, opts, run, scene_value, scratch_dir, summary

etfe = etfe_path()
chk = Checker("formfind_catenoid")


def mean_curvature(x, tri):
    """|H| per node from the cotangent Laplacian: H n = 1/(4 A_i) sum (cot a + cot b)(x_i - x_j)."""
    n = len(x)
    lap = np.zeros((n, 3))
    area = np.zeros(n)
    for t in tri:
        for k in range(3):
            i, j, l = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
            # angle at l opposite edge (i, j)
            u, v = x[i] - x[l], x[j] - x[l]
            cot = np.dot(u, v) / np.linalg.norm(np.cross(u, v))
            lap[i] += cot * (x[i] - x[j])
            lap[j] += cot * (x[j] - x[i])
        a = 0.5 * np.linalg.norm(np.cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]))
        area[t] += a / 3.0
    return np.linalg.norm(lap, axis=1) / (4.0 * area)


with scratch_dir() as tmp:
    print("%8s %10s %14s %12s %8s" % ("refine", "triangles", "neck [mm]", "error", "wall s"))
    errors = []
    for r in (0, 1, 2):
        out_file = os.path.join(tmp, "cat%d.h5" % r)
        rc, out = run(etfe, ["-options_file", opts("catenoid"), "-mesh_refine", r, "-formfind_monitor", 0,
                             "-output_file", out_file, "-formfind_mesh_out", os.path.join(tmp, "c%d.msh" % r)])
        err = scene_value(out, "catenoid", "ring", "relative_error")
        neck = float(out.split("neck_radius = ")[1].split()[0])
        errors.append(err)
        print("%8d %10d %14.6f %12.3e %8.3f" % (r, 1536 * 4 ** r, neck, err, summary(out)["wall"]))
        if r == 0:
            chk.check(err < 0.01, "neck radius within 1 %% of the closed form at 48 x 16 (error %.2e)" % err)
            with h5py.File(out_file, "r") as f:
                chk.check(f.attrs["status"].decode() == "complete", "results status is complete")
                steps = sorted(f["steps"].keys())
                x0 = f["mesh/coordinates"][:]
                x = x0 + f["steps"][steps[-1]]["displacement"][:]
                tri = f["mesh/triangles"][:]
            z = x0[:, 2]
            interior = np.abs(np.abs(z) - 500.0) > 1.0  # away from the rings
            H = mean_curvature(x, tri)[interior]
            H0 = mean_curvature(x0, tri)[interior]
            print("mean curvature at interior nodes: found surface max %.3e, mean %.3e; starting cylinder %.3e 1/mm"
                  % (H.max(), H.mean(), H0.mean()))
            chk.check(H.max() < 0.02 * H0.mean(),
                      "mean curvature of the found surface below 2 %% of the cylinder's (max %.2e vs %.2e)"
                      % (H.max(), H0.mean()))
            chk.check(os.path.exists(os.path.join(tmp, "c0.msh")), "the found surface is written as a Gmsh file")
    chk.check(errors[0] > errors[1] > errors[2], "the neck error shrinks under refinement")

    rc, out = run(etfe, ["-options_file", opts("catenoid"), "-catenoid_separation", 1400, "-formfind_monitor", 0,
                         "-output_file", os.path.join(tmp, "gold.h5")], expect_fail=True)
    chk.check("collapsed" in out or "no equilibrium" in out.lower(),
              "beyond the Goldschmidt limit the run stops with a message naming the collapse")
    with h5py.File(os.path.join(tmp, "gold.h5"), "r") as f:
        chk.check(f.attrs["status"].decode().startswith("failed"), "and the results file says failed")
chk.finish()
