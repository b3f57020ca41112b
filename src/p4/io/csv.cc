#include "p4/io/csv.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "p4/core/error.h"

namespace p4 {

std::vector<std::vector<std::string>> ReadCsv(const std::string& path, const std::string& header) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open");
  std::string line;
  const auto strip = [](std::string* l) {
    if (!l->empty() && l->back() == '\r') l->pop_back();
  };
  if (std::getline(in, line)) strip(&line);
  if (!in || line != header) {
    throw Error(path + ": line 1: expected the header '" + header + "'");
  }
  const std::size_t fields = std::count(header.begin(), header.end(), ',') + 1;
  std::vector<std::vector<std::string>> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    strip(&line);
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    if (cells.size() != fields) {
      // A last line with no end and too few fields: a row torn by a crash (io/line_appender.h),
      // not a malformed file.
      if (in.eof() && cells.size() < fields) break;
      throw Error(
          fmt::format("{}: line {}: expected {} fields ({})", path, number, fields, header));
    }
    rows.push_back(std::move(cells));
  }
  return rows;
}

double CsvNumber(const std::string& path, std::size_t row, const std::string& cell) {
  try {
    std::size_t used = 0;
    const double v = std::stod(cell, &used);
    if (used != cell.size()) throw std::invalid_argument(cell);
    return v;
  } catch (const std::exception&) {
    throw Error(fmt::format("{}: line {}: '{}' is not a number", path, row + 2, cell));
  }
}

int CsvInt(const std::string& path, std::size_t row, const std::string& cell, int lo, int hi) {
  const double v = CsvNumber(path, row, cell);
  if (!(v >= lo && v <= hi) || v != std::floor(v)) {
    throw Error(fmt::format("{}: line {}: '{}' is not a whole number in {}-{}", path, row + 2, cell,
                            lo, hi));
  }
  return static_cast<int>(v);
}

}  // namespace p4
