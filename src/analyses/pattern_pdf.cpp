// PDF of a cutting-pattern sheet (see etfe/analyses/pattern_sheet.h): one page, vector lines and
// Helvetica texts, 1:1 in mm (content scaled by 72/25.4 pt per mm), the same layers' colours and
// the same scale bar as the SVG. A page longer than PDF's 14 400 units (5.08 m at 1:1) declares
// /UserUnit k (PDF 1.6) with the content drawn 1/k: a reader that honours it (Acrobat, pdf.js)
// shows it 1:1, one that does not shows it at 1:k; the scale bar tells which.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "etfe/analyses/pattern_sheet.h"

namespace etfe {

namespace {

void Put(std::string *s, const char *fmt, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  *s += buf;
}

// RGB of the AutoCAD colour indices the sheets use (as in the SVG; others black).
void Rgb(int aci, double c[3]) {
  c[0] = c[1] = c[2] = 0;
  switch (aci) {
  case 1: c[0] = 0.816; break;
  case 3: c[1] = 0.502; break;
  case 5: c[1] = 0.251, c[2] = 0.816; break;
  case 6: c[0] = 0.8, c[2] = 0.8; break;
  case 8: c[0] = c[1] = c[2] = 0.314; break;
  case 30: c[0] = 1, c[1] = 0.502; break;
  default: break;
  }
}

// A PDF string literal: ( ) \ escaped, bytes outside printable ASCII as '?'.
std::string PdfString(const std::string &t) {
  std::string s = "(";
  for (unsigned char c : t) {
    if (c == '(' || c == ')' || c == '\\') s += '\\', s += (char)c;
    else s += c >= 32 && c < 127 ? (char)c : '?';
  }
  return s + ")";
}

} // namespace

bool WriteSheetPdf(const std::string &path, const Sheet &sh, std::string *err) {
  const SheetPage sp(sh);
  const double w = sp.w, margin = sp.margin, h = sp.h, sw = sp.line, W = sp.W, H = sp.H;
  const double pt = 72.0 / 25.4;
  const double unit = std::max(1.0, std::ceil(std::max(W, H) * pt / 14400.0));
  // Content in mm: the drawing's (x, y) at (margin + x - lo x, 4 h + margin + y - lo y), the
  // scale bar below it.
  std::string c;
  Put(&c, "%.6f 0 0 %.6f 0 0 cm\n1 J 1 j\n", pt / unit, pt / unit);
  auto X = [&](double x) { return margin + x - sh.lo[0]; };
  auto Y = [&](double y) { return 4 * h + margin + y - sh.lo[1]; };
  for (const auto &ly : sh.layers) {
    double rgb[3];
    Rgb(ly.second, rgb);
    const double width = sp.LineWidth(ly.first);
    Put(&c, "%.3f %.3f %.3f RG %.3f w %s\n", rgb[0], rgb[1], rgb[2], width, ly.first == "WELD" ? "[8 3] 0 d" : "[] 0 d");
    for (const SheetPolyline &p : sh.lines) {
      if (p.layer != ly.first || p.pts.size() < 4) continue;
      for (size_t k = 0; k + 1 < p.pts.size(); k += 2) Put(&c, "%.4f %.4f %s\n", X(p.pts[k]), Y(p.pts[k + 1]), k ? "l" : "m");
      c += p.closed ? "s\n" : "S\n";
    }
    const bool text = ly.first == "TEXT";
    Put(&c, "%.3f %.3f %.3f rg\n", text ? 0.0 : rgb[0], text ? 0.0 : rgb[1], text ? 0.0 : rgb[2]);
    for (const SheetText &t : sh.texts)
      if (t.layer == ly.first)
        Put(&c, "BT /F1 %.3f Tf %.4f %.4f Td %s Tj ET\n", t.h / 0.718, X(t.x), Y(t.y), PdfString(t.text).c_str());
  }
  // Scale bar: 0 to a round length, ticks at its ends and middle (Helvetica's caps are 0.718 em).
  const double L = NiceLength(std::max(1.0, 0.3 * w)), x0 = margin, y0 = 1.5 * h;
  Put(&c, "0 0 0 RG 0 0 0 rg %.3f w [] 0 d %.4f %.4f m %.4f %.4f l S\n", sw, x0, y0, x0 + L, y0);
  for (double f : {0.0, 0.5, 1.0}) Put(&c, "%.4f %.4f m %.4f %.4f l S\n", x0 + f * L, y0 - 0.5 * h, x0 + f * L, y0 + 0.5 * h);
  char label[64];
  std::snprintf(label, sizeof label, "%g mm", L);
  Put(&c, "BT /F1 %.3f Tf %.4f %.4f Td (0) Tj ET\n", h / 0.718, x0, y0 + 0.7 * h);
  Put(&c, "BT /F1 %.3f Tf %.4f %.4f Td %s Tj ET\n", h / 0.718, x0 + L - 0.6 * h * std::strlen(label), y0 + 0.7 * h,
      PdfString(label).c_str());
  // The file: catalog, pages, page, content, font, info; then the cross-reference table.
  std::string s = "%PDF-1.6\n%\xe2\xe3\xcf\xd3\n";
  std::vector<size_t> off;
  auto obj = [&](const std::string &body) {
    off.push_back(s.size());
    Put(&s, "%zu 0 obj\n", off.size());
    s += body + "\nendobj\n";
  };
  obj("<< /Type /Catalog /Pages 2 0 R >>");
  obj("<< /Type /Pages /Kids [3 0 R] /Count 1 >>");
  char page[400];
  std::snprintf(page, sizeof page,
                "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 %.3f %.3f]%s /Contents 4 0 R "
                "/Resources << /Font << /F1 5 0 R >> >> >>",
                W * pt / unit, H * pt / unit, unit > 1 ? (" /UserUnit " + std::to_string((int)unit)).c_str() : "");
  obj(page);
  obj("<< /Length " + std::to_string(c.size()) + " >>\nstream\n" + c + "endstream");
  obj("<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>");
  obj("<< /Title " + PdfString(sh.title) + " /Producer (etfe) >>");
  const size_t xref = s.size();
  Put(&s, "xref\n0 %zu\n0000000000 65535 f \n", off.size() + 1);
  for (size_t o : off) Put(&s, "%010zu 00000 n \n", o);
  Put(&s, "trailer\n<< /Size %zu /Root 1 0 R /Info %zu 0 R >>\nstartxref\n%zu\n%%%%EOF\n", off.size() + 1, off.size(), xref);
  return WriteTextFile(path, s, err);
}

} // namespace etfe
