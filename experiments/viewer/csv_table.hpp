#pragma once
// A numeric CSV file with a header line, as a run writes them (docs/outputs.md), read strictly:
// a missing column, a short row, a field that is not a number or a last line without its
// newline (a cut file) is an InputError naming the file and the line. A number read is any
// double, inf and nan too; finite() and integer() are the checked reads for the columns where
// those are damage.
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

/// The columns a caller asked for, row by row.
class CsvTable {
 public:
  /// Reads `file`, keeping the numeric `columns` and the `text_columns` (all must be in the
  /// header; others are ignored).
  CsvTable(const std::filesystem::path& file, const std::vector<std::string>& columns,
           const std::vector<std::string>& text_columns = {});

  int rows() const { return m_rows; }
  /// Value of the c-th requested column in row r.
  double at(int r, int c) const { return m_values[static_cast<size_t>(r) * m_width + c]; }
  /// at(r, c), an InputError naming the file, the line and the column when it is not finite.
  double finite(int r, int c) const;
  /// at(r, c) as an int, an InputError naming the file, the line and the column when it is not
  /// an integer in [low, high] (a cast of nan or 1e12 to int is undefined behaviour).
  int integer(int r, int c, int low, int high) const;
  /// "line N" of row r in the file, for messages.
  std::string line(int r) const { return "line " + std::to_string(m_lines[static_cast<size_t>(r)]); }
  /// Value of the c-th requested text column in row r.
  const std::string& text(int r, int c) const {
    return m_text[static_cast<size_t>(r) * m_text_width + c];
  }
  const std::string& file() const { return m_file; }

 private:
  std::string m_file;
  std::vector<std::string> m_columns;
  std::vector<int> m_lines;  ///< each row's line in the file (blank lines are skipped)
  size_t m_width = 0;
  int m_rows = 0;
  size_t m_text_width = 0;
  std::vector<double> m_values;
  std::vector<std::string> m_text;
};

}  // namespace drape
