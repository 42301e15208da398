// Text from users' data reaches gnuplot scripts (CSV column names, JSON units, labels). Given hostile
// text that would run a shell command if it escaped its string literal, when the plot is made, then no
// command runs, gnuplot reads the text back exactly as given, and the plot is still made.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.hpp"
#include "common/plot/gnuplot.hpp"

namespace fs = std::filesystem;
using ldv::test::run_ldv;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("ldv_inject_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Every way out of a gnuplot string into a command: closing quote, backquote substitution, a line break
// that ends the literal, a macro, a backslash before the quote.
std::vector<std::string> hostile_texts(const fs::path& marker) {
  const std::string m = marker.string();
  return {"x'; system('touch " + m + "'); print '",
          "x`touch " + m + "`",
          "x\nsystem('touch " + m + "')\nprint 'y",
          "x\r\nsystem('touch " + m + "')",
          "@cmd x",
          "x\\'; system('touch " + m + "'); #",
          "x\"; system(\"touch " + m + "\"); #"};
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST(GnuplotQuoting, HostileTextIsReadBackAsTextAndRunsNothing) {
  const fs::path dir = fresh_dir("quoting"), marker = dir / "PWNED";
  for (const std::string& text : hostile_texts(marker)) {
    {
      std::ofstream gp(dir / "t.gp");
      gp << "cmd = \"system('touch " << marker.string() << "')\"\n"  // a macro that would run if expanded
         << "print " << ldv::plot::gnuplot_literal(text) << "\n"
         << "set title " << ldv::plot::gnuplot_label(text) << "\n";
    }
    ASSERT_EQ(ldv::plot::run_gnuplot("t.gp", dir, "t.log"), 0) << slurp(dir / "t.log");
    std::string expected = text;  // line breaks and other controls become spaces, nothing else changes
    for (char& c : expected)
      if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    EXPECT_EQ(slurp(dir / "t.log"), expected + "\n");
    EXPECT_FALSE(fs::exists(marker)) << "text ran a command: " << text;
  }
}

TEST(GnuplotQuoting, AllanPlotTitleFromACsvColumnName) {
  const fs::path dir = fresh_dir("allan"), marker = dir / "PWNED";
  // The header splits on commas and blanks: a name without either, that spells its space in octal.
  const std::string column = "gyro';system(\"touch\\040" + marker.string() + "\");print'";
  {
    std::ofstream csv(dir / "rate.csv");
    csv << "t," << column << "\n";
    unsigned s = 12345;
    for (int i = 0; i < 4000; ++i) {
      s = s * 1103515245u + 12345u;
      csv << i * 0.01 << "," << ((s >> 8) % 2001 - 1000.0) * 1e-6 << "\n";
    }
  }
  const auto r = run_ldv({"allan", (dir / "rate.csv").string(), "--time-column", "t", "--columns", column,
                          "--curve-only", "--plot", (dir / "allan.png").string()},
                         120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(marker)) << r.output;
  EXPECT_GT(fs::file_size(dir / "allan.png"), 1000u);
}

namespace {

// A straight drive east at 10 m/s as a `.nav` (week, sow, lat, lon, h, vn, ve, vd, roll, pitch, yaw).
void write_nav(const fs::path& p, double east_offset_m) {
  std::ofstream f(p);
  f.precision(12);
  for (int i = 0; i < 600; ++i) {
    const double t = 100.0 + 0.1 * i, east_m = 1.0 * i + east_offset_m;
    f << 2200 << " " << t << " " << 30.0 << " " << 114.0 + east_m / 96000.0 << " " << 20.0 << " 0 10 0 0 0 90\n";
  }
}

}  // namespace

TEST(GnuplotQuoting, ReportReferenceLabelAndAllanUnit) {
  const fs::path dir = fresh_dir("report"), marker = dir / "PWNED";
  write_nav(dir / "sol.nav", 0.0);
  write_nav(dir / "ref.nav", 0.05);
  const std::string hostile = "ref'; system('touch " + marker.string() + "'); print '";
  std::ofstream(dir / "allan.json")
      << "{\"tool\": \"ldv allan\", \"channels\": [{\"name\": \"gyro_x\", \"unit\": \"rad/s'; system('touch "
      << marker.string() << "'); print '\", \"taus_s\": [0.01, 0.1, 1, 10], \"oadev\": [1e-3, 3e-4, 1e-4, 4e-5]}]}\n";
  const auto r = run_ldv(
      {"report", "--nav", (dir / "sol.nav").string(), "--truth", (dir / "ref.nav").string(), "--reference-label",
       hostile, "--allan-json", (dir / "allan.json").string(), "--out", (dir / "page").string()},
      120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(marker)) << r.output;
  EXPECT_TRUE(fs::exists(dir / "page" / "index.html"));
}
