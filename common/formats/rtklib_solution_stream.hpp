#pragma once
// The rtkrcv TCP solution stream (or a .pos file read in chunks): bytes in any chunking -> one
// callback per solution line; malformed and overlong lines are counted and skipped.
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "common/formats/rtklib_solution.hpp"

namespace ldv::gnss {

struct RtklibStreamCounters {
  std::uint64_t solutions = 0;
  std::uint64_t header_lines = 0;
  std::uint64_t malformed_lines = 0;
  std::uint64_t overlong_lines = 0;  // longer than max_line_chars: dropped
};

class RtklibSolutionStream {
 public:
  using SolutionHandler = std::function<void(const GnssSolution&)>;

  explicit RtklibSolutionStream(SolutionHandler on_solution, RtklibParserOptions options = {},
                                std::size_t max_line_chars = 1024);

  void feed(std::span<const std::uint8_t> bytes);
  void feed(std::string_view text);
  // A final line without its line end (end of file).
  void flush();
  const RtklibStreamCounters& counters() const { return counters_; }
  const std::string& last_error() const { return last_error_; }

 private:
  void end_line();

  SolutionHandler on_solution_;
  RtklibSolutionParser parser_;
  std::size_t max_line_chars_;
  RtklibStreamCounters counters_;
  std::string line_;
  bool discarding_ = false;  // inside an overlong line
  std::string last_error_;
};

}  // namespace ldv::gnss
