#pragma once
// A table written both as markdown (for people: rounded, with units) and as CSV (for programs:
// full precision, fractions rather than percentages).

#include <filesystem>
#include <string>
#include <vector>

namespace stocs::tools {

struct Cell {
  std::string markdown;
  std::string csv;
};

/// The same text in both forms.
Cell textCell(const std::string& text);
/// A fraction: "85.3%" in markdown, 0.853333 in CSV; "-" / empty for NaN.
Cell percentCell(double fraction);
/// A number with `decimals` in markdown, full precision in CSV; "inf" for infinity, "-" / empty
/// for NaN.
Cell numberCell(double value, int decimals);

class ReportTable {
 public:
  explicit ReportTable(std::vector<Cell> header) : header_(std::move(header)) {}
  /// Throws std::logic_error when the row does not have one cell per column.
  void add(std::vector<Cell> row);

  std::string markdown() const;
  std::string csv() const;
  bool empty() const { return rows_.empty(); }

 private:
  std::vector<Cell> header_;
  std::vector<std::vector<Cell>> rows_;
};

/// Writes `text` to `file`, creating its folder; throws InputError naming the file on failure.
void writeTextFile(const std::filesystem::path& file, const std::string& text);

}  // namespace stocs::tools
