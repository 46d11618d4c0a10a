#include "sheetgen/report/sheet_table.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sheetgen/report/sheet_pen.hpp"

namespace sheetgen::sheet {
namespace {

constexpr double kRowFactor = 1.8;    // row pitch / text height
constexpr double kTitleFactor = 1.2;  // title capitals / text height
constexpr double kPad = 1.0;          // mm, cell text from the rules

double row_pitch(double h) { return kRowFactor * h; }
double title_room(const SheetTable& t, double h) { return t.title.empty() ? 0 : kTitleFactor * h + 0.8 * h; }

// One row of cells between y and y + pitch; every cell's text shrinks to fit its column.
void draw_row(cairo_t* cr, const SheetTable& t, const std::vector<std::string>& cells, double x, double y, double h,
              bool bold) {
  double cx = x;
  for (size_t c = 0; c < t.widths.size() && c < cells.size(); ++c) {
    const double w = t.widths[c], a = c < t.align.size() ? t.align[c] : 0;
    fit_text(cr, cells[c], h, w - 2 * kPad, bold);
    draw_text(cr, cx + kPad + a * (w - 2 * kPad), y + row_pitch(h) / 2, cells[c], a, 0.5);
    cx += w;
  }
}

// The frame around the header and `body_rows` rows, the rule under the header,
// and the column rules down to the last of the `cell_rows` rows with cells.
void draw_rules(cairo_t* cr, const SheetTable& t, double x, double y, double h, int body_rows, int cell_rows) {
  const double width = std::accumulate(t.widths.begin(), t.widths.end(), 0.0);
  const double height = (1 + body_rows) * row_pitch(h);
  set_ink(cr, kBlack);
  cairo_set_line_width(cr, kThin);
  cairo_rectangle(cr, x, y, width, height);
  cairo_stroke(cr);
  draw_line(cr, x, y + row_pitch(h), x + width, y + row_pitch(h), kThin);
  double cx = x;
  for (size_t c = 0; c + 1 < t.widths.size(); ++c) {
    cx += t.widths[c];
    draw_line(cr, cx, y, cx, y + (1 + cell_rows) * row_pitch(h), kThin);
  }
}

}  // namespace

double table_height(const SheetTable& t, double h) {
  return title_room(t, h) + (1 + t.rows.size()) * row_pitch(h) + t.notes.size() * row_pitch(h) * 0.8;
}

TableFit draw_table(cairo_t* cr, const SheetTable& t, double x, double y, double max_height, double h) {
  TableFit fit;
  set_ink(cr, kBlack);
  set_dash(cr, {});
  if (!t.title.empty()) {
    set_text_height(cr, kTitleFactor * h, true);
    draw_text(cr, x, y, t.title, 0, 0);
  }
  const double top = y + title_room(t, h);
  const double notes = t.notes.size() * row_pitch(h) * 0.8;
  const int room = static_cast<int>(std::floor((max_height - title_room(t, h) - notes) / row_pitch(h) + 1e-9)) - 1;
  const int n = static_cast<int>(t.rows.size());
  fit.rows_drawn = n <= room ? n : std::max(0, room - 1);  // one row says what is left out
  fit.rows_omitted = n - fit.rows_drawn;
  draw_row(cr, t, t.header, x, top, h, true);
  for (int r = 0; r < fit.rows_drawn; ++r) draw_row(cr, t, t.rows[r], x, top + (1 + r) * row_pitch(h), h, false);
  const int body = fit.rows_drawn + (fit.rows_omitted > 0 ? 1 : 0);
  if (fit.rows_omitted > 0) {
    const std::string more = "... " + std::to_string(fit.rows_omitted) + " more rows in " + t.more_rows_in;
    const double width = std::accumulate(t.widths.begin(), t.widths.end(), 0.0);
    fit_text(cr, more, h, width - 2 * kPad);
    draw_text(cr, x + kPad, top + (1 + fit.rows_drawn + 0.5) * row_pitch(h), more, 0, 0.5);
  }
  draw_rules(cr, t, x, top, h, body, fit.rows_drawn);
  double note_y = top + (1 + body) * row_pitch(h) + 0.6 * h;
  for (const std::string& line : t.notes) {
    fit_text(cr, line, 0.8 * h, std::accumulate(t.widths.begin(), t.widths.end(), 0.0));
    draw_text(cr, x, note_y, line, 0, 0);
    note_y += row_pitch(h) * 0.8;
  }
  fit.height = note_y - y;
  return fit;
}

}  // namespace sheetgen::sheet
