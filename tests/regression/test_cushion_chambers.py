"""Gas chambers (-structure_chambers, src/assembly/chamber.cpp) and the cushion cases.

* A sealed spherical balloon (an octant, 16 x 16 cells, E h = 200 N/mm, R = 1 m), inflated to 2
  kPa, sealed, then under 1 kPa outside: the gauge pressure and the radius (from the chamber's
  volume against the faceted start) match the closed form to 1e-3, for kappa = 1 and 1.4; the
  gas's work along the sealed stage equals the change of its stored energy.
* The rank-one term makes Newton quadratic on a sealed cushion: with it the sealed snow stage of
  options/cushion/hexagon_2layer.opts takes at most 3 iterations an increment; without it
  (-chamber_rank_one 0, the pressure updated between iterations only) far more, or no
  convergence.
* A sealed chamber with a huge reservoir (-chamber_air_extra_volume) gives the supplied answer.
* Sealing per stage (a power cut under snow, then the supply back) ends where supplied
  throughout ends; snow on and off a sealed cushion brings it back to its inflated state.
* The three-layer cushion (two chambers, -mesh_welds): 2 ranks agree with 1; a restart inside
  the sealed stage is bit for bit; a restart with another kappa is refused.
* Bad input: a chamber group that does not exist, signs of the wrong count, a gauge pressure below
  minus the atmosphere, a chamber sealed from the start that encloses nothing, a chamber whose
  open edge may leave its closing plane (the node named); snow heavier than the supplied pressure
  turns the top foil through the bottom one: stopped, naming the load time.
"""
import math
import os
import re
import subprocess

from etfe_testlib import (Checker, etfe_path, increments, largest_family_difference, read_history, run, scratch_dir,
                          stop_and_restart, REPO)
import balloon_mesh

etfe = etfe_path()
chk = Checker("cushion_chambers")
C2 = os.path.join(REPO, "options", "cushion", "hexagon_2layer.opts")
C3 = os.path.join(REPO, "options", "cushion", "hexagon_3layer.opts")
CI = os.path.join(REPO, "options", "cushion", "hexagon_inflate_snow.opts")


def case(args, tmp, name, np=1, expect_fail=False):
    hist = os.path.join(tmp, name + ".csv")
    rc, out = run(etfe, list(args) + ["-output_file", os.path.join(tmp, name + ".h5"), "-structure_history", hist,
                                      "-load_monitor", 1], np=np, expect_fail=expect_fail)
    return rc, out, (read_history(hist) if rc == 0 else [])


with scratch_dir() as tmp:
    # --- the sealed balloon
    msh = os.path.join(tmp, "octant.msh")
    V0 = balloon_mesh.write(msh, 16, 1000.0)
    for kappa in (1.0, 1.4):
        base = ["-scene", "structure", "-mesh_file", msh, "-material_type", "elastic", "-material_young", 800,
                "-material_poisson", 0.3, "-membrane_thickness", 0.25, "-bc_sym_x_fix", "x", "-bc_sym_y_fix", "y",
                "-bc_sym_z_fix", "z", "-structure_chambers", "gas", "-chamber_gas_groups", "skin",
                "-chamber_gas_pressure", "2,2", "-chamber_gas_sealed_from_stage", 2, "-chamber_gas_kappa", kappa,
                "-film_skin_pressure", "0,-1", "-load_increments", 10, "-output", 0]
        rc, out, h = case(base, tmp, "balloon%g" % kappa)
        lam1, lam2, gauge = balloon_mesh.closed_form(800.0, 0.3, 0.25, 1000.0, 2e-3, 1e-3, 0.101325, kappa)
        p = float(h[-1]["gas_p_kPa"]) * 1e-3
        lam = (float(h[-1]["gas_V_m3"]) * 1e9 / V0) ** (1.0 / 3.0)
        lam_sealed = (float(h[4]["gas_V_m3"]) * 1e9 / V0) ** (1.0 / 3.0)
        chk.less(abs(p - gauge) / gauge, 1e-3, "balloon kappa %g: gauge pressure %.6f kPa against the closed form "
                                               "%.6f kPa, relative error" % (kappa, 1e3 * p, 1e3 * gauge))
        chk.less(abs(lam - lam2), 1e-3, "balloon kappa %g: radius %.7f R against %.7f R (from the volume), error / R"
                 % (kappa, lam, lam2))
        chk.less(abs(lam_sealed - lam1), 1e-3, "balloon kappa %g: radius when sealed %.7f R against %.7f R"
                 % (kappa, lam_sealed, lam1))
        # The gas's work along the sealed stage, the trapezoid of p_abs dV over the increments,
        # against the change of its stored energy: C ln(V2/V1) (kappa 1), C (V2^(1-k) - V1^(1-k)) / (1-k).
        patm = 0.101325
        sealed = [r for r in h if float(r["time"]) >= 1.0 - 1e-9]
        V = [1e9 * float(r["gas_V_m3"]) for r in sealed]
        pa = [1e-3 * float(r["gas_p_kPa"]) + patm for r in sealed]
        work = sum(0.5 * (pa[i] + pa[i + 1]) * (V[i + 1] - V[i]) for i in range(len(V) - 1))
        C = pa[0] * V[0] ** kappa
        energy = C * math.log(V[-1] / V[0]) if kappa == 1.0 else C * (V[-1] ** (1 - kappa) - V[0] ** (1 - kappa)) / (1 - kappa)
        chk.less(abs(work - energy) / abs(energy), 1e-4, "balloon kappa %g: the gas's work along the sealed stage "
                                                         "%.6g N mm against its stored energy's change %.6g N mm"
                 % (kappa, work, energy))
        chk.check(abs((lam2 - 1) - (lam - 1)) < 0.01 * (lam2 - 1),
                  "balloon kappa %g: the radial displacement %.4f mm within 1 %% of %.4f mm"
                  % (kappa, 1000 * (lam - 1), 1000 * (lam2 - 1)))

    # --- Newton on the sealed cushion, with and without the rank-one term
    rc, out, h2 = case(["-options_file", C2, "-output", 0], tmp, "c2")
    sealed = [i for i in increments(out) if i["t"] > 2.0 + 1e-9]
    worst = max(i["newton"] for i in sealed)
    chk.check(len(sealed) == 20 and worst <= 3, "2-layer cushion, sealed snow stage: %d increments, at most %d Newton "
                                                "iterations each (quadratic)" % (len(sealed), worst))
    rc1, out1, _ = case(["-options_file", C2, "-output", 0, "-chamber_rank_one", 0, "-load_max_cutbacks", 2], tmp,
                        "c2_no_rank_one", expect_fail=None)
    sealed1 = [i for i in increments(out1) if i["t"] > 2.0 + 1e-9]
    more = sum(i["newton"] for i in sealed1) > 3 * sum(i["newton"] for i in sealed[:len(sealed1)]) if sealed1 else True
    chk.check(rc1 != 0 or more, "without the rank-one term the sealed stage needs far more Newton iterations or "
                                "does not converge (exit %d, %d increments done)" % (rc1, len(sealed1)))
    gauge_end = float(h2[-1]["air_p_kPa"])
    chk.check(gauge_end > 0.45, "sealed cushion under 0.25 kPa of snow: the gauge pressure rose from 0.3 to %.4f kPa"
                                % gauge_end)
    # A huge reservoir keeps the pressure: the supplied answer.
    _, _, hs = case(["-options_file", C2, "-output", 0, "-chamber_air_sealed_from_stage", 0], tmp, "c2_supplied")
    # (The snow squashes the cushion by ~0.2 m^3 against a net 0.05 kPa: a reservoir of V_r moves the
    # pressure by ~p_abs 0.2 / V_r, so the difference falls as 1 / V_r.)
    diffs = []
    for vr in (1e5, 1e6):
        _, _, hr = case(["-options_file", C2, "-output", 0, "-chamber_air_extra_volume", vr], tmp, "c2_res%g" % vr)
        diffs.append(abs(float(hr[-1]["node1_uZ"]) - float(hs[-1]["node1_uZ"])) / abs(float(hs[-1]["node1_uZ"])))
    chk.check(diffs[1] < 1e-3 and 8 < diffs[0] / diffs[1] < 12,
              "sealed with a reservoir tends to the supplied answer as 1 / V_r: centre deflection differs by %.2e "
              "(1e5 m^3) and %.2e (1e6 m^3)" % tuple(diffs))

    # --- 1 vs 2 ranks (each column against the scale of its quantity)
    parallel_difference = largest_family_difference
    _, _, g1 = case(["-options_file", C2, "-load_increments", 30, "-output", 0], tmp, "c2_np1")
    _, _, g2 = case(["-options_file", C2, "-load_increments", 30, "-output", 0], tmp, "c2_np2", np=2)
    worst, where = parallel_difference(g1, g2)
    chk.less(worst, 1e-9, "2-layer cushion: 2 ranks against 1 (at %s)" % (where,))
    # The three-layer cushion's middle foil lies between two chambers of nearly one pressure and
    # carries its weight (without it, a stress-free flat foil: 1 and 2 ranks parted at 6e-7).
    common = ["-options_file", C3, "-load_increments", 30, "-output_every", 1]
    _, out_a, h1 = case(common, tmp, "c3_np1")
    _, _, h2r = case(common, tmp, "c3_np2", np=2)
    worst, where = parallel_difference(h1, h2r)
    chk.less(worst, 1e-9, "3-layer cushion: 2 ranks against 1 (at %s)" % (where,))
    chk.check(len(re.findall(r"chamber (upper|lower): sealed", out_a)) == 2, "3-layer cushion: both chambers sealed")
    # One gas in both chambers (connected) is one chamber of the outer foils: up to the sealing its
    # volume is the sum of the two chambers' (the middle foil, one pressure on both sides, hangs).
    one_gas = os.path.join(tmp, "c3_one_gas.opts")
    with open(one_gas, "w") as f:
        for line in open(C3):
            if not line.startswith(("-chamber_", "-structure_chambers", "-options_file")):
                f.write(line)
        f.write("-options_file %s\n-structure_chambers air\n-chamber_air_groups top,bottom\n"
                "-chamber_air_pressure 0.3,0.3,0.3\n-chamber_air_sealed_from_stage 3\n"
                % os.path.join(REPO, "options", "solvers", "mumps_lu.opts"))
    _, _, hc = case(["-options_file", one_gas, "-load_increments", 30, "-output", 0], tmp, "c3_one_gas")
    at = [k for k, r in enumerate(h1) if abs(float(r["time"]) - 2.0) < 1e-9][0]
    v_two = float(h1[at]["upper_V_m3"]) + float(h1[at]["lower_V_m3"])
    chk.less(abs(float(hc[at]["air_V_m3"]) - v_two) / v_two, 1e-7,
             "3-layer cushion, one gas: its volume at sealing (%.6f m^3) is the two chambers' (%.6f m^3)"
             % (float(hc[at]["air_V_m3"]), v_two))
    full, part, ck = (os.path.join(tmp, n) for n in ("c3_np1.h5", "c3_part.h5", "c3_ck.h5"))
    stop = ["-structure_history", os.path.join(tmp, "c3_part.csv"), "-load_monitor", 0]
    fails, _ = stop_and_restart(etfe, common + stop, part, ck, 25, full)
    chk.check(not fails, "3-layer cushion: stopped inside the sealed stage and restarted, bit for bit%s"
              % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))
    _, out = run(etfe, common + stop + ["-output_file", part, "-chamber_upper_kappa", 1.4, "-restart", ck],
                 expect_fail=True)
    chk.check("kappa" in out or "physics" in out or "differ" in out,
              "3-layer cushion: a restart with another kappa is refused")

    # --- sealed for one stage only (a power cut under snow), then supplied again: the supply takes
    # over from the sealed pressure over the next stage and ends where supplied throughout ends;
    # a restart after the release is bit for bit (the release is in the checkpoint)
    per_stage = ["-options_file", CI, "-chamber_air_sealed_from_stage", 0, "-chamber_air_pressure", "0.3,0.3,0.3",
                 "-film_top_snow", "0,0.25,0.25", "-load_increments", 30, "-output_every", 1]
    _, out_r, hr = case(per_stage + ["-chamber_air_sealed", "0,1,0"], tmp, "cut")
    _, _, hsup = case(per_stage, tmp, "cut_supplied")
    chk.check("chamber air: supplied again at load time 2" in out_r, "power cut: the supply is on again at load time 2")
    at2 = [r for r in hr if abs(float(r["time"]) - 2.0) < 1e-9][0]
    chk.check(float(at2["air_p_kPa"]) > 0.4, "power cut: sealed under the snow the pressure rose to %s kPa"
              % at2["air_p_kPa"])
    for col in ("air_p_kPa", "air_V_m3", "node1_uZ"):
        a, b = float(hr[-1][col]), float(hsup[-1][col])
        chk.less(abs(a - b) / abs(b), 1e-8, "power cut: %s at the end %.8g, supplied throughout %.8g" % (col, a, b))
    full, part, ck = (os.path.join(tmp, n) for n in ("cut.h5", "cut_part.h5", "cut_ck.h5"))
    stop = ["-chamber_air_sealed", "0,1,0", "-structure_history", os.path.join(tmp, "cut_part.csv"), "-load_monitor", 0]
    fails, _ = stop_and_restart(etfe, per_stage + stop, part, ck, 24, full)
    chk.check(not fails, "power cut: restarted after the release, bit for bit%s"
              % ("" if not fails else ": " + "; ".join(map(str, fails[:3]))))

    # --- unloading: the snow on the sealed cushion and off again; the film stays elastic and the
    # isothermal gas is reversible, so the cushion comes back to its inflated state
    _, _, hu = case(["-options_file", CI, "-chamber_air_pressure", "0.3,0.3,0.3", "-film_top_snow", "0,0.25,0",
                     "-load_increments", 30, "-output", 0], tmp, "unload")
    at1 = [r for r in hu if abs(float(r["time"]) - 1.0) < 1e-9][0]
    for col in ("air_p_kPa", "air_V_m3", "node1_uZ", "top_mises"):
        a, b = float(hu[-1][col]), float(at1[col])
        chk.less(abs(a - b) / abs(b), 1e-7, "snow on and off the sealed cushion: %s back to %.8g (inflated %.8g)"
                 % (col, a, b))

    # --- the foils' patterns with a 20 mm weld allowance and the MD mark: the allowance outline lies
    # 20 mm outside the pattern along every edge (the SVG's 4 decimals), further only at corners
    run(etfe, ["-analysis", "cutpattern", "-mesh_file", os.path.join(REPO, "meshes", "cushion_hexagon_2layer.msh"),
               "-cutpattern_strips", "top,bottom", "-cutpattern_seam_allowance", 20, "-cutpattern_md_mark",
               "-output_file", os.path.join(tmp, "foils.h5")])
    svg = open(os.path.join(tmp, "foils_top.svg")).read()

    def group_points(name):
        body = re.search(r'<g id="%s"[^>]*>(.*?)</g>' % name, svg, re.S).group(1)
        d = re.search(r'd="([^"]*)"', body).group(1)
        return [tuple(map(float, p.split(","))) for p in re.findall(r"[-\d.]+,[-\d.]+", d)]

    def distance(p, poly):
        best = math.inf
        for a, b in zip(poly, poly[1:] + poly[:1]):
            dx, dy = b[0] - a[0], b[1] - a[1]
            t = max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)))
            best = min(best, math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy))
        return best
    # The SVG's groups are the DXF's layers: "weld" the pattern's edge, "outline" the cut line.
    outline, seam = group_points("weld"), group_points("outline")
    mids = [((a[0] + b[0]) / 2, (a[1] + b[1]) / 2) for a, b in zip(seam, seam[1:] + seam[:1])]
    dm = [distance(m, outline) for m in mids]
    chk.check(len(seam) == len(outline) and max(abs(x - 20.0) for x in dm) < 1e-3,
              "cushion foil pattern: the weld allowance runs 20 mm outside every edge (%.5f-%.5f mm)" % (min(dm), max(dm)))
    chk.check('<g id="md"' in svg and ">MD</text>" in svg and "MD" in open(os.path.join(tmp, "foils_top.dxf")).read(),
              "cushion foil pattern: the MD (roll) direction is marked in the SVG and the DXF")

    # --- refusals
    flat = os.path.join(tmp, "flat.msh")
    subprocess.run([os.path.join(REPO, "scripts", "cushion-mesh"), flat, "--hexagon", "1500", "--lens", "0"], check=True,
                   stdout=subprocess.DEVNULL)
    square = os.path.join(tmp, "square.msh")  # one flat foil, closed by the plane it lies in
    with open(square, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"edge\"\n2 2 \"skin\"\n"
                "$EndPhysicalNames\n$Nodes\n5\n1 0 0 0\n2 1000 0 0\n3 1000 1000 0\n4 0 1000 0\n5 500 500 0\n"
                "$EndNodes\n$Elements\n8\n" + "".join("%d 1 2 1 1 %d %d\n" % (k + 1, k + 1, k % 4 + 2 if k < 3 else 1)
                                                      for k in range(4)) +
                "".join("%d 2 2 2 2 %d %d 5\n" % (k + 5, k + 1, k + 2 if k < 3 else 1) for k in range(4)) +
                "$EndElements\n")
    bad = [(["-chamber_air_groups", "roof"], r"-chamber_air_groups: the mesh has no surface group roof"),
           (["-chamber_air_signs", "1"], r"-chamber_air_signs: one sign per group"),
           (["-chamber_air_pressure", "-200,0.3,0.3"], r"below minus the atmosphere"),
           (["-chamber_air_groups", "top", "-chamber_air_sealed_from_stage", 1, "-chamber_air_signs", -1],
            r"chamber air encloses a negative volume at the start \(-0\.\d+ m\^3\)"),
           (["-chamber_air_signs", "1,-1"],
            r"chamber air: its surfaces are not oriented consistently: two of its triangles \(groups top and bottom\) "
            r"run along the edge from node \d+ to node \d+"),
           (["-chamber_air_sealed", "0,1,1"], r"give -chamber_air_sealed \(per stage\) or -chamber_air_sealed_from_stage"),
           (["-chamber_air_sealed_from_stage", 0, "-chamber_air_sealed", "0,1"],
            r"-chamber_air_sealed: one flag per stage \(2 given, the analysis has 3 stages\)"),
           (["-mesh_file", flat, "-structure_reference", "mesh"],
            r"node \d+ \(tag \d+ in the file\) and node \d+ \(tag \d+ in the file\) coincide.*start them apart"),
           (["-chamber_air_groups", "top", "-bc_rim_fix", "xy"], r"chamber air is not closed: node \d+"),
           (["-chamber_air_sealed_from_stage", 0, "-film_top_snow", "0,0,2"],
            r"chamber air turned inside out at load time 2\.\d+")]
    for args, pattern in bad:
        _, out = run(etfe, ["-options_file", C2, "-output", 0] + args, expect_fail=True)
        chk.check(re.search(pattern, out), "refused: %s (%s)" % (" ".join(map(str, args)), pattern))
    _, out = run(etfe, ["-scene", "structure", "-mesh_file", square, "-bc_edge_fix", "xyz", "-structure_chambers", "gas",
                        "-chamber_gas_groups", "skin", "-chamber_gas_pressure", 0.3, "-output", 0], expect_fail=True)
    chk.check("chamber gas encloses no volume at the start (0. m^3 for 1. m^2 of foil)" in out,
              "refused: a flat foil closed by the plane it lies in encloses no volume")

chk.finish()
