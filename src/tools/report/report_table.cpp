#include "report_table.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string markdownLine(const std::vector<Cell>& row) {
  std::string line = "|";
  for (const Cell& c : row) line += " " + c.markdown + " |";
  return line + "\n";
}

std::string csvLine(const std::vector<Cell>& row) {
  std::string line;
  for (size_t i = 0; i < row.size(); ++i) line += (i ? "," : "") + csvField(row[i].csv);
  return line + "\n";
}

}  // namespace

Cell textCell(const std::string& text) {
  return {text, text};
}

Cell percentCell(double fraction) {
  if (std::isnan(fraction)) return {"-", ""};
  return {fmt::format("{:.1f}%", 100 * fraction), fmt::format("{:.6g}", fraction)};
}

Cell numberCell(double value, int decimals) {
  if (std::isnan(value)) return {"-", ""};
  if (std::isinf(value)) return {"inf", "inf"};
  return {fmt::format("{:.{}f}", value, decimals), fmt::format("{:.9g}", value)};
}

void ReportTable::add(std::vector<Cell> row) {
  if (row.size() != header_.size())
    throw std::logic_error("report row without one cell per column");
  rows_.push_back(std::move(row));
}

std::string ReportTable::markdown() const {
  std::string out = markdownLine(header_) + "|";
  for (size_t i = 0; i < header_.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& row : rows_) out += markdownLine(row);
  return out;
}

std::string ReportTable::csv() const {
  std::string out = csvLine(header_);
  for (const auto& row : rows_) out += csvLine(row);
  return out;
}

void writeTextFile(const std::filesystem::path& file, const std::string& text) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  if (!(out << text) || !out.flush()) {
    throw InputError(fmt::format("{}: cannot write", file.string()));
  }
}

}  // namespace stocs::tools
