"""Gas chambers in the results file: their physics term's fields (PhysicsTerm::Fields).

A two-layer hexagon cushion inflated to 0.3 kPa in 3 increments, with results and the structure
history:
* every written step holds chambers/gauge_pressure [MPa] and chambers/volume [mm^3], one row per
  chamber, each with the attributes of its row of the field table (written "with its term");
* at every step they are the pressure and volume the history CSV gives for that step (kPa and
  m^3, printed to 9 significant digits);
* the last step's pressure is the supplied 0.3 kPa.
"""
import os
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

CASE = os.path.join(T.REPO, "options", "cushion", "hexagon_inflate_snow.opts")


def field_rows(f):
    lines = T.h5compare.text(f.attrs["field_table"]).strip("\n").split("\n")
    keys = lines[0].split("\t")
    return {r["name"]: r for r in (dict(zip(keys, line.split("\t"))) for line in lines[1:])}


def main_test(etfe, chk):
    import h5py
    with T.scratch_dir("chambers") as tmp:
        msh, h5, hist = (os.path.join(tmp, n) for n in ("hexagon.msh", "cushion.h5", "history.csv"))
        subprocess.run([os.path.join(T.REPO, "scripts", "cushion-mesh"), msh, "--layers", "2", "--size", "250",
                        "--hexagon", "1500"], check=True, capture_output=True)
        T.run(etfe, ["-options_file", CASE, "-mesh_file", msh, "-chamber_air_pressure", 0.3,
                     "-chamber_air_sealed_from_stage", 0, "-film_top_snow", 0, "-load_increments", 3,
                     "-load_monitor", 0, "-output_every", 1, "-output_file", h5, "-structure_history", hist])
        rows = {int(r["step"]): r for r in T.read_history(hist)}
        with h5py.File(h5, "r") as f:
            table = field_rows(f)
            steps = T.h5compare.written_steps(f)
            bad = []
            for name, unit in (("chambers/gauge_pressure", "MPa"), ("chambers/volume", "mm^3")):
                r = table.get(name)
                if r is None or r["units"] != unit or r["written"] != "with its term" or r["location"] != "item":
                    bad.append("%s: field table row %s" % (name, r))
                for k in steps:
                    d = f["steps/%06d" % k].get(name)
                    if d is None or d.shape != (1,) or T.h5compare.text(d.attrs.get("units", b"")) != unit:
                        bad.append("step %d: %s %s" % (k, name, None if d is None else d.shape))
            chk.check(len(steps) >= 2 and not bad, "%d steps, each with the chamber's pressure [MPa] and volume [mm^3] "
                      "as rows of the field table%s" % (len(steps), "" if not bad else ": " + "; ".join(bad[:4])))
            if bad:
                return
            worst = 0.0
            for k in steps:
                if k not in rows:
                    continue
                p = 1e3 * f["steps/%06d/chambers/gauge_pressure" % k][0]  # kPa
                v = 1e-9 * f["steps/%06d/chambers/volume" % k][0]  # m^3
                for got, want in ((p, float(rows[k]["air_p_kPa"])), (v, float(rows[k]["air_V_m3"]))):
                    worst = max(worst, abs(got - want) / max(abs(want), 1e-30))
            chk.less(worst, 1e-8, "the results' pressure and volume are the history's at every step (largest "
                     "relative difference %.2g)" % worst)
            last = f["steps/%06d/chambers/gauge_pressure" % steps[-1]][0]
            chk.less(abs(last - 0.3e-3) / 0.3e-3, 1e-9, "last step: gauge pressure %.6g MPa, the supplied 0.3 kPa" % last)


if __name__ == "__main__":
    T.main(main_test)
