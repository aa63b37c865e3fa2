"""The cushion planforms of scripts/cushion-mesh, each inflated from its flat patterns.

For a circle, a rectangle, a triangle, a hexagon and an irregular convex polygon (2 layers, the
patterns the reference from the start, 0.3 kPa supplied in 5 increments):
* the run converges and the chamber encloses a positive volume;
* the bottom foil is the top foil's mirror image (the mesh mirrors it, the pressure pushes both
  out): their largest displacements and mean stresses agree to 1e-8;
* the frame carries no net vertical force (the gas pushes the two foils apart, nothing else
  loads them): |R_z| below 1e-6 of the pressure on the plan area.
And a three-layer rectangle with one gas in both chambers (one chamber of the outer foils): its
middle foil, the same pressure on both sides, carries nothing and stays flat.
"""
import os
import subprocess

from etfe_testlib import Checker, etfe_path, read_history, run, scratch_dir, REPO

etfe = etfe_path()
chk = Checker("cushion_planforms")
CASE = os.path.join(REPO, "options", "cushion", "hexagon_inflate_snow.opts")
PLANFORMS = [("circle", ["--circle", "1200"]), ("rectangle", ["--rectangle", "3000,1800"]),
             ("triangle", ["--triangle", "1800"]), ("hexagon", ["--hexagon", "1500"]),
             ("polygon", ["--polygon", "0,0,2600,-300,3100,1400,1200,2300,-400,1200"])]


def inflate(tmp, name, planform, layers=2):
    msh = os.path.join(tmp, name + ".msh")
    out = subprocess.run([os.path.join(REPO, "scripts", "cushion-mesh"), msh, "--layers", str(layers), "--size", "250"]
                         + planform, check=True, capture_output=True, text=True).stdout
    hist = os.path.join(tmp, name + ".csv")
    args = ["-options_file", CASE, "-mesh_file", msh, "-chamber_air_pressure", 0.3, "-chamber_air_sealed_from_stage", 0,
            "-film_top_snow", 0, "-load_increments", 5, "-output", 0, "-structure_history", hist]
    if layers == 3:
        args += ["-mesh_welds", "-structure_pattern_strips", "top,middle,bottom"]
    rc, log = run(etfe, args)
    return out, log, read_history(hist)[-1]


with scratch_dir() as tmp:
    for name, planform in PLANFORMS:
        mesh_line, log, h = inflate(tmp, name, planform)
        chk.check("completed after 5 increments" in log and float(h["air_V_m3"]) > 0,
                  "%s: inflated to 0.3 kPa, %.4f m^3 (%s)" % (name, float(h["air_V_m3"]), mesh_line.strip()))
        for col in ("u_max", "mises", "mises_max"):
            t, b = float(h["top_" + col]), float(h["bottom_" + col])
            chk.less(abs(t - b) / abs(t), 1e-8, "%s: bottom foil mirrors the top, %s %.6g against %.6g" % (name, col, b, t))
        plan_force = 0.3e-3 * float(h["air_V_m3"]) * 1e9 / (2 * float(h["top_u_max"]))  # p x plan area, roughly
        chk.less(abs(float(h["rim_RZ"])) / plan_force, 1e-6, "%s: no net vertical force on the frame (R_z = %.3g N)"
                 % (name, float(h["rim_RZ"])))
    _, log, h = inflate(tmp, "rectangle3", ["--rectangle", "3000,1800"], layers=3)
    chk.less(float(h["middle_u_max"]) / float(h["top_u_max"]), 1e-8,
             "3-layer rectangle, one gas: the middle foil stays flat (%.3g mm)"
             % float(h["middle_u_max"]))

chk.finish()
