// Delimited tables as people publish them (common/io/delimited_table.hpp): the layout is read from the file, the
// columns named as the user names them. Checked against files whose layout is known: the real MPU-6050 log in
// ../shared (four preamble lines, then a header), and tables written here as spreadsheets and loggers write them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/io/delimited_table.hpp"
#include "common/io/input_error.hpp"

namespace ldv {
namespace {

namespace fs = std::filesystem;

std::string write_table_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("ldv_table_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

// Every row's fields as numbers (the test's own reading).
std::vector<std::vector<double>> rows_of(const std::string& path, const TableLayout& layout) {
  std::vector<std::vector<double>> rows;
  for_each_table_row(path, layout, [&](long, const std::vector<std::string_view>& fields) {
    std::vector<double> r;
    for (const std::string_view f : fields) {
      double v = NAN;
      parse_table_number(f, layout, v);
      r.push_back(v);
    }
    rows.push_back(r);
  });
  return rows;
}

TEST(DelimitedTable, GivenTheRealMpu6050LogWithFourPreambleLines_ThenItsHeaderAndRowsAreFound) {
  const std::string path = std::string(LDV_SHARED_DATA_DIR) + "/calib/mpu6050/static_7min.csv";
  const TableLayout t = sniff_table_layout(path);
  EXPECT_EQ(t.separator, ',');
  EXPECT_EQ(t.columns, 6);
  EXPECT_EQ(t.header_line, 5);
  EXPECT_EQ(t.first_row_line, 6);
  EXPECT_EQ(t.header, (std::vector<std::string>{"ax", "ay", "az", "gx", "gy", "gz"}));
  EXPECT_EQ(table_column(t, "gx", path, "gyro.columns"), 3);
  EXPECT_EQ(table_column(t, "GZ", path, "gyro.columns"), 5);  // the only case-insensitive match
  EXPECT_EQ(table_column(t, "2", path, "accel.columns"), 1);  // by 1-based index
  long rows = 0;
  std::vector<double> first;
  for_each_table_row(path, t, [&](long line, const std::vector<std::string_view>& f) {
    if (rows++ == 0) {
      EXPECT_EQ(line, 6);
      for (const auto x : f) {
        double v = 0;
        ASSERT_TRUE(parse_table_number(x, t, v));
        first.push_back(v);
      }
    }
  });
  EXPECT_EQ(first, (std::vector<double>{2508, -604, 14684, -429, 140, -53}));  // line 6 of the file
  EXPECT_GT(rows, 40000);                                                      // 7 min at 100 Hz
}

TEST(DelimitedTable, GivenASpreadsheetExportWithSepLineQuotedNamesAndDecimalCommas_ThenTheNumbersAreRead) {
  const std::string path = write_table_file(
      "excel.csv", "sep=;\r\n\"Time [s]\";\"Acc X\";\"Acc Y\"\r\n0,00;0,5;-9,81\r\n0,01;0,25;-9,8\r\n");
  const TableLayout t = sniff_table_layout(path);
  EXPECT_EQ(t.separator, ';');
  EXPECT_TRUE(t.decimal_comma);
  EXPECT_EQ(t.header, (std::vector<std::string>{"Time [s]", "Acc X", "Acc Y"}));
  EXPECT_EQ(t.first_row_line, 3);
  const auto rows = rows_of(path, t);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[1][0], 0.01);
  EXPECT_DOUBLE_EQ(rows[1][1], 0.25);
  EXPECT_DOUBLE_EQ(rows[0][2], -9.81);
  fs::remove(path);
}

TEST(DelimitedTable, GivenAWhitespaceListingWithACommentedHeaderAndATextDateColumn_ThenTheRowsStartAfterIt) {
  const std::string path = write_table_file("listing.txt",
                                            "% recorded by logger v2\n%  date       time_s    lat           lon\n"
                                            "2024-05-01  1.000  40.0966933  -105.1471668\n"
                                            "2024-05-01  1.200  40.0966934  -105.1471669\n"
                                            "# a comment inside\n"
                                            "2024-05-01  1.400  40.0966935  -105.1471670\n");
  const TableLayout t = sniff_table_layout(path);
  EXPECT_EQ(t.separator, ' ');
  EXPECT_EQ(t.columns, 4);
  EXPECT_EQ(t.header, (std::vector<std::string>{"date", "time_s", "lat", "lon"}));
  EXPECT_EQ(t.first_row_line, 3);
  const auto rows = rows_of(path, t);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_DOUBLE_EQ(rows[2][table_column(t, "lon", path, "position.columns")], -105.1471670);
  fs::remove(path);
}

TEST(DelimitedTable, GivenAQuotedFieldHoldingTheSeparator_ThenItStaysOneField) {
  const std::string path = write_table_file("quoted.csv", "name,t,x\n\"a, b\",1,2\n\"c, d\",2,3\n");
  const TableLayout t = sniff_table_layout(path);
  EXPECT_EQ(t.columns, 3);
  const auto rows = rows_of(path, t);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[1][2], 3.0);
  fs::remove(path);
}

TEST(DelimitedTable, GivenNoHeader_ThenColumnsAreByIndexAndANameIsRefusedSayingSo) {
  const std::string path = write_table_file("bare.txt", "1 2 3\n4 5 6\n");
  const TableLayout t = sniff_table_layout(path);
  EXPECT_TRUE(t.header.empty());
  EXPECT_EQ(t.first_row_line, 1);
  EXPECT_EQ(table_column(t, "3", path, "gyro.columns"), 2);
  try {
    table_column(t, "gx", path, "imu_table.gyro.columns");
    FAIL() << "a name in a file without a header";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("imu_table.gyro.columns: no column 'gx'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no header"), std::string::npos) << e.what();
  }
  EXPECT_THROW(table_column(t, "4", path, "gyro.columns"), InputError);
  fs::remove(path);
}

TEST(DelimitedTable, GivenAnUnknownColumnName_ThenTheErrorNamesTheFileTheKeyAndTheHeader) {
  const std::string path = write_table_file("named.csv", "t,gx,gy\n1,2,3\n");
  const TableLayout t = sniff_table_layout(path);
  try {
    table_column(t, "Gyro_X", path, "imu_table.gyro.columns");
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path + ":1: imu_table.gyro.columns: no column 'Gyro_X' (the header names: t, gx, gy)"),
              std::string::npos)
        << m;
  }
  fs::remove(path);
}

TEST(DelimitedTable, GivenAFileWithoutNumbers_ThenTheErrorSaysSo) {
  const std::string path = write_table_file("words.txt", "a,b\nc,d\n");
  EXPECT_THROW(sniff_table_layout(path), InputError);
  const std::string empty = write_table_file("empty.txt", "");
  EXPECT_THROW(sniff_table_layout(empty), InputError);
  fs::remove(path);
  fs::remove(empty);
}

}  // namespace
}  // namespace ldv
