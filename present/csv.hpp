// CSV data files (RFC 4180 without quoting: names may not hold a comma, quote or line break):
// a header line and one row per index, each number in the shortest form that reads back to
// the same double.
#pragma once

#include <string>
#include <vector>

namespace rigidlab::present {

struct Column {
  std::string name;
  std::vector<double> values;
};

// Why `name` cannot head a column (a comma, quote, line break or NUL in it), or "".
std::string column_name_problem(const std::string& name);

// The shortest decimal that reads back as x (std::to_chars), "nan", "inf" or "-inf".
std::string csv_number(double x);

// Writes the columns (all the same length) to `path`. Throws std::invalid_argument for a bad
// name or ragged columns, FileError (present/file.hpp) when the file cannot be written.
void write_csv(const std::string& path, const std::vector<Column>& columns);

}  // namespace rigidlab::present
