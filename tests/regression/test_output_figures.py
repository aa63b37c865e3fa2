#!/usr/bin/python3
"""Figures of a run (scripts/figures) and the case comparison (scripts/compare_cases).

A small DD1511 saddle (its form-found surface made in the temp dir, 8 increments), the same with
a short pressure cycle (0.5, 0 kPa; every 2nd increment written) and the capstan:
  * scripts/figures exits 0, prints exactly the figures the data supports and writes them as
    non-empty PNGs of the expected size (150 dpi) beside the results or into --out;
  * a figure the data does not support is skipped with a printed note (no pressure cycle, elastic
    material, results without the probe history), not an error;
  * a probe history that belongs to another run (other load times) is reported and not plotted;
  * scripts/compare_cases writes the bar chart and prints the last history row of each run.
"""
import os
import shutil
import struct
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

FIGURES = os.path.join(T.REPO, "scripts", "figures")
COMPARE = os.path.join(T.REPO, "scripts", "compare_cases")
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
SADDLE = ["mises_map", "plastic_strain_map", "min_strain_map", "shape", "slide_history", "parts_history",
          "wrinkle_history", "friction_vs_slide"]
CAPSTAN = ["mises_map", "min_strain_map", "shape", "friction_vs_slide", "contact_wrap", "contact_status",
           "capstan_tension", "probe_history"]


def script(args, timeout=120):
    """Runs a python script of scripts/; (returncode, stdout + stderr, wall seconds)."""
    t0 = time.time()
    p = subprocess.run([PYTHON] + [str(a) for a in args], cwd=T.REPO, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=timeout)
    return p.returncode, p.stdout.decode("utf-8", "replace"), time.time() - t0


def png_size(path):
    """(width, height) of a PNG file, or None when it is not one."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_figures(chk, what, out, expected, outdir, wall):
    listed = [l.strip() for l in out.splitlines() if l.strip().endswith(".png")]
    names = sorted(os.path.splitext(os.path.basename(p))[0] for p in listed)
    chk.check(names == sorted(expected), "%s: figures printed %s (expected %s)" % (what, names, sorted(expected)))
    bad = []
    for name in expected:
        p = os.path.join(outdir, name + ".png")
        size = png_size(p) if os.path.isfile(p) else None
        # every figure is at least 6 x 4 inches at 150 dpi
        if size is None or os.path.getsize(p) < 5000 or size[0] < 900 or size[1] < 450:
            bad.append("%s (%s)" % (name, size))
    chk.check(not bad, "%s: every figure is a non-empty PNG of at least 900 x 450 px in %s%s"
              % (what, outdir, (": bad " + ", ".join(bad)) if bad else ""))
    # Speed belongs to benchmarks, not to a test that CI runs on a loaded machine: reported only.
    print("  %s: figures made in %.1f s" % (what, wall))


def main_test(etfe, chk):
    with T.scratch_dir("figures") as tmp:
        # The DD1511 initial shape (form finding at the thesis density) into the temp dir.
        msh = os.path.join(tmp, "ff_r15_s11_n19.msh")
        T.run(etfe, ["-options_file", os.path.join(T.OPTIONS, "saddle", "ff_r15_s11_n19.opts"), "-formfind_monitor", "0",
                     "-output_file", os.path.join(tmp, "ff", "ff.h5"), "-formfind_mesh_out", msh])
        chk.check(os.path.isfile(msh), "form-found surface written to the temp dir")

        # 1. DD1511, 8 increments (steps 0 and 8 written), figures beside the results.
        dd = os.path.join(tmp, "dd", "dd.h5")
        T.run(etfe, ["-options_file", os.path.join(T.OPTIONS, "saddle", "dd1511.opts"), "-mesh_file", msh,
                     "-load_increments", 8, "-output_file", dd, "-load_monitor", 0])
        rc, out, wall = script([FIGURES, dd])
        chk.check(rc == 0, "figures dd.h5 exits 0 (rc %d)%s" % (rc, "" if rc == 0 else "\n" + T.tail(out)))
        check_figures(chk, "saddle", out, SADDLE, os.path.dirname(dd), wall)
        chk.check("note: pressure_displacement.png" in out, "saddle without a pressure cycle: pressure figure "
                  "skipped with a note")
        chk.check("figure failed" not in out, "no figure failed")

        # 2. With a pressure cycle after the drawing; figures into --out.
        dp = os.path.join(tmp, "dp", "dp.h5")
        T.run(etfe, ["-options_file", os.path.join(T.OPTIONS, "saddle", "dd1511.opts"), "-mesh_file", msh,
                     "-load_increments", 24, "-output_every", 2, "-saddle_pressure_cycle", "0.5,0",
                     "-output_file", dp, "-load_monitor", 0])
        figs = os.path.join(tmp, "dp_figs")
        rc, out, wall = script([FIGURES, dp, "--out", figs, "--pressure-cycle", "0.5,0"])
        chk.check(rc == 0, "figures dp.h5 --out exits 0 (rc %d)%s" % (rc, "" if rc == 0 else "\n" + T.tail(out)))
        check_figures(chk, "saddle + pressure", out, SADDLE + ["pressure_displacement"], figs, wall)
        chk.check(not any(f.endswith(".png") for f in os.listdir(os.path.dirname(dp))),
                  "--out: nothing written beside the results")

        # 3. The capstan (elastic, contact everywhere, probe CSVs).
        cap = os.path.join(tmp, "cap", "capstan.h5")
        T.run(etfe, ["-options_file", T.opts("capstan"), "-output_file", cap, "-load_monitor", 0])
        rc, out, wall = script([FIGURES, cap])
        chk.check(rc == 0, "figures capstan.h5 exits 0 (rc %d)%s" % (rc, "" if rc == 0 else "\n" + T.tail(out)))
        check_figures(chk, "capstan", out, CAPSTAN, os.path.dirname(cap), wall)
        chk.check("note: plastic_strain_map.png" in out, "elastic run: plastic strain map skipped with a note")

        # 4. Missing and foreign data: results without the history, a history of another run.
        bare = os.path.join(tmp, "bare", "bare.h5")
        os.makedirs(os.path.dirname(bare))
        shutil.copy(dd, bare)
        rc, out, wall = script([FIGURES, bare])
        chk.check(rc == 0, "results without the probe history: exits 0 (rc %d)" % rc)
        check_figures(chk, "saddle without history", out,
                      ["mises_map", "plastic_strain_map", "min_strain_map", "shape", "friction_vs_slide"],
                      os.path.dirname(bare), wall)
        chk.check("note: slide_history.png" in out and "note: parts_history.png" in out,
                  "history figures skipped with a note")
        hist = os.path.join(tmp, "bare", "bare_history.csv")
        with open(os.path.join(tmp, "dd", "dd_history.csv")) as f:
            lines = f.read().splitlines()
        with open(hist, "w") as f:  # the same increments at other load times: another run's CSV
            f.write("\n".join([lines[0]] + [",".join([l.split(",")[0], "0.123"] + l.split(",")[2:])
                                            for l in lines[1:]]) + "\n")
        rc, out, wall = script([FIGURES, bare])
        chk.check(rc == 0 and "does not belong to this results file" in out and "slide_history.png" not in
                  "".join(l for l in out.splitlines() if l.endswith(".png")),
                  "a history with other load times is reported and not plotted")

        # 5. compare_cases: the bar chart and the last history rows.
        bars = os.path.join(tmp, "bars", "parts.png")
        rc, out, wall = script([COMPARE, bars, "mu=0.3 (8 inc)=" + dd, "with pressure=" + dp, "none=" + cap])
        chk.check(rc == 0, "compare_cases exits 0 (rc %d)%s" % (rc, "" if rc == 0 else "\n" + T.tail(out)))
        size = png_size(bars) if os.path.isfile(bars) else None
        chk.check(size is not None and os.path.getsize(bars) > 5000, "bar chart written: %s" % (size,))
        last = lines[-1].split(",")
        label = "mu=0.3 (8 inc)"
        row = [l[len(label):].split() for l in out.splitlines() if l.startswith(label)]
        chk.check(len(row) == 1 and abs(float(row[0][0]) - float(last[5])) < 1e-3 and
                  abs(float(row[0][1]) - float(last[9])) < 1e-3,
                  "compare_cases prints the last history row (A_mises %s, B_mises %s): %s"
                  % (last[5], last[9], row))
        chk.check("note: none skipped" in out, "a run without a probe history is skipped with a note")


if __name__ == "__main__":
    T.main(main_test)
