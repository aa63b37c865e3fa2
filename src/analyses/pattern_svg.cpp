// SVG of a pattern sheet, for people: the DXF's content (one group per layer, id = the layer's
// name in lower case) in mm (width/height in mm, viewBox in mm: 1 user unit = 1 mm at print), y
// flipped to keep the DXF's orientation (y up), and a scale bar under the drawing.
#include <cctype>
#include <cmath>

#include "etfe/analyses/pattern_sheet.h"
#include "pattern_text.h"

namespace etfe {
namespace {

std::string XmlEscape(const std::string &t) {
  std::string s;
  for (char c : t) {
    switch (c) {
    case '&': s += "&amp;"; break;
    case '<': s += "&lt;"; break;
    case '>': s += "&gt;"; break;
    case '"': s += "&quot;"; break;
    default:
      if ((unsigned char)c >= 32 || c == '\t') s += c;
    }
  }
  return s;
}

std::string Lower(const std::string &t) {
  std::string s;
  for (char c : t) s += (char)std::tolower((unsigned char)c);
  return s;
}

// The RGB of the few AutoCAD colour indices the sheets use (others black).
const char *Rgb(int aci) {
  switch (aci) {
  case 1: return "#d00000";
  case 3: return "#008000";
  case 5: return "#0040d0";
  case 6: return "#cc00cc";
  case 8: return "#505050";
  case 30: return "#ff8000";
  default: return "#000000";
  }
}

} // namespace

bool WriteSheetSvg(const std::string &path, const Sheet &sh, std::string *err) {
  const SheetPage page(sh);
  const double w = page.w, hgt = page.hgt, margin = page.margin, h = page.h, sw = page.line, W = page.W, H = page.H;
  auto X = [&](double x) { return margin + x - sh.lo[0]; };
  auto Y = [&](double y) { return margin + sh.hi[1] - y; };
  std::string s;
  Append(&s, "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n");
  Append(&s,
         "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"%.3fmm\" "
         "height=\"%.3fmm\" viewBox=\"0 0 %.3f %.3f\">\n",
         W, H, W, H);
  Append(&s, "<title>%s</title>\n", XmlEscape(sh.title).c_str());
  Append(&s, "<desc>Cutting pattern, 1 user unit = 1 mm (print at 100 %% for 1:1), y up as in the DXF; "
             "groups = the DXF's layers</desc>\n");
  for (const auto &ly : sh.layers) {
    bool any = false;
    for (const SheetPolyline &p : sh.lines) any = any || p.layer == ly.first;
    for (const SheetText &t : sh.texts) any = any || t.layer == ly.first;
    if (!any) continue;
    const double width = page.LineWidth(ly.first);
    Append(&s, "<g id=\"%s\" fill=\"none\" stroke=\"%s\" stroke-width=\"%.3f\" stroke-linejoin=\"round\"%s>\n",
           XmlEscape(Lower(ly.first)).c_str(), Rgb(ly.second), width,
           ly.first == "WELD" ? " stroke-dasharray=\"8 3\"" : "");
    for (const SheetPolyline &p : sh.lines) {
      if (p.layer != ly.first) continue;
      if (p.closed) {
        s += "<path d=\"";
        for (size_t k = 0; k + 1 < p.pts.size(); k += 2)
          Append(&s, "%s%.4f,%.4f ", k == 0 ? "M " : (k == 2 ? "L " : ""), X(p.pts[k]), Y(p.pts[k + 1]));
        s += "Z\"/>\n";
      } else {
        s += "<polyline points=\"";
        for (size_t k = 0; k + 1 < p.pts.size(); k += 2)
          Append(&s, "%s%.4f,%.4f", k ? " " : "", X(p.pts[k]), Y(p.pts[k + 1]));
        s += "\"/>\n";
      }
    }
    for (const SheetText &t : sh.texts)
      if (t.layer == ly.first)
        Append(&s, "<text x=\"%.4f\" y=\"%.4f\" font-family=\"sans-serif\" font-size=\"%.3f\" fill=\"%s\" "
                   "stroke=\"none\">%s</text>\n",
               X(t.x), Y(t.y), t.h, ly.first == "TEXT" ? "#000000" : Rgb(ly.second), XmlEscape(t.text).c_str());
    s += "</g>\n";
  }
  // Scale bar: 0 to a round length, ticks at its ends and middle, under the drawing.
  const double L = NiceLength(std::max(1.0, 0.3 * w)), y0 = margin + hgt + 2.5 * h, x0 = margin;
  Append(&s, "<g id=\"scale\" stroke=\"#000000\" stroke-width=\"%.3f\" fill=\"none\">\n", sw);
  Append(&s, "<path d=\"M %.4f,%.4f L %.4f,%.4f\"/>\n", x0, y0, x0 + L, y0);
  for (double f : {0.0, 0.5, 1.0})
    Append(&s, "<path d=\"M %.4f,%.4f L %.4f,%.4f\"/>\n", x0 + f * L, y0 - 0.5 * h, x0 + f * L, y0 + 0.5 * h);
  Append(&s, "<text x=\"%.4f\" y=\"%.4f\" font-family=\"sans-serif\" font-size=\"%.3f\" fill=\"#000000\" "
             "stroke=\"none\">0</text>\n", x0, y0 - 0.7 * h, h);
  Append(&s, "<text x=\"%.4f\" y=\"%.4f\" font-family=\"sans-serif\" font-size=\"%.3f\" fill=\"#000000\" "
             "stroke=\"none\" text-anchor=\"end\">%g mm</text>\n", x0 + L, y0 - 0.7 * h, h, L);
  s += "</g>\n</svg>\n";
  return WriteTextFile(path, s, err);
}

} // namespace etfe
