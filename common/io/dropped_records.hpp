#pragma once
// What a reader dropped, counted by reason, with the first occurrence of each reason as "file:line: message"
// (the readers' results carry one; `ldv nav` prints it and warns when a file loses more than a few percent).
#include <array>
#include <string>

namespace ldv {

enum class DropReason : int {
  kMalformed = 0,  // a field is not a number (or a cut line)
  kWrongColumns,   // the column count differs from the one the file declares or started with
  kNonFinite,      // nan / inf
  kTimeBackwards,  // time (or counter) earlier than the record before
  kRepeated,       // the same time (or counter) as the record before
  kTimeJump,       // one record far ahead of both neighbours (a corrupted time stamp)
  kOutOfRange,     // a value outside its physical or declared range
  kCount
};

const char* to_string(DropReason reason);

struct DroppedRecords {
  std::array<long, static_cast<int>(DropReason::kCount)> count{};
  std::array<std::string, static_cast<int>(DropReason::kCount)> first{};  // "file:line: message"

  // Counts one dropped record; the first few of each reason are logged (spdlog warn) with file and line.
  void add(DropReason reason, const std::string& file, long line, const std::string& message);
  long operator[](DropReason r) const { return count[static_cast<int>(r)]; }
  long total() const;
  // "3 wrong column count (first: imu.txt:17: expected 7 columns, found 8), 1 time backwards (...)", or "none".
  std::string describe() const;
};

}  // namespace ldv
