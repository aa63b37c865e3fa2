"""One parser per kind of line that etfe prints (the formats are in src/app/etfe.cpp, run summary
and header; src/solver/load_stepper.cpp, progress and cut-back lines; src/scenes/*.cpp, the scene
reports), and for the PETSc -log_view / -memory_view tables and error messages the benchmarks and
tests read. Each parser takes the whole output of a run and returns plain numbers; a line that is
not there gives None (or an empty list), so the caller decides whether that is a failure.
"""
import math
import re

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?(?:inf|nan)"
N = "(%s)" % NUMBER

# etfe: completed after 200 increments (load time 4), 583 Newton iterations, 0 cut-backs, 1.571 s
SUMMARY = re.compile(r"etfe: (completed|stopped as asked|STOPPED) after (\d+) increments \(load time %s\), "
                     r"(\d+) Newton iterations, (\d+) cut-backs, %s s" % (N, N))
# step     1/40   2.5%  t 0.05000  stage 1/2 tension 0.05  newton  2  |R| 6.18e-11  contact open 0 stick 0
#   slip 325 (3 lift-offs since the last line)  work 1.0e+00 N mm shift 1.0e-01 (1.0e-01 of it)  cut-backs 1
#   0.01 s  elapsed 0:00:00  ETA 0:00:00     (contact, work and cut-backs only when they apply)
PROGRESS = re.compile(
    r"^step +(\d+)/(\d+) +%s%% +t +%s +stage (\d+)/(\d+) ?(.*?) +newton +(\d+) +\|R\| %s"
    r"(?: +contact open (\d+) stick (\d+) slip (\d+)(?: \((\d+) lift-offs since the last line\))?)?"
    r"(?: +work %s N mm shift %s \(%s of it\))?(?: +cut-backs (\d+))? +%s s +elapsed"
    % (N, N, N, N, N, N, N), re.M)
# step    12  t  0.55000 -> 0.60000 failed: DIVERGED_LINE_SEARCH; cutting back to dt 2.500e-02
CUTBACK = re.compile(r"^step +(\d+) +t +%s -> %s failed: (.*); cutting back to dt %s" % (N, N, N), re.M)
HEADER = {
    "scene": re.compile(r"^etfe: scene (\S+)", re.M),
    "mesh": re.compile(r"^  mesh: (.*), (\d+) nodes, (\d+) triangles, (\d+) DOF", re.M),
    "ranks": re.compile(r"^  ranks: (\d+) \(METIS\), elements per rank (\d+)-(\d+), owned nodes per rank "
                        r"(\d+)-(\d+) \(imbalance %s\)" % N, re.M),
    "share": re.compile(r"^  set-up: rank 0 built the scene and sent each rank its share: (\d+) kB \(max\), "
                        r"(\d+) kB \(min\)", re.M),
}
KEY_VALUE = re.compile(r"([A-Za-z_][\w]*(?:\([^)]*\))?)\s*=\s*(%s)" % NUMBER)
SNES_NORM = re.compile(r"^\s*(\d+) SNES Function norm %s" % N)
# PETSc -log_view event row: name, count, ratio, time, ratio, flop, ratio, messages, length, reductions
EVENT = re.compile(r"^([A-Za-z][A-Za-z0-9_]*)\s+(\d+)\s+[0-9.]+\s+([0-9.eE+-]+)\s+[0-9.]+\s+([0-9.eE+-]+)\s+[0-9.]+"
                   r"\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)\s")
MEMORY = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)\s+min\s+(\S+)")


def _num(s):
    return float(s) if s is not None else None


def summary(out):
    """The run's summary line as dict(end, completed, increments, time, newton, cutbacks, wall)
    (end: "completed", "stopped as asked" or "STOPPED"), or None when it was not printed."""
    m = SUMMARY.search(out)
    if not m:
        return None
    return dict(end=m.group(1), completed=m.group(1) == "completed", increments=int(m.group(2)),
                time=float(m.group(3)), newton=int(m.group(4)), cutbacks=int(m.group(5)), wall=float(m.group(6)))


def progress(out):
    """The progress lines (-load_monitor 1), one dict per converged increment: step, nominal, t,
    stage (numbered from 1, as printed), stages, what, newton, residual, seconds; contact open,
    stick, slip, lift_offs (with contact, else None); work, shift_work, shift_fraction (with a
    tangent shift, else None); cutbacks (0 unless printed); span, where the line is in out."""
    res = []
    for m in PROGRESS.finditer(out):
        g = m.groups()
        res.append(dict(step=int(g[0]), nominal=int(g[1]), t=float(g[3]), stage=int(g[4]), stages=int(g[5]),
                        what=g[6], newton=int(g[7]), residual=float(g[8]),
                        open=_int(g[9]), stick=_int(g[10]), slip=_int(g[11]), lift_offs=_int(g[12]) or 0,
                        work=_num(g[13]), shift_work=_num(g[14]), shift_fraction=_num(g[15]),
                        cutbacks=_int(g[16]) or 0, seconds=float(g[17]), span=m.span()))
    return res


def _int(s):
    return int(s) if s is not None else None


def cutbacks(out):
    """Each failed attempt (monitor on): dict(step, t, t_new, why, dt)."""
    return [dict(step=int(m.group(1)), t=float(m.group(2)), t_new=float(m.group(3)), why=m.group(4),
                 dt=float(m.group(5))) for m in CUTBACK.finditer(out)]


def header(out):
    """The set-up lines: dict(scene, mesh, nodes, triangles, dofs, ranks, elements_per_rank,
    owned_per_rank, imbalance, share_kb); keys of lines not printed are missing."""
    d = {}
    m = HEADER["scene"].search(out)
    if m:
        d["scene"] = m.group(1)
    m = HEADER["mesh"].search(out)
    if m:
        d.update(mesh=m.group(1), nodes=int(m.group(2)), triangles=int(m.group(3)), dofs=int(m.group(4)))
    m = HEADER["ranks"].search(out)
    if m:
        d.update(ranks=int(m.group(1)), elements_per_rank=(int(m.group(2)), int(m.group(3))),
                 owned_per_rank=(int(m.group(4)), int(m.group(5))), imbalance=float(m.group(6)))
    m = HEADER["share"].search(out)
    if m:
        d["share_kb"] = (int(m.group(1)), int(m.group(2)))
    return d


def value(out, key):
    """The first `key = number` of the output (lines without a scene prefix such as `mu_eff = ...`,
    `neck_radius = ...`), or None."""
    m = re.search(r"(?<![\w(])%s = (%s)" % (re.escape(key), NUMBER), out)
    return float(m.group(1)) if m else None


FORMFIND = re.compile(r"formfind: converged after (\d+) iterations")


def formfind_iterations(out):
    """Iterations of a converged form finding (`formfind: converged after N iterations`), or None."""
    m = FORMFIND.search(out)
    return int(m.group(1)) if m else None


def numbers(text):
    """Every `key = number` pair of a line, in order: [(key, value, printed)]."""
    return [(m.group(1), float(m.group(2)), m.group(2)) for m in KEY_VALUE.finditer(text)]


def scene_lines(out, scene):
    """The lines a scene prints (`<scene>: ...`), without the prefix."""
    pre = scene + ":"
    return [l[len(pre):].strip() for l in out.splitlines() if l.startswith(pre)]


def scene_values(out, scene, printed=False):
    """{tag: {key: value}} from the scene's lines; tag is the line's first word.

    `hencky: centre_deflection = 2.6e+01 mm, closed_form = 2.59e+01 mm, relative_error = 9.2e-04`
    gives values["centre_deflection"] = {"centre_deflection": 26.0, "closed_form": 25.9,
    "relative_error": 9.2e-4}. With printed=True the values are the printed strings.
    """
    res = {}
    for line in scene_lines(out, scene):
        m = re.match(r"(\w+)", line)
        if not m:
            continue
        d = res.setdefault(m.group(1), {})
        for k, v, s in numbers(line):
            d[k] = s if printed else v
    return res


SADDLE = {
    "parts": re.compile(r"saddle: part_A mises = %s MPa \(PK2; Exx %s, Eyy %s, Exy %s\); part_B mises = %s MPa "
                        r"\(Exx %s, Eyy %s, Exy %s\)" % ((N,) * 8)),
    "elements": re.compile(r"saddle: element_I emin = %s smin = %s MPa; element_II emin = %s smin = %s MPa" % ((N,) * 4)),
    "wrinkled": re.compile(r"saddle: wrinkled elements: strain-based = %s, stress-based = %s; max plastic_strain_eq = "
                           r"%s; max [^=;]*slide[^=;]* = %s mm" % ((N,) * 4)),
}
SADDLE_KEYS = {
    "parts": ("A_mises", "A_Exx", "A_Eyy", "A_Exy", "B_mises", "B_Exx", "B_Eyy", "B_Exy"),
    "elements": ("I_emin", "I_smin", "II_emin", "II_smin"),
    "wrinkled": ("wrinkled_strain", "wrinkled_stress", "max_plastic_strain_eq", "max_arch_slide"),
}


def saddle_report(out, printed=False):
    """The saddle stretch's report at the end of a run: A_mises (PK2, MPa), A_Exx, A_Eyy, A_Exy and
    the same for B; I_emin, I_smin, II_emin, II_smin (elements I and II); wrinkled_strain,
    wrinkled_stress (element counts), max_plastic_strain_eq, max_arch_slide (mm, along the arch).
    The last report of the output counts; keys of lines not printed are missing."""
    d = {}
    for kind, rx in SADDLE.items():
        found = rx.findall(out)
        if found:
            d.update(zip(SADDLE_KEYS[kind], found[-1] if printed else map(float, found[-1])))
    return d


PATCH_RANGES = re.compile(r"patch: Sxx in \[%s, %s\], Syy in \[%s, %s\](?:, Sxy in \[%s, %s\])?" % ((N,) * 6))


def patch_ranges(out, printed=False):
    """The patch scene's stress ranges {"Sxx": (lo, hi), "Syy": ..., "Sxy": ...} (MPa), or None."""
    m = PATCH_RANGES.search(out)
    if not m:
        return None
    g = [x if printed or x is None else float(x) for x in m.groups()]
    return {k: (g[2 * j], g[2 * j + 1]) for j, k in enumerate(("Sxx", "Syy", "Sxy")) if g[2 * j] is not None}


CUTPATTERN = {
    "links": re.compile(r"^cutpattern: strip (\w+): .* link error max %s rms %s" % (N, N), re.M),
    "outline": re.compile(r"^cutpattern: strip (\w+) outline: 3D %s mm, 2D %s mm, expansion %s %%" % (N, N, N), re.M),
    "line": re.compile(r"^cutpattern: strip (\w+) line (\w+): 3D %s mm, 2D %s mm, expansion %s %%" % (N, N, N), re.M),
}


def cutpattern_report(out, printed=False):
    """The flattening report per strip: {strip: dict(link_max, link_rms, outline=(3D, 2D, expansion %),
    lines={name: (3D, 2D, expansion %)})}; lengths in mm, errors relative."""
    conv = (lambda x: x) if printed else float
    res = {}
    strip = lambda name: res.setdefault(name, dict(lines={}))
    for m in CUTPATTERN["links"].finditer(out):
        strip(m.group(1)).update(link_max=conv(m.group(2)), link_rms=conv(m.group(3)))
    for m in CUTPATTERN["outline"].finditer(out):
        strip(m.group(1))["outline"] = tuple(map(conv, m.groups()[1:]))
    for m in CUTPATTERN["line"].finditer(out):
        strip(m.group(1))["lines"][m.group(2)] = tuple(map(conv, m.groups()[2:]))
    return res


def snes_histories(out):
    """Residual norms of every SNES solve (from -snes_monitor), one list per solve, in order."""
    hist = []
    for l in out.splitlines():
        m = SNES_NORM.match(l)
        if not m:
            continue
        if int(m.group(1)) == 0:
            hist.append([])
        hist[-1].append(float(m.group(2)))
    return hist


SLIDE = re.compile(r"saddle: slide_(\d+) \(Y = (?:%s)\) X = %s mm, Y = %s mm" % (NUMBER, N, N))


def saddle_slides(out):
    """|slide| = hypot(X, Y) [mm] of the report's `saddle: slide_k (Y = ..) X = .. mm, Y = .. mm`, I..V."""
    found = SLIDE.findall(out)
    return [math.hypot(float(x), float(y)) for _, x, y in sorted(found, key=lambda s: int(s[0]))]


STABILIZED = re.compile(r"etfe: (\d+) increments stabilized .*?\(%s of the work done on the film\)" % N)


def stabilized(out):
    """(increments, work fraction) of the stabilization summary (`etfe: N increments stabilized ...`);
    (0, None) when no increment needed it."""
    m = STABILIZED.search(out)
    return (int(m.group(1)), float(m.group(2))) if m else (0, None)


FAILED_INCREMENT = re.compile(r"increment (\d+) \(.*?\) did not converge after \d+ cut-backs: (.*?)"
                              r"(?:\. The last converged|$)", re.M)


def failed_increment(out):
    """(increment, reason) of a run that stopped on an increment that would not converge; else
    (None, the first line of the error message or None)."""
    m = FAILED_INCREMENT.search(out)
    if m:
        return int(m.group(1)), m.group(2).strip()
    return None, first_error(out) or None


def error_message(out):
    """The lines of a PETSc error message that say what went wrong: no trace (#n ... or the
    concise "(raised in f() at file:line ...)"), no "Option left" warnings, no option table, no
    version/configure banner."""
    keep, in_table = [], False
    for l in out.splitlines():
        m = re.match(r"\[\d+\]PETSC ERROR: (.*)", l)
        if not m:
            continue
        t = m.group(1)
        if t.startswith("PETSc Option Table entries"):
            in_table = True
            continue
        if "End of Error Message" in t or "Error Message" in t:
            in_table = False
            continue
        if in_table or t.startswith("#") or t.startswith("Option left") or \
                t.strip().startswith("(raised in ") or \
                "Configure options" in t or t.startswith("Petsc Release") or \
                t.startswith("See https") or (" on a " in t and " named " in t) or \
                t.startswith("WARNING! There are option"):
            continue
        keep.append(t)
    return "\n".join(keep)


def first_error(out):
    """The first line of the PETSc error message, or ""."""
    lines = [l for l in error_message(out).splitlines() if l.strip()]
    return lines[0].strip() if lines else ""


def petsc_events(out):
    """{event: dict(count, time, flop, mess, avglen, reduct)} of a -log_view table (first row of each)."""
    ev = {}
    for line in out.splitlines():
        m = EVENT.match(line)
        if m and m.group(1) not in ev:
            ev[m.group(1)] = dict(count=int(m.group(2)), time=float(m.group(3)), flop=float(m.group(4)),
                                  mess=float(m.group(5)), avglen=float(m.group(6)), reduct=float(m.group(7)))
    return ev


def petsc_memory(out):
    """(total, max, min) bytes of -memory_view's peak process memory over the run, or None."""
    m = MEMORY.search(out)
    return tuple(float(x) for x in m.groups()) if m else None


def tail(out, n=40):
    """The last n lines of a run's output without PETSc's configure-options noise."""
    lines = [l for l in out.splitlines() if "Configure options" not in l]
    return "\n".join(lines[-n:])


# /usr/bin/time -v, in front of a benchmark run
TIME_V = {"maxrss_kb": re.compile(r"Maximum resident set size \(kbytes\): (\d+)"),
          "user": re.compile(r"User time \(seconds\): ([0-9.]+)"),
          "system": re.compile(r"System time \(seconds\): ([0-9.]+)")}


def run_log(out):
    """Everything a benchmark reads from one run's log: header (nodes, triangles, dofs), summary
    (end, increments, newton, cutbacks, solve_wall), steps (progress()), events (petsc_events()),
    mem_total, mem_max, mem_min (-memory_view, bytes), maxrss_kb and cpu (/usr/bin/time -v, s),
    error (first line of a PETSc error message, or ""). Keys of what was not printed are missing."""
    d = {k: v for k, v in header(out).items() if k in ("nodes", "triangles", "dofs")}
    s = summary(out)
    if s:
        d.update(end=s["end"], increments=s["increments"], newton=s["newton"], cutbacks=s["cutbacks"],
                 solve_wall=s["wall"])
    d["steps"] = progress(out)
    d["events"] = petsc_events(out)
    mem = petsc_memory(out)
    if mem:
        d["mem_total"], d["mem_max"], d["mem_min"] = mem
    m = TIME_V["maxrss_kb"].search(out)
    if m:
        d["maxrss_kb"] = int(m.group(1))
    u, s = TIME_V["user"].search(out), TIME_V["system"].search(out)
    if u and s:
        d["cpu"] = float(u.group(1)) + float(s.group(1))
    d["error"] = first_error(out)
    return d
