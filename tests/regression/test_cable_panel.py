"""A cable-reinforced single-layer ETFE panel (options/structure/cable_panel.opts, docs/cables.md):
a flat 3 m x 3 m film in a frame with two cables each way along lines of its mesh (meshes/
cable_panel.py, here 4 x 4 squares a bay), prestressed by drawing the frame outward by a
homogeneous biaxial stretch e = 1.5e-3 (stage 1), then under wind suction 0.5 kPa x cp -0.8
(stage 2, the frame held):

* prestress: the film and the cables share one homogeneous stretch, so every cable segment carries
  the closed form N = EA E s (s = (1 + e)(1 + T/EA) its stretch from the stress-free length, E =
  (s^2 - 1)/2) at the end of stage 1, within 1e-6;
* equilibrium: the frame's vertical reaction equals the suction on the drawn panel's plan area,
  0.4 kPa x (3000 (1 + e))^2, within 1e-6 (the frame holds the boundary in its plane, so the
  follower pressure's vertical resultant is p times the plan area whatever the film's shape);
* the cables carry a share of the suction: the vertical pulls at their eight anchors add up to
  more than 30 % of the frame's reaction, and every cable's force rises under the suction;
* the net stiffens the panel: the centre deflects less than half as much as the same film without
  cables.
"""
import os
import re
import subprocess
import sys

import etfe_testlib as T
from etfe_testlib import run, scratch_dir

CABLES = ("cable_x1", "cable_x2", "cable_y1", "cable_y2")
PULL = re.compile(r"structure: cable (\w+) end \d \(node \d+\): pull = \((\S+), (\S+), (\S+)\) N")
FRAME = re.compile(r"structure: support frame reaction = \((\S+), (\S+), (\S+)\) N")
CENTRE = re.compile(r"structure: probe node 1 .* u = \((\S+), (\S+), (\S+)\) mm")
E, T0, EA, Q, CP, SIDE = 1.5e-3, 2000.0, 4e6, 0.5, -0.8, 3000.0


def panel(etfe, tmp, mesh, name, cables=True):
    """One run of cable_panel.opts on `mesh` (without the cables' options when cables is False)."""
    opts = os.path.join(T.OPTIONS, "structure", "cable_panel.opts")
    args = ["-options_file", opts, "-mesh_file", mesh, "-output", 0,
            "-structure_history", os.path.join(tmp, name + "_history.csv")]
    if not cables:  # the same case with the net's options left out: the film alone
        plain = os.path.join(tmp, name + ".opts")
        with open(opts) as f, open(plain, "w") as g:
            g.write("".join(l for l in f if not l.startswith("-cable_")).replace(
                "-options_file options/", "-options_file %s/" % T.OPTIONS))
        args[1] = plain
    _, out = run(etfe, args)
    frame, centre = FRAME.search(out), CENTRE.search(out)
    if not frame or not centre:
        raise T.TestFailure("no frame reaction or centre probe line:\n" + T.tail(out))
    return out, float(frame.group(3)), float(centre.group(3)), T.read_history(os.path.join(tmp, name + "_history.csv"))


def test(etfe, chk):
    with scratch_dir("etfe-cable-panel") as tmp:
        mesh = os.path.join(tmp, "panel.msh")
        subprocess.run([sys.executable, os.path.join(T.REPO, "meshes", "cable_panel.py"), "4", "3000,3000", "2,2", mesh],
                       check=True, stdout=subprocess.DEVNULL)
        out, rz, w, hist = panel(etfe, tmp, mesh, "net")

        s = (1 + E) * (1 + T0 / EA)
        closed = EA * (s * s - 1) / 2 * s
        stage1 = [r for r in hist if abs(float(r["time"]) - 1.0) < 1e-9]
        if len(stage1) != 1:
            raise T.TestFailure("no history row at the end of stage 1 (load time 1)")
        worst = max(abs(float(stage1[0]["cable_%s_force_max" % g]) / closed - 1) for g in CABLES)
        chk.less(worst, 1e-6, "end of stage 1: the cables' force against EA E s = %.3f N (homogeneous stretch), largest "
                              "relative difference" % closed)

        load = Q * -CP * 1e-3 * (SIDE * (1 + E)) ** 2
        chk.less(abs(-rz / load - 1), 1e-6, "suction: frame reaction Z %.6f N against p x plan area %.6f N, relative "
                                            "difference" % (rz, load))

        pulls = [float(m.group(4)) for m in PULL.finditer(out)]
        chk.check(len(pulls) == 8, "eight cable anchors report their pull (%d)" % len(pulls))
        share = sum(pulls) / -rz
        chk.check(share > 0.3, "the cables' anchors take %.1f %% of the suction (more than 30 %%)" % (100 * share))
        rise = min(float(hist[-1]["cable_%s_force_max" % g]) - float(stage1[0]["cable_%s_force_max" % g]) for g in CABLES)
        chk.check(rise > 0, "every cable's force rises under the suction (smallest rise %.1f N)" % rise)

        _, rz0, w0, _ = panel(etfe, tmp, mesh, "film", cables=False)
        chk.less(abs(-rz0 / load - 1), 1e-6, "film alone: frame reaction Z against p x plan area, relative difference")
        chk.check(0 < w < 0.5 * w0, "centre deflection with the net %.2f mm, less than half the film's alone %.2f mm"
                  % (w, w0))


if __name__ == "__main__":
    T.main(test)
