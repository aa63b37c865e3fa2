"""What -help shows is what a run uses: for every option of the saddle's stretch and mesh sections,
of the patch scene and its mesh and of the hencky and annulus meshes, the default -help prints, given explicitly, must leave the run
exactly as it is without the option (the same progress lines, probe history and report). An array
default cut to its first value (-saddle_part_A <0.> for 0,0,400,400) fails here: given back, it
is a different box or an error. The saddle report compares its Mises values with the material's
first yield stress, whatever -material_yield says."""
import os
import re

from etfe_testlib import Checker, etfe_path, run, scratch_dir

etfe = etfe_path()
chk = Checker("help_defaults")

# "-name <now X : formerly D>", "-name <X : D>" (reals) or "-name <D>": D is the default.
OPTION = re.compile(r"^\s+-(\w+) <(?:now (.*?) : formerly (.*?)|([^:>]*?)(?: : ([^>]*))?)>")
SECTION = re.compile(r"^(\S.*):$")
# What differs between two runs of the same case: wall times and memory.
TIMES = re.compile(r"\s+[\d.]+ s\s+elapsed.*|peak memory.*|resident.*|\d+(\.\d+)? s\b|\d+ kB")


def help_defaults(args, sections):
    """{option: default} of the options -help lists in the sections whose title starts as given."""
    _, out = run(etfe, args + ["-help"])
    defaults, inside = {}, False
    for line in out.splitlines():
        s = SECTION.match(line)
        if s:
            inside = any(s.group(1).startswith(t) for t in sections)
            continue
        m = OPTION.match(line)
        if inside and m:
            now_fmt = m.group(2) is not None
            defaults[m.group(1)] = (m.group(3) if now_fmt else (m.group(5) if m.group(5) is not None else m.group(4))).strip()
    return defaults


def masked_run(args, tmp):
    """Printed lines (times masked) and the probe history of one run; None when it failed."""
    history = os.path.join(tmp, "history.csv")
    if os.path.exists(history):
        os.remove(history)
    rc, out = run(etfe, args, expect_fail=None)
    if rc != 0:
        return None, out
    text = "\n".join(TIMES.sub("", line) for line in out.splitlines())
    if os.path.exists(history):
        text += "\n" + open(history).read()
    return text, out


def check_defaults(name, base, sections, skip, tmp):
    defaults = help_defaults(base, sections)
    chk.check(len(defaults) > 0, "%s: -help lists the options of %s" % (name, ", ".join(sections)))
    reference, out = masked_run(base, tmp)
    chk.check(reference is not None, "%s: the case runs with its defaults%s" % (name, "" if reference else "\n" + out[-800:]))
    for option, default in sorted(defaults.items()):
        if option in skip or default == "":
            continue
        text, out = masked_run(base + ["-" + option, default], tmp)
        same = text is not None and text == reference
        chk.check(same, "%s: -%s %s (the default -help prints) runs as the default does%s"
                  % (name, option, default, "" if same else ": " + (out.strip().splitlines() or [""])[-1][:160]))


with scratch_dir() as tmp:
    history = os.path.join(tmp, "history.csv")
    saddle = ["-options_file", os.path.join("options", "saddle", "stretch_base.opts"), "-mesh_n", 4, "-output", 0,
              "-load_increments", 8, "-load_stop_after", 2, "-load_monitor", 1, "-saddle_history", history,
              "-checkpoint_file", os.path.join(tmp, "saddle.checkpoint.h5")]
    check_defaults("saddle", saddle, ["Saddle stretch fabrication", "Mesh of the saddle scene"],
                   {"mesh_n", "saddle_history", "mesh_file"}, tmp)
    patch = ["-scene", "patch", "-output", 0, "-load_monitor", 1]
    check_defaults("patch", patch, ["Patch scene", "Mesh of the patch scene"], {"mesh_file"}, tmp)
    # The mesh keys of the disc and the annulus (the shared -mesh_* reader), one increment each.
    for scene in ("hencky", "annulus"):
        short = ["-scene", scene, "-output", 0, "-load_monitor", 1, "-load_stop_after", 1,
                 "-checkpoint_file", os.path.join(tmp, scene + ".checkpoint.h5")]
        check_defaults(scene, short, ["Mesh of the %s scene" % scene], set(), tmp)

    # The report's "within 10 % of S_y1" uses the material's first yield.
    short = ["-options_file", os.path.join("options", "saddle", "stretch_base.opts"), "-mesh_n", 4, "-output", 0,
             "-load_increments", 4, "-load_monitor", 0] + sum((["-saddle_draw_" + p, 5] for p in "abcd"), [])
    for yields, shown in (([], "13.28"), (["-material_yield", "3,25"], "3")):
        _, out = run(etfe, short + yields)
        chk.check("within 10%% of S_y1 = %s:" % shown in out,
                  "the saddle report compares with the first yield %s (%s)" % (shown, " ".join(yields) or "default"))
chk.finish()
