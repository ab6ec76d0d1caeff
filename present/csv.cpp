#include "present/csv.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "present/file.hpp"

namespace rigidlab::present {

std::string column_name_problem(const std::string& name) {
  if (name.find('\0') != std::string::npos) return "may not contain a NUL byte";
  if (name.find_first_of(",\"\r\n") != std::string::npos)
    return "may not contain a comma, quote or line break";
  return "";
}

std::string csv_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

void write_csv(const std::string& path, const std::vector<Column>& columns) {
  for (const Column& c : columns) {
    if (const std::string problem = column_name_problem(c.name); !problem.empty())
      throw std::invalid_argument("column name " + problem);
    if (c.values.size() != columns[0].values.size())
      throw std::invalid_argument("columns must have the same length");
  }
  OutputFile file(path);
  std::string line;
  for (std::size_t c = 0; c < columns.size(); ++c) line += (c ? "," : "") + columns[c].name;
  file.write(line + "\n");
  const std::size_t rows = columns.empty() ? 0 : columns[0].values.size();
  for (std::size_t row = 0; row < rows; ++row) {
    line.clear();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) line += ',';
      line += csv_number(columns[c].values[row]);
    }
    line += '\n';
    file.write(line);
  }
  file.close();
}

}  // namespace rigidlab::present
