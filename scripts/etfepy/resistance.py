"""The design run's resistance model, given as data (docs/design-run.md): per material (a foil grade
and thickness) the characteristic strength at each load-duration class and temperature and a
material factor, in CEN/TS 19102's shape

    f_d = f_k(duration, temperature) / gamma_M,

and which material each surface group is. A combination states its duration class and temperature
(or its load cases do); each element's utilisation is its design stress over its own group's f_d
for that combination.
"""
import numpy as np

# Example values for demonstration only: NOT the values of CEN/TS 19102:2023.
EXAMPLE_SOURCE = (
    "example values for demonstration only, not those of CEN/TS 19102:2023: f_k 21 MPa (short, 23 C) is near the "
    "lower end of ETFE's second yield point at 23 C (21-25 MPa, Surholt, Uhlemann, Stranghoener, Polymers 14 (2022) "
    "3156); the reductions for medium (0.9) and long (0.75) loads and to 0.7 at 50 C are illustrative, and so is "
    "gamma_M 1.2. Give your own with their source.")
EXAMPLE_MATERIAL = "ETFE example"
EXAMPLE_RESISTANCE = {
    "stress": "cauchy_mises",
    "durations": ["short", "medium", "long"],
    "reference_temperature": 23.0,
    "materials": {EXAMPLE_MATERIAL: {
        "gamma_M": 1.2,
        "f_k": {"short": {"23": 21.0, "50": 14.7}, "medium": {"23": 18.9, "50": 13.23},
                "long": {"23": 15.75, "50": 11.025}}}},
    "source": EXAMPLE_SOURCE,
}


class ResistanceError(Exception):
    pass


def _positive(x, what):
    try:
        v = float(x)
    except (TypeError, ValueError):
        raise ResistanceError("%s is %r, not a number" % (what, x))
    if not v > 0 or not np.isfinite(v):
        raise ResistanceError("%s is %s: it must be a positive number" % (what, x))
    return v


class Resistance:
    """data: the design file's "resistance" (None: the example). Older files' single material
    {f_k, k_mod: {duration: factor}, gamma_M} is read as f_k(d) = f_k k_mod(d) at any temperature up
    to the reference one."""

    def __init__(self, data=None):
        data = dict(EXAMPLE_RESISTANCE if data is None else data)
        self.stress = data.get("stress", "cauchy_mises")
        if self.stress not in ("cauchy_mises", "max_principal_stress"):
            raise ResistanceError("resistance stress %r: cauchy_mises or max_principal_stress" % self.stress)
        self.source = data.get("source", "")
        self.durations = list(data.get("durations", ["short", "medium", "long"]))
        self.reference_temperature = float(data.get("reference_temperature", 23.0))
        if "materials" in data:
            mats = data["materials"]
        elif "f_k" in data:  # one material, k_mod per duration
            kmod = data.get("k_mod", 1.0)
            kmod = kmod if isinstance(kmod, dict) else {d: kmod for d in self.durations}
            f_k = _positive(data["f_k"], "resistance f_k")
            t_ref = repr(self.reference_temperature)
            mats = {"film": {"gamma_M": data.get("gamma_M"),
                             "f_k": {d: {t_ref: f_k * _positive(k, "resistance k_mod %s" % d)} for d, k in kmod.items()}}}
        else:
            raise ResistanceError("resistance: give materials {name: {f_k: {duration: {temperature C: MPa}}, "
                                  "gamma_M}} (docs/design-run.md)")
        if not isinstance(mats, dict) or not mats:
            raise ResistanceError("resistance materials: give at least one material")
        self.materials = {}
        for name, m in mats.items():
            gm = _positive(m.get("gamma_M"), "resistance material %s: gamma_M" % name)
            table = m.get("f_k")
            if not isinstance(table, dict) or not table:
                raise ResistanceError("resistance material %s: f_k must be {duration: {temperature C: MPa}}" % name)
            rows = {}
            for d, by_t in table.items():
                if d not in self.durations:
                    raise ResistanceError("resistance material %s: duration class %r is not one of durations %s"
                                          % (name, d, self.durations))
                if not isinstance(by_t, dict) or not by_t:
                    by_t = {repr(self.reference_temperature): by_t}
                pts = sorted((float(t), _positive(v, "resistance material %s: f_k %s at %s C" % (name, d, t)))
                             for t, v in by_t.items())
                rows[d] = pts
            self.materials[name] = dict(gamma_M=gm, f_k=rows)
        self.groups = dict(data.get("groups", {}))
        for g, mname in self.groups.items():
            if mname not in self.materials:
                raise ResistanceError("resistance groups: surface group %s is given material %r, which is not one of "
                                      "materials %s" % (g, mname, sorted(self.materials)))
        self.default = data.get("default_material")
        if self.default is None and len(self.materials) == 1:
            self.default = next(iter(self.materials))
        if self.default is not None and self.default not in self.materials:
            raise ResistanceError("resistance default_material %r is not one of materials %s"
                                  % (self.default, sorted(self.materials)))

    def combination_class(self, comb, cases):
        """(duration class, temperature C, where each came from) of a combination: its own, else from its
        load cases (the shortest duration among them, as k_mod takes the shortest action's in EN 1995-1-1
        3.1.3(2); the highest temperature), else no duration (None) and the reference temperature."""
        dur, dsrc = comb.get("duration"), "combination"
        active = [c for c, f in comb["factors"].items() if f != 0]
        if dur is None:
            given = [cases[c]["duration"] for c in active if cases[c].get("duration") is not None]
            for d in given:
                if d not in self.durations:
                    raise ResistanceError("combination %s: a load case's duration %r is not one of %s"
                                          % (comb["name"], d, self.durations))
            if given:
                dur, dsrc = min(given, key=self.durations.index), "load cases"
        elif dur not in self.durations:
            raise ResistanceError("combination %s: duration %r is not one of the resistance's durations %s"
                                  % (comb["name"], dur, self.durations))
        temp, tsrc = comb.get("temperature"), "combination"
        if temp is None:
            given = [float(cases[c]["temperature"]) for c in active if cases[c].get("temperature") is not None]
            temp, tsrc = (max(given), "load cases") if given else (self.reference_temperature, "reference")
        return dur, float(temp), "%s; %s" % (dsrc, tsrc)

    def design_strength(self, material, duration, temperature, where):
        """f_d of a material: f_k interpolated linearly in temperature between the tabulated ones (below
        the lowest: the lowest's, which is on the safe side where strength falls as it warms; above the
        highest: refused), over gamma_M."""
        m = self.materials[material]
        if duration is None:
            raise ResistanceError("%s: no duration class: give the combination (or its load cases) a duration, "
                                  "one of %s" % (where, self.durations))
        if duration not in m["f_k"]:
            raise ResistanceError("%s: material %s has no strength for duration class %r (it has %s)"
                                  % (where, material, duration, sorted(m["f_k"])))
        pts = m["f_k"][duration]
        ts = [t for t, _ in pts]
        if temperature > ts[-1]:
            raise ResistanceError("%s: temperature %g C is above material %s's highest for %s loads (%g C): give its "
                                  "strength there" % (where, temperature, material, duration, ts[-1]))
        f_k = float(np.interp(temperature, ts, [v for _, v in pts]))
        return f_k / m["gamma_M"], f_k

    def element_materials(self, groups):
        """[material name per element] from {surface group: element mask} ("all" included)."""
        n = len(groups["all"])
        mat = np.array([None] * n, dtype=object)
        first = np.array([None] * n, dtype=object)
        for g, mname in self.groups.items():
            if g not in groups:
                raise ResistanceError("resistance groups: surface group %s is not in the mesh (its groups: %s)"
                                      % (g, ", ".join(sorted(groups))))
            m = groups[g]
            clash = m & (mat != None) & (mat != mname)  # noqa: E711
            if clash.any():
                e = int(np.argmax(clash))
                raise ResistanceError("resistance groups: element %d is in groups %s (%s) and %s (%s): give it one "
                                      "material" % (e, first[e], mat[e], g, mname))
            first[m & (mat == None)] = g  # noqa: E711
            mat[m] = mname
        rest = mat == None  # noqa: E711
        if rest.any():
            if self.default is None:
                raise ResistanceError("resistance: %d elements are in no group of resistance groups (%s) and there "
                                      "is no default_material" % (int(rest.sum()), ", ".join(self.groups)))
            mat[rest] = self.default
        return mat

    def element_strengths(self, materials, comb, cases):
        """(f_d per element, {material: (f_d, f_k)}, duration, temperature, source) for a combination."""
        dur, temp, src = self.combination_class(comb, cases)
        where = "combination %s" % comb["name"]
        per = {m: self.design_strength(m, dur, temp, where) for m in sorted(set(materials))}
        return np.array([per[m][0] for m in materials]), per, dur, temp, src

    def describe(self):
        """One line per material for the report."""
        out = []
        for name, m in self.materials.items():
            groups = [g for g, mm in self.groups.items() if mm == name]
            if name == self.default:
                groups.append("every other element" if self.groups else "every element")
            table = "; ".join("%s: %s" % (d, ", ".join("%g C %g MPa" % tv for tv in pts))
                              for d, pts in m["f_k"].items())
            out.append((name, ", ".join(groups) or "-", m["gamma_M"], table))
        return out
