#include "experiments/viewer/csv_table.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>

#include "core/io/input_error.hpp"

namespace drape {

namespace {

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(
        line.substr(start, comma == std::string_view::npos ? line.npos : comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

// std::from_chars for double: exact, locale-free, and rejects trailing garbage.
bool parse_number(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && !text.empty();
}

}  // namespace

CsvTable::CsvTable(const std::filesystem::path& file, const std::vector<std::string>& columns,
                   const std::vector<std::string>& text_columns)
    : m_file(file.string()),
      m_columns(columns),
      m_width(columns.size()),
      m_text_width(text_columns.size()) {
  std::ifstream in(file);
  if (!in) throw InputError(m_file, "", "cannot read the file");
  std::string line;
  if (!std::getline(in, line)) throw InputError(m_file, "", "empty file, no header line");
  // Every line a run writes ends in a newline: a line at the end without one was cut (a full
  // disk, `head -c`), and its last number may be cut short yet still parse.
  const auto check_not_cut = [&](int number) {
    if (in.eof())
      throw InputError(m_file, "line " + std::to_string(number),
                       "the last line is cut (the file does not end in a newline)");
  };
  check_not_cut(1);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string_view> header = split_fields(line);
  const auto column_index = [&](const std::string& name) {
    size_t k = 0;
    while (k < header.size() && header[k] != name) ++k;
    if (k == header.size())
      throw InputError(m_file, "line 1", "no column '" + name + "' in the header '" + line + "'");
    return k;
  };
  std::vector<size_t> index, text_index;
  for (const std::string& name : columns) index.push_back(column_index(name));
  for (const std::string& name : text_columns) text_index.push_back(column_index(name));
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    check_not_cut(line_number);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string_view> fields = split_fields(line);
    const std::string where = "line " + std::to_string(line_number);
    if (fields.size() != header.size())
      throw InputError(m_file, where,
                       "expected " + std::to_string(header.size()) + " fields, got " +
                           std::to_string(fields.size()));
    for (size_t c = 0; c < columns.size(); ++c) {
      double value = 0.0;
      if (!parse_number(fields[index[c]], value))
        throw InputError(
            m_file, where,
            "column '" + columns[c] + "' is not a number: '" + std::string(fields[index[c]]) + "'");
      m_values.push_back(value);
    }
    for (const size_t k : text_index) m_text.emplace_back(fields[k]);
    m_lines.push_back(line_number);
    ++m_rows;
  }
}

double CsvTable::finite(int r, int c) const {
  const double value = at(r, c);
  if (!std::isfinite(value))
    throw InputError(m_file, line(r),
                     fmt::format("column '{}' is not a finite number: {}", m_columns[static_cast<size_t>(c)], value));
  return value;
}

int CsvTable::integer(int r, int c, int low, int high) const {
  const double value = at(r, c);
  // Compared as doubles first: only a value in range may be converted.
  if (!(value >= low && value <= high && value == std::floor(value)))
    throw InputError(m_file, line(r),
                     fmt::format("column '{}' is {}, expected an integer in [{}, {}]",
                                 m_columns[static_cast<size_t>(c)], value, low, high));
  return static_cast<int>(value);
}

}  // namespace drape
