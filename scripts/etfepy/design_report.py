"""The design run's tables (CSV) and its report: one self-contained HTML file (styles inline, the
pictures inline SVG, no script and nothing fetched), docs/design-run.md."""
import csv
import html
import math

import numpy as np

from .envelope import ENVELOPES, finite

COMBINATION_COLUMNS = [
    ("combination", ""), ("situation", ""), ("loads", ""), ("status", ""), ("duration", ""), ("temperature", "C"),
    ("design_resistance", "MPa"),
    ("max_utilisation", "1"),
    ("utilisation_place", ""), ("max_principal_stress", "MPa"), ("max_deflection", "mm"),
    ("max_plastic_strain", "1"), ("wrinkled_elements", "1"), ("increments", "1"), ("newton_iterations", "1"),
    ("cutbacks", "1"), ("wall", "s"), ("steps", "1"), ("reactions", "N"), ("chamber_pressures", "kPa"),
    ("cable_forces", "N"), ("warnings", "")]
CABLE_COLUMNS = [("cable", ""), ("max_force", "N"), ("combination", ""), ("segment", "")]
GROUP_COLUMNS = [("quantity", ""), ("max", "unit"), ("max_combination", ""), ("max_increment", ""), ("min", "unit"),
                 ("min_combination", ""), ("min_increment", ""), ("unit", "")]
CHECK_COLUMNS = [("check", ""), ("combination", ""), ("situation", ""), ("value", "unit"), ("limit", "unit"),
                 ("unit", ""), ("verdict", ""), ("place", "")]


def number(x, digits=4):
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    return "%.*g" % (digits, x)


def header(cols):
    return ["%s [%s]" % (c, u) if u and u != "unit" else c for c, u in cols]


def write_csv(path, cols, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header(cols))
        for r in rows:
            w.writerow([number(r.get(c, ""), 8) if not isinstance(r.get(c, ""), str) else r.get(c, "") for c, _ in cols])


def colour(t):
    """A blue-green-yellow-red ramp for t in [0, 1]."""
    t = min(max(t, 0.0), 1.0)
    stops = [(0.0, (49, 54, 149)), (0.35, (69, 170, 190)), (0.65, (230, 220, 90)), (1.0, (200, 30, 40))]
    for (a, ca), (b, cb) in zip(stops, stops[1:]):
        if t <= b:
            s = (t - a) / (b - a)
            return "rgb(%d,%d,%d)" % tuple(int(ca[i] + s * (cb[i] - ca[i])) for i in range(3))
    return "rgb(200,30,40)"


PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
           "#17becf"]


def plan_svg(X, tri, values, title, unit, categories=None, lo=None, hi=None, width=420, order=None):
    """The film in plan (x, y) coloured per element (values) or per category (categories: names,
    values their indices); a legend beside it. Elements are drawn in ascending order of `order`
    (default: the values), so where layers overlap in plan (a cushion's foils) the largest shows."""
    x, y = X[:, 0], X[:, 1]
    x0, x1, y0, y1 = x.min(), x.max(), y.min(), y.max()
    s = (width - 20) / max(x1 - x0, y1 - y0, 1e-12)
    h = int((y1 - y0) * s) + 20
    parts = []
    vmin = float(np.min(values)) if lo is None else lo
    vmax = float(np.max(values)) if hi is None else hi
    for e in np.argsort(values if order is None else order, kind="stable"):
        t = tri[e]
        pts = " ".join("%.1f,%.1f" % (10 + (x[n] - x0) * s, 10 + (y1 - y[n]) * s) for n in t)
        if categories is not None:
            c = PALETTE[int(values[e]) % len(PALETTE)]
        else:
            c = colour((values[e] - vmin) / (vmax - vmin) if vmax > vmin else 0.5)
        parts.append('<polygon points="%s" fill="%s" stroke="%s" stroke-width="0.3"/>' % (pts, c, c))
    legend = []
    if categories is not None:
        for k, name in enumerate(categories):
            legend.append('<div><span class="sw" style="background:%s"></span>%s</div>'
                          % (PALETTE[k % len(PALETTE)], html.escape(name)))
    else:
        legend.append('<div class="ramp"></div><div>%s to %s %s</div>' % (number(vmin), number(vmax), html.escape(unit)))
    return ('<figure><figcaption>%s</figcaption><svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
            'viewBox="0 0 %d %d">%s</svg><div class="legend">%s</div></figure>'
            % (html.escape(title), width, h, width, h, "".join(parts), "".join(legend)))


STYLE = """
body{font-family:sans-serif;margin:1.5em;color:#222}table{border-collapse:collapse;margin:0.5em 0 1.5em}
td,th{border:1px solid #bbb;padding:3px 6px;font-size:13px;text-align:left;vertical-align:top}
th{background:#eee}.pass{background:#d8f0d8}.FAIL,.notconverged{background:#f6c8c8;font-weight:bold}
figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}figcaption{font-weight:bold}
.sw{display:inline-block;width:12px;height:12px;margin-right:4px}.legend{font-size:12px}
.ramp{width:200px;height:10px;background:linear-gradient(90deg,rgb(49,54,149),rgb(69,170,190),rgb(230,220,90),rgb(200,30,40))}
.warn{color:#a33}
"""


def table(cols, rows, table_id, verdict_col=None):
    out = ['<table id="%s"><tr>%s</tr>' % (table_id, "".join("<th>%s</th>" % html.escape(h) for h in header(cols)))]
    for r in rows:
        cells = []
        for c, unit in cols:
            v = r.get(c, "")
            shown = number(v)
            if unit == "unit" and shown != "-" and str(r.get("unit", "")) not in ("", "1"):
                shown += " " + str(r.get("unit", ""))
            cls = ' class="%s"' % str(v).replace(" ", "") if c == verdict_col else ""
            cells.append("<td%s>%s</td>" % (cls, html.escape(shown)))
        out.append("<tr>%s</tr>" % "".join(cells))
    out.append("</table>")
    return "\n".join(out)


def write_html(path, design, summary, comb_rows, check_rows, X, tri, env, names, missing, groups=(), cables=()):
    overall = "PASS" if check_rows and all(r["verdict"] == "pass" for r in check_rows) and not missing else "FAIL"
    if not check_rows:
        overall = "NO CHECKS"
    r = design.resistance
    body = ["<h1>%s</h1>" % html.escape(design.title),
            '<p id="overall" class="%s">Overall verdict: <b>%s</b>%s</p>'
            % (overall, overall, " (envelopes incomplete: %s did not converge)" % ", ".join(missing) if missing else ""),
            "<h2>Model</h2><table id='model'>"]
    for k, v in summary:
        body.append("<tr><th>%s</th><td>%s</td></tr>" % (html.escape(k), html.escape(str(v))))
    body.append("</table>")
    body.append("<h2>Resistance model</h2><p>f_d = f_k(duration, temperature) / &gamma;_M per material, each element "
                "taking its surface group's material at the combination's duration class and temperature (column "
                "design_resistance of the combinations); f_k linear in temperature between the tabulated ones; "
                "design stress: %s. Source: %s</p>" % (html.escape(r.stress), html.escape(r.source)))
    body.append(table([("material", ""), ("groups", ""), ("gamma_M", "1"), ("f_k", "")],
                      [dict(material=m, groups=g, gamma_M=gm, f_k=t) for m, g, gm, t in r.describe()], "resistance"))
    body.append("<h2>Verdicts</h2>")
    body.append(table(CHECK_COLUMNS, check_rows, "verdicts", "verdict"))
    body.append("<h2>Combinations</h2><p>Each combination is its own nonlinear run from the base state (%s), its "
                "loads applied together in one stage.</p>" % html.escape(design.base_note or "the base stages"))
    body.append(table(COMBINATION_COLUMNS, comb_rows, "combinations"))
    body.append("<h2>Envelopes</h2><p>Over every written step of each combination's own stage (after the base): "
                "the stage end and every -output_every-th increment (column steps), not the increments between "
                "written steps.</p>")
    if env:
        u, ug = env["utilisation"]
        u = np.nan_to_num(u, nan=0.0)  # NaN: no combination with a duration class
        body.append(plan_svg(X, tri, u, "Utilisation envelope (plan)", "", lo=0.0, hi=max(1.0, float(u.max()))))
        body.append(plan_svg(X, tri, ug, "Governing combination of the utilisation (where it is largest in plan)", "",
                             categories=names, order=u))
        w, _ = env["wrinkle_state"]
        body.append(plan_svg(X, tri, w, "Wrinkle state envelope (0 taut, 1 wrinkled, 2 slack)", "", lo=0.0, hi=2.0))
        d, _ = env["deflection"]
        dc = d[tri].mean(axis=1)
        body.append(plan_svg(X, tri, dc, "Deflection from the base state, envelope", "mm"))
        rows = []
        for name, (vals, idx) in env.items():
            where, how, unit, desc = ENVELOPES[name]
            if name.endswith("governing"):
                continue
            if np.all(np.isnan(vals)):
                continue
            i = int(np.nanargmax(vals) if how == "max" else np.nanargmin(vals))
            rows.append(dict(field=name, extreme="%s %s %s" % (how, number(vals[i]), unit), where="%s %d" % (where, i),
                             governing=names[int(idx[i])], description=desc))
        body.append(table([("field", ""), ("extreme", ""), ("where", ""), ("governing", ""), ("description", "")],
                          rows, "envelopes"))
    else:
        body.append("<p class='FAIL'>No combination completed: no envelope.</p>")
    if groups:
        body.append("<h3>Reactions per support group and chamber pressures</h3><p>Over every increment of each "
                    "combination's stage (the history CSV's rows), with the combination and increment giving "
                    "each extreme.</p>")
        body.append(table(GROUP_COLUMNS, groups, "groups"))
    if cables:
        body.append("<h3>Largest cable force per cable</h3>")
        body.append(table(CABLE_COLUMNS, cables, "cables"))
    doc = ('<!DOCTYPE html><html><head><meta charset="utf-8"><title>%s</title><style>%s</style></head><body>%s'
           '</body></html>\n' % (html.escape(design.title), STYLE, "\n".join(body)))
    with open(path, "w") as f:
        f.write(doc)
    return overall
