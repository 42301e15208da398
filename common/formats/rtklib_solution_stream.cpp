#include "common/formats/rtklib_solution_stream.hpp"

namespace ldv::gnss {

RtklibSolutionStream::RtklibSolutionStream(SolutionHandler on_solution, RtklibParserOptions options,
                                           std::size_t max_line_chars)
    : on_solution_(std::move(on_solution)), parser_(std::move(options)), max_line_chars_(max_line_chars) {}

void RtklibSolutionStream::feed(std::string_view text) {
  feed(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void RtklibSolutionStream::feed(std::span<const std::uint8_t> bytes) {
  for (std::uint8_t b : bytes) {
    if (b == '\n') {
      end_line();
    } else if (discarding_) {
      continue;
    } else if (line_.size() >= max_line_chars_) {
      ++counters_.overlong_lines;
      discarding_ = true;
      line_.clear();
    } else {
      line_.push_back(static_cast<char>(b));
    }
  }
}

void RtklibSolutionStream::flush() {
  if (!line_.empty()) end_line();
}

void RtklibSolutionStream::end_line() {
  if (discarding_) {
    discarding_ = false;
    line_.clear();
    return;
  }
  GnssSolution s;
  switch (parser_.parse_line(line_, s, &last_error_)) {
    case RtklibSolutionParser::LineKind::kSolution:
      ++counters_.solutions;
      if (on_solution_) on_solution_(s);
      break;
    case RtklibSolutionParser::LineKind::kHeader: ++counters_.header_lines; break;
    case RtklibSolutionParser::LineKind::kMalformed: ++counters_.malformed_lines; break;
    case RtklibSolutionParser::LineKind::kEmpty: break;
  }
  line_.clear();
}

}  // namespace ldv::gnss
