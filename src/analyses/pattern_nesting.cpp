// Nesting of the strips on a roll (see etfe/analyses/pattern_sheet.h): each strip at its least width,
// first-fit decreasing shelves along the roll. Simple and honest: strips never interlock (each
// keeps its box), so the waste is what boxes leave; a real nesting program does better on
// curved strips.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "etfe/analyses/pattern_sheet.h"

namespace etfe {
namespace {

const double kPi = 3.14159265358979323846;

double Cross(const double *o, const double *a, const double *b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Convex hull (Andrew's monotone chain), counter-clockwise, 2 per point.
std::vector<double> Hull(const std::vector<double> &pts) {
  std::vector<std::pair<double, double>> p;
  for (size_t k = 0; k + 1 < pts.size(); k += 2) p.push_back({pts[k], pts[k + 1]});
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return pts;
  std::vector<std::pair<double, double>> h(2 * p.size());
  size_t k = 0;
  auto cross = [](const std::pair<double, double> &o, const std::pair<double, double> &a,
                  const std::pair<double, double> &b) {
    const double O[2] = {o.first, o.second}, A[2] = {a.first, a.second}, B[2] = {b.first, b.second};
    return Cross(O, A, B);
  };
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  std::vector<double> out;
  for (size_t i = 0; i + 1 < k; ++i) out.push_back(h[i].first), out.push_back(h[i].second);
  return out;
}

double Area(const std::vector<double> &p) {
  double a = 0;
  const size_t n = p.size() / 2;
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    a += p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1];
  }
  return 0.5 * a;
}

void Turn(std::vector<double> *p, double c, double s, double dx, double dy) {
  for (size_t k = 0; k + 1 < p->size(); k += 2) {
    const double x = (*p)[k], y = (*p)[k + 1];
    (*p)[k] = c * x - s * y + dx, (*p)[k + 1] = s * x + c * y + dy;
  }
}

} // namespace

bool NestOnRoll(const std::vector<NestItem> &items, const PatternDrawing &drawing, double roll_width, double gap,
                NestResult *out, Sheet *sheet, std::string *err) {
  *out = NestResult();
  std::vector<Sheet> parts;
  std::vector<NestPlacement> pl;
  for (const NestItem &it : items) {
    PatternDrawing d = drawing;
    d.labels = false;
    Sheet part = PatternSheet(*it.result, it.name, d);
    std::vector<double> cut;  // every point of the cut outline(s)
    double area = 0;
    for (const SheetPolyline &p : part.lines)
      if (p.layer == "OUTLINE") cut.insert(cut.end(), p.pts.begin(), p.pts.end()), area += Area(p.pts);
    // The least width: across one of the hull's edges (rotating calipers).
    const std::vector<double> h = Hull(cut);
    const size_t n = h.size() / 2;
    NestPlacement best;
    best.width = HUGE_VAL;
    for (size_t i = 0; i < n; ++i) {
      const size_t j = (i + 1) % n;
      const double ang = std::atan2(h[2 * j + 1] - h[2 * i + 1], h[2 * j] - h[2 * i]);
      const double c = std::cos(-ang), s = std::sin(-ang);
      double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
      for (size_t k = 0; k < n; ++k) {
        const double x = c * h[2 * k] - s * h[2 * k + 1], y = s * h[2 * k] + c * h[2 * k + 1];
        lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x), lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
      }
      const double w = hi[1] - lo[1], l = hi[0] - lo[0];
      // Ties (a box's four sides, a symmetric strip): the shorter, then the least turned.
      const double tol = 1e-9 * (1.0 + w);
      const bool better = w < best.width - tol ||
                          (w <= best.width + tol && (l < best.length - tol ||
                                                     (l <= best.length + tol && std::fabs(ang) < std::fabs(-best.angle_deg * kPi / 180.0))));
      if (better) {
        best.width = w, best.length = l, best.angle_deg = -ang * 180.0 / kPi;
        best.dx = -lo[0], best.dy = -lo[1];  // box to the origin, placed below
      }
    }
    best.name = it.name, best.area = area;
    if (best.width > roll_width) {
      char msg[512];
      std::snprintf(msg, sizeof msg,
                    "-cutpattern_roll_width %g mm: strip %s is %.1f mm wide at its narrowest (its cut outline, "
                    "with any seam allowance): it does not fit on the roll; give a wider roll or cut narrower strips "
                    "(-cutpattern_strip_width, or split the strip's physical surface)",
                    roll_width, it.name.c_str(), best.width);
      *err = msg;
      return false;
    }
    pl.push_back(best);
    parts.push_back(part);
  }
  // First-fit decreasing shelves: longest first.
  std::vector<size_t> order(pl.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return pl[a].length > pl[b].length; });
  struct Shelf {
    double x0, length, used;
  };
  std::vector<Shelf> shelves;
  *sheet = Sheet();
  sheet->title = "roll nesting";
  for (const auto &l : std::vector<std::pair<std::string, int>>{{"0", 7}, {"ROLL", 8}, {"OUTLINE", 7}, {"WELD", 5}})
    SheetLayer(sheet, l.first, l.second);
  if (drawing.md_mark) SheetLayer(sheet, "MD", 30);
  SheetLayer(sheet, "TEXT", 8);
  const double h = std::max(2.5, 0.012 * roll_width);
  sheet->text_height = h;
  for (size_t k : order) {
    NestPlacement &p = pl[k];
    Shelf *shelf = nullptr;
    for (Shelf &s : shelves)
      if (s.used + gap + p.width <= roll_width) {
        shelf = &s;
        break;
      }
    double y0 = 0;
    if (shelf) {
      y0 = shelf->used + gap;
    } else {
      const double x0 = shelves.empty() ? 0.0 : shelves.back().x0 + shelves.back().length + gap;
      shelves.push_back({x0, p.length, 0.0});
      shelf = &shelves.back();
    }
    shelf->used = y0 + p.width;
    // Turn about the origin, then move its box's corner to (shelf start, y0).
    const double c = std::cos(p.angle_deg * kPi / 180.0), s = std::sin(p.angle_deg * kPi / 180.0);
    p.dx += shelf->x0, p.dy += y0, p.x = shelf->x0, p.y = y0;
    std::vector<double> inside;
    std::vector<const SheetPolyline *> own;
    const size_t first = sheet->lines.size();
    for (SheetPolyline line : parts[k].lines) {
      Turn(&line.pts, c, s, p.dx, p.dy);
      if (line.layer == "OUTLINE" || line.layer == "WELD" || line.layer == "MD") sheet->lines.push_back(line);
      if (line.layer == "WELD" && inside.empty()) inside = line.pts;
    }
    for (size_t j = first; j < sheet->lines.size(); ++j)
      if (sheet->lines[j].layer != "MD") own.push_back(&sheet->lines[j]);
    std::vector<double> avoid;
    for (size_t j = first; j < sheet->lines.size(); ++j)
      if (sheet->lines[j].layer == "MD") {
        double b[4] = {HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        for (size_t i = 0; i + 1 < sheet->lines[j].pts.size(); i += 2)
          for (int q = 0; q < 2; ++q)
            b[q] = std::min(b[q], sheet->lines[j].pts[i + q]), b[q + 2] = std::max(b[q + 2], sheet->lines[j].pts[i + q]);
        avoid.insert(avoid.end(), b, b + 4);
      }
    for (const SheetText &t : parts[k].texts) {  // the MD letters: kept clear too
      SheetText u = t;
      const double half = 0.5 * t.h * (double)t.text.size();  // about the text's middle
      std::vector<double> xy{t.x + half, t.y};
      Turn(&xy, c, s, p.dx, p.dy);
      u.x = xy[0] - half, u.y = xy[1];
      double b[4];
      TextBox(u, b);
      bool clear = true;
      for (const SheetPolyline *q : own) clear = clear && !BoxCrossesPolyline(b, *q);
      if (clear) sheet->texts.push_back(u), avoid.insert(avoid.end(), b, b + 4);
    }
    // The strip's name inside it (smaller when it must be); left out only when no size fits.
    for (double th = h; th > h / 16; th *= 0.5) {
      const double bw = th * (double)(p.name.size() + 1), bh = 1.9 * th;
      double x, y, cx = 0, cy = 0;
      for (size_t i = 0; i + 1 < inside.size(); i += 2) cx += 2 * inside[i] / inside.size(), cy += 2 * inside[i + 1] / inside.size();
      if (PlaceBox(inside, own, avoid, bw, bh, cx, cy, &x, &y)) {
        sheet->texts.push_back({"TEXT", p.name, x + 0.5 * th, y + 0.5 * th, th});
        break;
      }
    }
    out->used_area += p.area;
  }
  out->roll_length = shelves.empty() ? 0.0 : shelves.back().x0 + shelves.back().length;
  out->waste_pct = out->roll_length > 0 ? 100.0 * (1.0 - out->used_area / (roll_width * out->roll_length)) : 0.0;
  out->placed = pl;
  sheet->lines.push_back({"ROLL", {0, 0, out->roll_length, 0, out->roll_length, roll_width, 0, roll_width}, true});
  char title[160];
  std::snprintf(title, sizeof title, "roll %.0f mm wide: %.1f mm used, waste %.1f %%", roll_width, out->roll_length,
                out->waste_pct);
  sheet->texts.push_back({"TEXT", title, 0.0, roll_width + h, h});
  SheetExtent(sheet);
  return true;
}

std::string NestReport(const NestResult &nest, double roll_width, const std::string &base) {
  std::string report;
  char line[512];
  for (const NestPlacement &p : nest.placed) {
    const double turn = std::fabs(p.angle_deg) < 0.05 ? 0.0 : p.angle_deg;  // no "-0.0"
    std::snprintf(line, sizeof line,
                  "cutpattern: nesting: strip %s turned %.1f deg (its MD mark %.1f deg off the roll), %.1f x %.1f mm "
                  "at (%.1f, %.1f)\n",
                  p.name.c_str(), turn, std::fabs(std::remainder(turn, 180.0)), p.length, p.width, p.x,
                  p.y);
    report += line;
  }
  std::snprintf(line, sizeof line,
                "cutpattern: nesting on a roll %.1f mm wide: roll length %.1f mm, strips %.4g m^2 of %.4g m^2, waste "
                "%.2f %%; files %s.{dxf,svg,pdf}\n",
                roll_width, nest.roll_length, nest.used_area * 1e-6, roll_width * nest.roll_length * 1e-6,
                nest.waste_pct, base.c_str());
  return report + line;
}

} // namespace etfe
