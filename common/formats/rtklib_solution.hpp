#pragma once
// RTKLIB solution text: the .pos files rnx2rtkp/rtkpost write and the stream rtkrcv serves over
// TCP (the same lines). Supports every layout RTKLIB prints with its default separators:
//   time:     GPST or UTC, "yyyy/mm/dd hh:mm:ss.sss" or "week tow"
//   position: lat/lon/height in degrees (ddd.ddd or "ddd mm ss.sss"), x/y/z ECEF, or e/n/u
//             baseline (absolute position then needs the base: "% ref pos" header or options)
//   then Q, ns, the six signed-sqrt covariance terms, age, ratio, and optionally the velocity and
//   its six covariance terms.
// Header lines ('%') set the layout; without a header (a TCP client that joined late) the layout
// is inferred from the data: calendar vs week/tow from the '/', ECEF vs lat/lon from magnitude.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/formats/gnss_solution.hpp"

namespace ldv::gnss {

enum class RtklibPositionLayout { kUnknown, kLatLonDeg, kLatLonDms, kEcef, kEnuBaseline };

struct RtklibParserOptions {
  RtklibPositionLayout layout = RtklibPositionLayout::kUnknown;  // kUnknown: from header or data
  double gps_minus_utc_s = 18.0;          // used only when the header says UTC
  std::optional<Vec3> base_ecef_m;        // for e/n/u baselines when no "% ref pos" header
};

class RtklibSolutionParser {
 public:
  enum class LineKind { kSolution, kHeader, kEmpty, kMalformed };

  explicit RtklibSolutionParser(RtklibParserOptions options = {});

  // Parses one line (without its line end). kSolution fills `out`; kMalformed says why.
  LineKind parse_line(std::string_view line, GnssSolution& out, std::string* why = nullptr);

  RtklibPositionLayout layout() const { return options_.layout; }

 private:
  void parse_header(std::string_view line);

  RtklibParserOptions options_;
  bool utc_ = false;
  std::vector<std::string_view> fields_;
};

// What read_rtklib_pos skipped: malformed lines counted by reason (each of the first ten is logged with
// its file:line).
struct RtklibReadReport {
  long solutions = 0;
  std::map<std::string, long> malformed_by_reason;
  std::map<std::string, long> first_line_by_reason;  // 1-based file line of each reason's first
  long malformed() const {
    long n = 0;
    for (const auto& [why, count] : malformed_by_reason) n += count;
    return n;
  }
  std::string summary() const;  // "118 solutions, 2 malformed (position sigma not positive)"
};

// Reads a whole .pos file, in file order. Malformed lines (also non-positive sigmas and what
// gnss::implausibility refuses: a week of 1980, a height of 1e300 m) are skipped and counted; a file whose
// lines are all malformed, or more than kMaxMalformedFraction of them, throws InputError naming the first
// one's line and the counts.
constexpr double kMaxMalformedFraction = 0.10;
std::vector<GnssSolution> read_rtklib_pos(const std::string& path, RtklibParserOptions options = {},
                                          RtklibReadReport* report = nullptr);

}  // namespace ldv::gnss
