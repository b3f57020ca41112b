// Small CSV files with a fixed header (the run's and the calibration's), read whole. Errors name
// the file and the line.
#pragma once

#include <string>
#include <vector>

namespace p4 {

// The rows after the header line, split at commas (blank lines skipped), each with as many
// fields as the header. Throws p4::Error when the file cannot be opened, its first line is not
// `header`, or a row has another number of fields (naming the line) — but a last line with no
// end and too few fields, a row torn by a crash, is skipped.
std::vector<std::vector<std::string>> ReadCsv(const std::string& path, const std::string& header);

// The cell as a number; throws p4::Error naming the file, the line (row + 2) and the text.
double CsvNumber(const std::string& path, std::size_t row, const std::string& cell);
// The cell as a whole number in [lo, hi]; throws p4::Error naming the file, line and text.
int CsvInt(const std::string& path, std::size_t row, const std::string& cell, int lo, int hi);

}  // namespace p4
