// Cutting-pattern drawings (docs/theory.md §9: fabricators cut from DXF or SVG): one drawing model,
// a Sheet of layered polylines and texts in mm, built once per strip (or per roll nesting) and
// written both as DXF for the cutting table and as SVG for people, so the two always agree.
//
// Layers: OUTLINE the cut line (the pattern edge plus the seam allowance, when one is given),
// WELD the net pattern edge (the weld line), MD the machine-direction arrow (the pattern's long
// axis, x of the drawing), TEXT the labels, one layer per named line (cut_*, weld_*, ...) and, in
// a nesting, ROLL the roll's edges. Texts are horizontal, left-aligned at their baseline; each
// text's box (TextBox) lies clear of every outline and inside the sheet's extent.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "etfe/analyses/flatten_strip.h"

namespace etfe {

struct SheetPolyline {
  std::string layer;
  std::vector<double> pts;  // 2 per point, mm
  bool closed = false;
};
struct SheetText {
  std::string layer, text;
  double x = 0, y = 0, h = 0;  // baseline start and height, mm
};
struct Sheet {
  std::string title;
  std::vector<std::pair<std::string, int>> layers;  // name, ACI colour
  std::vector<SheetPolyline> lines;
  std::vector<SheetText> texts;
  double lo[2] = {0, 0}, hi[2] = {0, 0};  // extent of every line and text box
  double text_height = 2.5;
};

// The box a text may cover: lo x, lo y, hi x, hi y. Its width is one text height per character
// (no character of a CAD text font is wider) and it reaches 0.35 h below the baseline
// (descenders) and 1.2 h above it.
void TextBox(const SheetText &t, double box[4]);
// Sets s->lo/hi to the extent of its lines and text boxes.
void SheetExtent(Sheet *s);
// Adds a layer unless present.
void SheetLayer(Sheet *s, const std::string &name, int aci);

// The corners of a pattern: positions in r.outline[0] where the outline turns by more than
// min_turn_deg. The edges run from corner to corner (the whole loop when there are none).
std::vector<int> PatternCorners(const FlattenResult &r, double min_turn_deg = 30.0);
// Edge k as node ids along r.outline[0] from corner k to corner k+1 (both included).
std::vector<std::vector<int>> PatternEdges(const FlattenResult &r, const std::vector<int> &corners);
// Corner names A, B, ..., Z, A1, ...
std::string CornerName(int k);

// The drawing of one strip: OUTLINE, WELD, named lines, the MD arrow (when drawing.md_mark) and
// the label block (when drawing.labels): the strip's name, its length and width (bounding box in
// its principal axes: x along MD), every edge's arc length, the two diagonals between the four
// sharpest corners and the named lines' lengths; corner letters inside the corners.
Sheet PatternSheet(const FlattenResult &r, const std::string &name, const PatternDrawing &drawing);
// Finds where a box bw x bh (lower-left corner returned in *x, *y) lies inside the closed
// polygon `inside` (2 per point), crossing none of `polys` (closed polylines) nor the boxes
// `avoid` (4 per box), nearest to (cx, cy). False when no such place is found.
bool PlaceBox(const std::vector<double> &inside, const std::vector<const SheetPolyline *> &polys,
              const std::vector<double> &avoid, double bw, double bh, double cx, double cy, double *x, double *y);
// Whether the box (4: lo x, lo y, hi x, hi y) crosses the polyline.
bool BoxCrossesPolyline(const double box[4], const SheetPolyline &p);

// DXF (R12, AC1009, with $INSUNITS = 4 mm and $MEASUREMENT = 1 metric) and SVG (mm, y up, a scale
// bar) of a sheet.
// The largest 1, 2 or 5 times a power of ten not above x (a scale bar's length).
double NiceLength(double x);

// The page of a sheet's SVG and PDF (mm): the drawing (w x hgt) inside a margin, with four text
// heights h below it for the scale bar; W x H the whole page; lines `line` wide on the outline and
// the welds, twice that elsewhere (LineWidth).
struct SheetPage {
  double w, hgt, margin, h, line, W, H;
  explicit SheetPage(const Sheet &s);
  double LineWidth(const std::string &layer) const { return layer == "OUTLINE" || layer == "WELD" ? line : 2 * line; }
};

bool WriteSheetDxf(const std::string &path, const Sheet &s, std::string *err);
bool WriteSheetSvg(const std::string &path, const Sheet &s, std::string *err);
// PDF of a sheet (pattern_pdf.cpp): one page, 1:1 in mm up to 5.08 m (beyond, /UserUnit), the
// SVG's colours and scale bar.
bool WriteSheetPdf(const std::string &path, const Sheet &s, std::string *err);
bool WriteTextFile(const std::string &path, const std::string &text, std::string *err);

// ---- Roll nesting (pattern_nesting.cpp)
// ---------------------------------------------------------- Every strip turned to the orientation
// of its least width (of its cut outline, the convex hull's narrowest caliper), then placed by
// first-fit decreasing shelves: strips sorted by length, each into the first shelf (a band along
// the roll, as long as its first strip) with room across the roll, else a new shelf after the last
// one; `gap` mm between strips and from the roll's edges along the roll. The roll runs along x, its
// width along y from 0 to roll_width.
struct NestItem {
  std::string name;
  const FlattenResult *result;
};
struct NestPlacement {
  std::string name;
  double angle_deg = 0;          // turn of the pattern (counter-clockwise)
  double dx = 0, dy = 0;         // then shifted by
  double x = 0, y = 0;           // where its box's lower-left corner lies on the roll
  double length = 0, width = 0;  // of its cut outline's box on the roll
  double area = 0;               // of its cut outline, mm^2
};
struct NestResult {
  std::vector<NestPlacement> placed;
  double roll_length = 0, used_area = 0, waste_pct = 0;
};
bool NestOnRoll(const std::vector<NestItem> &items, const PatternDrawing &drawing, double roll_width, double gap,
                NestResult *out, Sheet *sheet, std::string *err);
// The printed lines: each strip's turn and place, the roll length used and the waste.
std::string NestReport(const NestResult &nest, double roll_width, const std::string &base);

} // namespace etfe
