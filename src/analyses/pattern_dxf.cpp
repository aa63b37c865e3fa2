// DXF of a pattern sheet, for the cutting table.
//
// ASCII R12 (AC1009): the version cutting-table and plotter importers read most reliably, and
// one whose whole structure (HEADER, TABLES, ENTITIES) is checked here without handles, owner
// pointers and the OBJECTS section that R2000 (AC1015) readers such as AutoCAD insist on. Outlines
// are POLYLINE/VERTEX/SEQEND with the closed flag (70 = 1), the R12 closed polyline. The units are
// declared in the header as well as R12 allows: $INSUNITS = 4 (mm) and $MEASUREMENT = 1 (metric),
// variables of later versions that R12 readers skip and later readers (ezdxf: doc.units == 4,
// checked by test_cutpattern_drawings) take; the comment and the title label say mm too. The
// TABLES section defines the layers, the CONTINUOUS line type and the STANDARD text style, so
// strict readers find every referenced table entry.
#include <cerrno>
#include <cstring>

#include "etfe/analyses/pattern_sheet.h"
#include "pattern_text.h"

namespace etfe {
namespace {

void Pair(std::string *s, int code, const std::string &v) { Append(s, "%3d\n%s\n", code, v.c_str()); }
void Pair(std::string *s, int code, int v) { Append(s, "%3d\n%6d\n", code, v); }
void Pair(std::string *s, int code, double v) { Append(s, "%3d\n%.6f\n", code, v); }

// Text values: printable ASCII only, and no "%%" (a DXF control-code prefix).
std::string DxfText(const std::string &t) {
  std::string s;
  for (char c : t) {
    const unsigned char u = (unsigned char)c;
    if (u < 32 || u > 126 || (c == '%' && !s.empty() && s.back() == '%')) continue;
    s += c;
  }
  return s;
}

void Point(std::string *s, int code, double x, double y) {
  Pair(s, code, x);
  Pair(s, code + 10, y);
  Pair(s, code + 20, 0.0);
}

void Header(std::string *s, const Sheet &sh) {
  Pair(s, 0, "SECTION");
  Pair(s, 2, "HEADER");
  Pair(s, 9, "$ACADVER");
  Pair(s, 1, "AC1009");
  Pair(s, 9, "$INSUNITS");
  Pair(s, 70, 4);  // millimetres
  Pair(s, 9, "$MEASUREMENT");
  Pair(s, 70, 1);  // metric
  Pair(s, 9, "$INSBASE");
  Point(s, 10, 0.0, 0.0);
  Pair(s, 9, "$EXTMIN");
  Point(s, 10, sh.lo[0], sh.lo[1]);
  Pair(s, 9, "$EXTMAX");
  Point(s, 10, sh.hi[0], sh.hi[1]);
  Pair(s, 0, "ENDSEC");
}

void Tables(std::string *s, const Sheet &sh) {
  Pair(s, 0, "SECTION");
  Pair(s, 2, "TABLES");
  Pair(s, 0, "TABLE");
  Pair(s, 2, "LTYPE");
  Pair(s, 70, 1);
  Pair(s, 0, "LTYPE");
  Pair(s, 2, "CONTINUOUS");
  Pair(s, 70, 0);
  Pair(s, 3, "Solid line");
  Pair(s, 72, 65);
  Pair(s, 73, 0);
  Pair(s, 40, 0.0);
  Pair(s, 0, "ENDTAB");
  Pair(s, 0, "TABLE");
  Pair(s, 2, "LAYER");
  Pair(s, 70, (int)sh.layers.size());
  for (const auto &ly : sh.layers) {
    Pair(s, 0, "LAYER");
    Pair(s, 2, ly.first);
    Pair(s, 70, 0);
    Pair(s, 62, ly.second);
    Pair(s, 6, "CONTINUOUS");
  }
  Pair(s, 0, "ENDTAB");
  Pair(s, 0, "TABLE");
  Pair(s, 2, "STYLE");
  Pair(s, 70, 1);
  Pair(s, 0, "STYLE");
  Pair(s, 2, "STANDARD");
  Pair(s, 70, 0);
  Pair(s, 40, 0.0);
  Pair(s, 41, 1.0);
  Pair(s, 50, 0.0);
  Pair(s, 71, 0);
  Pair(s, 42, sh.text_height);
  Pair(s, 3, "txt");
  Pair(s, 4, "");
  Pair(s, 0, "ENDTAB");
  Pair(s, 0, "ENDSEC");
}

} // namespace

bool WriteTextFile(const std::string &path, const std::string &text, std::string *err) {
  std::FILE *f = std::fopen(path.c_str(), "wb");
  if (!f) {
    if (err) *err = "cannot open '" + path + "' for writing: " + std::strerror(errno);
    return false;
  }
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    if (err) *err = "writing '" + path + "' failed: " + std::strerror(errno);
    return false;
  }
  return true;
}

bool WriteSheetDxf(const std::string &path, const Sheet &sh, std::string *err) {
  std::string s;
  Pair(&s, 999, DxfText("cutting pattern " + sh.title + " (etfe, units mm)"));
  Header(&s, sh);
  Tables(&s, sh);
  Pair(&s, 0, "SECTION");
  Pair(&s, 2, "ENTITIES");
  for (const SheetPolyline &p : sh.lines) {
    Pair(&s, 0, "POLYLINE");
    Pair(&s, 8, p.layer);
    Pair(&s, 66, 1);  // vertices follow
    Point(&s, 10, 0.0, 0.0);
    Pair(&s, 70, p.closed ? 1 : 0);
    for (size_t k = 0; k + 1 < p.pts.size(); k += 2) {
      Pair(&s, 0, "VERTEX");
      Pair(&s, 8, p.layer);
      Point(&s, 10, p.pts[k], p.pts[k + 1]);
    }
    Pair(&s, 0, "SEQEND");
    Pair(&s, 8, p.layer);
  }
  for (const SheetText &t : sh.texts) {  // left-aligned at the baseline, horizontal
    Pair(&s, 0, "TEXT");
    Pair(&s, 8, t.layer);
    Point(&s, 10, t.x, t.y);
    Pair(&s, 40, t.h);
    Pair(&s, 1, DxfText(t.text));
    Pair(&s, 7, "STANDARD");
  }
  Pair(&s, 0, "ENDSEC");
  Pair(&s, 0, "EOF");
  return WriteTextFile(path, s, err);
}

} // namespace etfe
