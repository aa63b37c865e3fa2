"""Frictionless contact between film layers (-layer_contact, src/assembly/layer_contact.cpp).

The extreme case of a cushion: snow heavier than the supplied pressure (2 kPa against 0.3 kPa on
the two-layer hexagon, options/cushion/hexagon_inflate_snow.opts supplied throughout). Without
layer contact the top foil passes through the bottom one and the run stops (test_cushion_chambers);
with it the top foil rests on the bottom one:
* the run completes; the frame carries exactly the snow on the plan area (the gas pushes the foils
  apart and nothing else loads them): R_z = 2 kPa x 5.8457 m^2 to 1e-8 (9 printed digits);
* the penetration stays small (the penalty 10 kPa per mm against 1.7 kPa net: < 0.2 mm) and the
  chamber is empty (|V| below 1e-3 m^3, against 0.63 m^3 inflated);
* both foils hang below the rim, the top one on the bottom one (the top foil's centre within
  0.2 mm of the bottom foil's);
* 2 ranks against 1: the frame's reaction to 1e-9, the centre deflection to 1e-5 (a node that sits
  at a vertex of the layer below may take another of its triangles on another partition);
* a restart between increments with the foils in contact is bit for bit (the pairs are in the
  checkpoint).
"""
import math
import os
import re

from etfe_testlib import Checker, etfe_path, read_history, run, scratch_dir, REPO
import h5compare

etfe = etfe_path()
chk = Checker("layer_contact")
CASE = os.path.join(REPO, "options", "cushion", "hexagon_inflate_snow.opts")
ARGS = ["-options_file", CASE, "-chamber_air_sealed_from_stage", 0, "-film_top_snow", "0,2", "-layer_contact",
        "top:bottom", "-load_increments", 40]


def case(tmp, name, np=1, extra=()):
    hist = os.path.join(tmp, name + ".csv")
    _, out = run(etfe, ARGS + list(extra) + ["-output_file", os.path.join(tmp, name + ".h5"), "-structure_history",
                                             hist, "-output_every", 1], np=np)
    return out, read_history(hist)


with scratch_dir() as tmp:
    out, h = case(tmp, "np1")
    chk.check("completed after" in out, "snow of 2 kPa on 0.3 kPa supplied: completed with the foils in contact")
    snow = 2e-3 * 1.5 * math.sqrt(3) * 1500.0 ** 2  # 2 kPa on the hexagon's plan area (3 sqrt(3) / 2 R^2), N
    rz = float(h[-1]["rim_RZ"])
    chk.less(abs(rz - snow) / snow, 1e-8, "the frame carries the snow (the history's 9 digits): R_z %.6f N against %.6f N"
             % (rz, snow))
    m = re.search(r"layer contact: (\d+) of (\d+) paired nodes touching the layer below, deepest penetration (\S+) mm",
                  out)
    chk.check(m and int(m.group(1)) > 0 and float(m.group(3)) < 0.2,
              "touching nodes and penetration: %s" % (m.group(0) if m else "no report line"))
    vol = float(h[-1]["air_V_m3"])
    chk.less(abs(vol), 1e-3, "the chamber is empty: %.6f m^3" % vol)
    # the centres, from the 30 mm lens (top up, bottom down): the probe is the top's centre, the
    # bottom's largest displacement is at its centre
    top = float(h[-1]["node1_uZ"])
    z_top, z_bottom = 30.0 + top, -30.0 - float(h[-1]["bottom_u_max"])
    chk.check(z_top < -100 and abs(z_top - z_bottom) < 0.2,
              "the top foil rests on the bottom one: centres at z = %.4f and %.4f mm" % (z_top, z_bottom))

    _, h2 = case(tmp, "np2", np=2)
    chk.less(abs(float(h2[-1]["rim_RZ"]) - rz) / rz, 1e-9, "2 ranks against 1: the frame's reaction")
    chk.less(abs(float(h2[-1]["node1_uZ"]) - top) / abs(top), 1e-5,
             "2 ranks against 1: the top centre %s against %.9g mm" % (h2[-1]["node1_uZ"], top))

    part, ck = os.path.join(tmp, "part.h5"), os.path.join(tmp, "ck.h5")
    stop = ["-output_file", part, "-structure_history", os.path.join(tmp, "part.csv"), "-output_every", 1,
            "-load_monitor", 0]
    run(etfe, ARGS + stop + ["-load_stop_after", 31, "-checkpoint_file", ck])
    run(etfe, ARGS + stop + ["-restart", ck])
    fails = h5compare.compare(os.path.join(tmp, "np1.h5"), part, step="all", default_rtol=0.0, default_atol=0.0)
    chk.check(not fails, "restarted with the foils in contact, bit for bit%s"
              % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))

chk.finish()
