#include "common/io/dropped_records.hpp"

#include "common/logging.hpp"

namespace ldv {

const char* to_string(DropReason reason) {
  switch (reason) {
    case DropReason::kMalformed:
      return "malformed";
    case DropReason::kWrongColumns:
      return "wrong column count";
    case DropReason::kNonFinite:
      return "non-finite";
    case DropReason::kTimeBackwards:
      return "time backwards";
    case DropReason::kRepeated:
      return "repeated time";
    case DropReason::kTimeJump:
      return "time jump";
    case DropReason::kOutOfRange:
      return "out of range";
    case DropReason::kCount:
      break;
  }
  return "?";
}

void DroppedRecords::add(DropReason reason, const std::string& file, long line, const std::string& message) {
  constexpr long kLoggedPerReason = 5;  // enough to find the lines; a broken file must not flood the log
  const int i = static_cast<int>(reason);
  const std::string where = file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message;
  if (count[i] == 0) first[i] = where;
  if (count[i] < kLoggedPerReason) spdlog::warn("dropped ({}): {}", to_string(reason), where);
  ++count[i];
}

long DroppedRecords::total() const {
  long n = 0;
  for (long c : count) n += c;
  return n;
}

std::string DroppedRecords::describe() const {
  std::string s;
  for (int i = 0; i < static_cast<int>(DropReason::kCount); ++i) {
    if (count[i] == 0) continue;
    s += (s.empty() ? "" : ", ") + std::to_string(count[i]) + " " + to_string(static_cast<DropReason>(i)) +
         " (first: " + first[i] + ")";
  }
  return s.empty() ? "none" : s;
}

}  // namespace ldv
