// The CSV reader (common/include/uhpc/csv.hpp): parsing, units, text cells, and its error messages.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "uhpc/csv.hpp"
#include "uhpc/errors.hpp"

namespace {

template <typename F>
std::string input_error_of(F&& f) {
  return uhpc::test::error_of<uhpc::InputError>(f);
}

const char* const kSample =
    "# a comment line before the header\n"
    "name,impact_velocity [m/s], thickness [mm] ,note\n"
    "\n"
    "shot 1,610,32.31,first\n"
    "  # an indented comment between rows\n"
    "shot 2,613,31.80,\"with, a comma and \"\"quotes\"\"\"\r\n"
    "shot 3,-1.5e2,+29.14,\n";

TEST(Csv, ParsesHeaderUnitsAndCells) {
  const uhpc::CsvTable t = uhpc::CsvTable::parse(kSample, "sample.csv");
  EXPECT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.columns(), 4u);
  EXPECT_EQ(t.names(), (std::vector<std::string>{"name", "impact_velocity", "thickness", "note"}));
  EXPECT_EQ(t.unit("impact_velocity"), "m/s");
  EXPECT_EQ(t.unit("thickness"), "mm");
  EXPECT_EQ(t.unit("name"), "");
  EXPECT_EQ(t.column("impact_velocity"), (std::vector<double>{610.0, 613.0, -150.0}));
  EXPECT_EQ(t.column("thickness"), (std::vector<double>{32.31, 31.80, 29.14}));
  EXPECT_EQ(t.text_column("name"), (std::vector<std::string>{"shot 1", "shot 2", "shot 3"}));
  EXPECT_EQ(t.text_column("note"), (std::vector<std::string>{"first", "with, a comma and \"quotes\"", ""}));
  EXPECT_TRUE(t.has("note"));
  EXPECT_FALSE(t.has("velocity"));
  EXPECT_EQ(t.source(), "sample.csv");
}

TEST(Csv, HeaderOnlyHasNoRows) {
  const uhpc::CsvTable t = uhpc::CsvTable::parse("a [m],b\n", "h.csv");
  EXPECT_EQ(t.rows(), 0u);
  EXPECT_TRUE(t.column("a").empty());
}

TEST(Csv, NonNumberCellNamesFileColumnRowAndLine) {
  const uhpc::CsvTable t = uhpc::CsvTable::parse(kSample, "sample.csv");
  EXPECT_EQ(input_error_of([&] { (void)t.column("name"); }),
            "sample.csv: column 'name', row 1 (line 4): 'shot 1' is not a number");
  EXPECT_EQ(input_error_of([&] { (void)t.column("note"); }),
            "sample.csv: column 'note', row 1 (line 4): 'first' is not a number");
  const uhpc::CsvTable u = uhpc::CsvTable::parse("x\n1\n2abc\n", "u.csv");
  EXPECT_EQ(input_error_of([&] { (void)u.column("x"); }), "u.csv: column 'x', row 2 (line 3): '2abc' is not a number");
  const uhpc::CsvTable empty_cell = uhpc::CsvTable::parse("x,y\n1,\n", "e.csv");
  EXPECT_EQ(input_error_of([&] { (void)empty_cell.column("y"); }),
            "e.csv: column 'y', row 1 (line 2): '' is not a number");
  const uhpc::CsvTable inf = uhpc::CsvTable::parse("x\ninf\n", "i.csv");
  EXPECT_EQ(input_error_of([&] { (void)inf.column("x"); }), "i.csv: column 'x', row 1 (line 2): 'inf' is not a number");
}

TEST(Csv, MissingColumnListsTheColumns) {
  const uhpc::CsvTable t = uhpc::CsvTable::parse(kSample, "sample.csv");
  EXPECT_EQ(input_error_of([&] { (void)t.column("velocity"); }),
            "sample.csv: no column 'velocity' (columns: name, impact_velocity, thickness, note)");
  EXPECT_EQ(input_error_of([&] { (void)t.unit("velocity"); }),
            "sample.csv: no column 'velocity' (columns: name, impact_velocity, thickness, note)");
  EXPECT_FALSE(input_error_of([&] { (void)t.text_column("velocity"); }).empty());
}

TEST(Csv, MissingFile) {
  const std::string path = std::string(UHPC_BINARY_DIR) + "/no_such_dir/missing.csv";
  EXPECT_EQ(input_error_of([&] { (void)uhpc::CsvTable::read(path); }), path + ": cannot open file");
}

TEST(Csv, MalformedTables) {
  EXPECT_EQ(input_error_of([] { (void)uhpc::CsvTable::parse("a,b\n1,2,3\n", "m.csv"); }),
            "m.csv: line 2: expected 2 cells, got 3");
  EXPECT_EQ(input_error_of([] { (void)uhpc::CsvTable::parse("# only a comment\n\n", "m.csv"); }),
            "m.csv: no header row");
  EXPECT_EQ(input_error_of([] { (void)uhpc::CsvTable::parse("a,a [m]\n", "m.csv"); }), "m.csv: duplicate column 'a'");
  EXPECT_EQ(input_error_of([] { (void)uhpc::CsvTable::parse("a,\n", "m.csv"); }), "m.csv: line 1: empty column name");
  EXPECT_EQ(input_error_of([] { (void)uhpc::CsvTable::parse("a\n\"open\n", "m.csv"); }),
            "m.csv: line 2: unterminated quote");
}

TEST(Csv, ReadsAFile) {
  const std::filesystem::path path = std::filesystem::path(UHPC_BINARY_DIR) / "test_csv_reads_a_file.csv";
  {
    std::ofstream out(path);
    out << kSample;
  }
  const uhpc::CsvTable t = uhpc::read_csv(path.string());
  EXPECT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.source(), path.string());
  std::filesystem::remove(path);
}

}  // namespace
