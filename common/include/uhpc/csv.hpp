#pragma once
// A small reader for the project's CSV tables (data/ and the programs' history files).
//
// Format: comma separated; the first non-comment line is the header; a header cell is "name [unit]"
// or "name" (no unit). Lines whose first non-blank character is '#' and blank lines are skipped
// anywhere. Cells are trimmed; a cell may be double-quoted to hold commas ("" is a literal quote).
// Every row must have as many cells as the header. Cells stay text until a column is asked for as
// numbers, so a table may mix text and number columns.
//
// Every error is an InputError whose message starts with the file name, e.g.
//   "data/t.csv: column 'impact_velocity', row 3 (line 6): 'abc' is not a number"
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace uhpc {

class CsvTable {
 public:
  // Reads and parses `path`. Errors: file missing/unreadable, no header, duplicate column name,
  // a row with the wrong number of cells, an unterminated quote.
  static CsvTable read(const std::string& path);
  // Parses text already in memory; `source` names it in error messages.
  static CsvTable parse(std::string_view text, std::string source);

  std::size_t rows() const { return cells_.size(); }
  std::size_t columns() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  bool has(const std::string& name) const;
  // The unit from "name [unit]", "" when the header gave none.
  const std::string& unit(const std::string& name) const;
  // The column parsed as finite numbers; the error names file, column, row and line of a bad cell.
  std::vector<double> column(const std::string& name) const;
  // The column's cells as text (trimmed, quotes removed).
  std::vector<std::string> text_column(const std::string& name) const;
  const std::string& source() const { return source_; }

 private:
  std::size_t index_of(const std::string& name) const;  // throws naming the available columns

  std::string source_;
  std::vector<std::string> names_;
  std::vector<std::string> units_;
  std::vector<std::vector<std::string>> cells_;  // [row][column]
  std::vector<std::size_t> lines_;               // 1-based file line of each row, for messages
};

// Shorthand for CsvTable::read.
inline CsvTable read_csv(const std::string& path) { return CsvTable::read(path); }

}  // namespace uhpc
