"""A cushion's chamber turned inside out is never a completed run (src/assembly/chamber.cpp,
src/assembly/layer_contact.cpp).

A supplied chamber under snow heavier than its pressure empties; its top foil may then rest on the
foil below only where layer contact between the chamber's own foils keeps them apart. Otherwise the
top foil passes through and the chamber's volume goes negative: the run must stop, naming the
chamber, its volume and the stage.
* -layer_contact top:top (a foil with itself, which pairs nothing) is refused at set-up, and so is
  a pair with no node to hold (the upper foil held everywhere);
* the three-layer hexagon (scripts/cushion-mesh, 216 triangles a foil), supplied throughout under
  2 kPa of snow with contact top:bottom only: the top foil passes through the middle one, the upper
  chamber (top, middle) is not kept apart by that pair, so the run fails, its results' status
  "failed" naming the chamber, the stage and the missing pair top:middle;
* the same with -layer_contact top:middle,middle:bottom completes with all three foils on each
  other and both chambers empty (the penalty's penetration only: |V| < 1e-3 m^3);
* two chambers on the same side of one foil (two chambers of top,bottom, whose pressures would add)
  are refused at set-up, naming both chambers and the group.
"""
import os
import re
import subprocess
import sys

from etfe_testlib import Checker, etfe_path, read_history, run, scratch_dir, status, REPO

etfe = etfe_path()
chk = Checker("cushion_inside_out")
C2 = os.path.join(REPO, "options", "cushion", "hexagon_inflate_snow.opts")
C3 = os.path.join(REPO, "options", "cushion", "hexagon_3layer.opts")
SNOW2 = ["-options_file", C2, "-chamber_air_sealed_from_stage", 0, "-film_top_snow", "0,2", "-load_increments", 40,
         "-output", 0]

with scratch_dir() as tmp:
    rc, out = run(etfe, SNOW2 + ["-layer_contact", "top:top"], expect_fail=None)
    chk.check(rc != 0 and re.search(r"-layer_contact top:top: a foil's contact with itself is not modelled", out),
              "refused: -layer_contact top:top (exit code %d)" % rc)

    rc, out = run(etfe, SNOW2 + ["-layer_contact", "top:bottom", "-bc_top_fix", "xyz"], expect_fail=None)
    chk.check(rc != 0 and "-layer_contact top:bottom pairs no node" in out,
              "refused: a pair whose upper foil is held everywhere holds nothing (exit code %d)" % rc)

    # (accepted before, the two pressures adding on the foils: 0.79 m^3 inflated against 0.73)
    rc, out = run(etfe, ["-options_file", C2, "-output", 0, "-structure_chambers", "air,gas", "-chamber_gas_groups",
                         "top,bottom", "-chamber_gas_pressure", "0.3,0.3"], expect_fail=None)
    chk.check(rc != 0 and re.search(r"chambers air and gas lie on the same side of one foil \(surface group top of "
                                     r"air, top of gas", out),
              "refused: two chambers on the same foils, both named with the group (exit code %d)" % rc)

    msh = os.path.join(tmp, "cushion3.msh")
    subprocess.run([sys.executable, os.path.join(REPO, "scripts", "cushion-mesh"), msh, "--hexagon", "1500",
                    "--layers", "3", "--size", "300"], check=True, stdout=subprocess.DEVNULL)
    snow3 = ["-options_file", C3, "-mesh_file", msh, "-chamber_upper_sealed_from_stage", 0,
             "-chamber_lower_sealed_from_stage", 0, "-film_top_snow", "0,0,2", "-load_increments", 90]

    def three_layer(name, contact, expect_fail):
        h5, hist = os.path.join(tmp, name + ".h5"), os.path.join(tmp, name + ".csv")
        rc, out = run(etfe, snow3 + ["-layer_contact", contact, "-output_file", h5, "-structure_history", hist],
                      expect_fail=expect_fail)
        return rc, out, status(h5), read_history(hist)

    rc, out, st, h = three_layer("one_pair", "top:bottom", None)
    chk.check(rc != 0, "three layers, contact top:bottom only: the run fails (exit code %d)" % rc)
    m = re.search(r"chamber upper turned inside out at load time (\S+) \(stage 3, volume (\S+) m\^3\)", st)
    chk.check(st.startswith("failed") and m and float(m.group(2)) <= 0 and "top:middle in -layer_contact" in st,
              "its status is failed, naming the chamber, the stage, the volume and the pair to add: %s" % st[:160])
    chk.check(all(float(r["upper_V_m3"]) > 0 for r in h),
              "every increment the results keep has a positive upper chamber (the last %s m^3)" % h[-1]["upper_V_m3"])

    _, out, st, h = three_layer("both_pairs", "top:middle,middle:bottom", False)
    chk.check(st == "complete" and "completed after" in out, "three layers, contact top:middle,middle:bottom: "
                                                             "complete (%s)" % st)
    vu, vl = float(h[-1]["upper_V_m3"]), float(h[-1]["lower_V_m3"])
    chk.check(abs(vu) < 1e-3 and abs(vl) < 1e-3, "both chambers empty, the foils on each other: %.6f and %.6f m^3"
              % (vu, vl))

chk.finish()
