#pragma once
// A table on a drawing sheet: a title, a header row, body rows, thin rules,
// and a note under it. When the rows do not fit the height given, the last
// row that fits says how many more there are and where to find them (a CSV
// beside the drawing), so nothing runs over the next block. mm on the paper,
// y down; internal to the report (it draws with cairo).
#include <cairo.h>

#include <string>
#include <vector>

namespace sheetgen::sheet {

struct SheetTable {
  std::string title;
  std::vector<double> widths;                  // mm per column
  std::vector<double> align;                   // per column: 0 left, 0.5 centre, 1 right (default left)
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as many cells as widths
  std::vector<std::string> notes;              // lines under the table
  std::string more_rows_in;                    // where omitted rows are, e.g. "bends.csv"
};

struct TableFit {
  double height = 0;     // mm used
  int rows_drawn = 0;
  int rows_omitted = 0;
};

// Rows are 1.8 x the text height apart; the title is 1.2 x taller and bold.
double table_height(const SheetTable& table, double text_height);  // mm, with every row

// Draws the table with its top-left corner at (x, y), within max_height mm.
TableFit draw_table(cairo_t* cr, const SheetTable& table, double x, double y, double max_height, double text_height);

}  // namespace sheetgen::sheet
