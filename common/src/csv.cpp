#include "uhpc/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

#include "uhpc/errors.hpp"

namespace uhpc {
namespace {

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

// Splits one line into cells; quoted cells keep their commas and lose their quotes.
std::vector<std::string> split_cells(std::string_view line, const std::string& source, std::size_t line_no) {
  std::vector<std::string> cells;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string cell;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        cell += line[i++];
      }
      if (!closed) throw_input_error(source, "", "line " + std::to_string(line_no) + ": unterminated quote");
      const std::size_t comma = line.find(',', i);
      const std::string_view rest = line.substr(i, comma == std::string_view::npos ? std::string_view::npos : comma - i);
      if (!trim(rest).empty()) {
        throw_input_error(source, "", "line " + std::to_string(line_no) + ": text after a closing quote");
      }
      i = comma;
    } else {
      const std::size_t comma = line.find(',', i);
      cell = std::string(trim(line.substr(i, comma == std::string_view::npos ? std::string_view::npos : comma - i)));
      i = comma;
    }
    cells.push_back(std::move(cell));
    if (i == std::string_view::npos) break;
    ++i;  // past the comma; a trailing comma yields one more (empty) cell
  }
  return cells;
}

// "name [unit]" -> {name, unit}; "name" -> {name, ""}.
std::pair<std::string, std::string> split_header(const std::string& cell) {
  const std::string_view s = cell;
  const std::size_t open = s.rfind('[');
  if (!s.empty() && s.back() == ']' && open != std::string_view::npos) {
    return {std::string(trim(s.substr(0, open))), std::string(trim(s.substr(open + 1, s.size() - open - 2)))};
  }
  return {cell, ""};
}

bool parse_double(const std::string& text, double& value) {
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars rejects a leading '+'
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size() && std::isfinite(value);
}

}  // namespace

CsvTable CsvTable::read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_error(path, "", "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw_input_error(path, "", "cannot read file");
  return parse(text.str(), path);
}

CsvTable CsvTable::parse(std::string_view text, std::string source) {
  CsvTable table;
  table.source_ = std::move(source);
  bool have_header = false;
  std::size_t line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t eol = text.find('\n', pos);
    const std::string_view raw = text.substr(pos, eol == std::string_view::npos ? std::string_view::npos : eol - pos);
    pos = eol == std::string_view::npos ? text.size() : eol + 1;
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;

    std::vector<std::string> cells = split_cells(line, table.source_, line_no);
    if (!have_header) {
      for (const std::string& cell : cells) {
        auto [name, unit] = split_header(cell);
        if (name.empty()) throw_input_error(table.source_, "", "line " + std::to_string(line_no) + ": empty column name");
        if (table.has(name)) throw_input_error(table.source_, "", "duplicate column '" + name + "'");
        table.names_.push_back(std::move(name));
        table.units_.push_back(std::move(unit));
      }
      have_header = true;
      continue;
    }
    if (cells.size() != table.names_.size()) {
      throw_input_error(table.source_, "",
                        "line " + std::to_string(line_no) + ": expected " + std::to_string(table.names_.size()) +
                            " cells, got " + std::to_string(cells.size()));
    }
    table.cells_.push_back(std::move(cells));
    table.lines_.push_back(line_no);
  }
  if (!have_header) throw_input_error(table.source_, "", "no header row");
  return table;
}

bool CsvTable::has(const std::string& name) const {
  for (const std::string& n : names_) {
    if (n == name) return true;
  }
  return false;
}

std::size_t CsvTable::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == name) return i;
  }
  std::string available;
  for (const std::string& n : names_) available += (available.empty() ? "" : ", ") + n;
  throw_input_error(source_, "", "no column '" + name + "' (columns: " + available + ")");
}

const std::string& CsvTable::unit(const std::string& name) const { return units_[index_of(name)]; }

std::vector<double> CsvTable::column(const std::string& name) const {
  const std::size_t c = index_of(name);
  std::vector<double> values(cells_.size());
  for (std::size_t r = 0; r < cells_.size(); ++r) {
    if (!parse_double(cells_[r][c], values[r])) {
      throw_input_error(source_, "",
                        "column '" + name + "', row " + std::to_string(r + 1) + " (line " +
                            std::to_string(lines_[r]) + "): '" + cells_[r][c] + "' is not a number");
    }
  }
  return values;
}

std::vector<std::string> CsvTable::text_column(const std::string& name) const {
  const std::size_t c = index_of(name);
  std::vector<std::string> values;
  values.reserve(cells_.size());
  for (const auto& row : cells_) values.push_back(row[c]);
  return values;
}

}  // namespace uhpc
