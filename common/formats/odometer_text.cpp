#include "common/formats/odometer_text.hpp"

#include <cmath>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/io/text_file_lines.hpp"
#include "common/io/text_table.hpp"
#include "common/time/gps_time.hpp"

namespace ldv {

std::vector<OdometerSample> read_odometer_text(const std::string& path) {
  std::vector<OdometerSample> out;
  TextFileLines lines(path);
  std::string_view text;
  double v[2];
  FieldError err;
  while (lines.next(text)) {
    const long line = lines.line_number();
    const int n = scan_numeric_line(text, v, 2, &err);
    if (n == 0) continue;
    if (n < 0) throw InputError(path, line, "expected 'sow speed_mps' (2 numbers): " + err.message());
    if (n != 2) throw InputError(path, line, "expected 2 columns 'sow speed_mps', found " + std::to_string(n));
    if (!(v[0] >= 0.0 && v[0] < kSecondsPerWeek))
      throw InputError(path, line,
                       "column 1 (sow): expected GPS seconds of week in [0, 604800), found " + std::to_string(v[0]));
    if (!out.empty() && !(v[0] > out.back().t_s))
      throw InputError(path, line,
                       "column 1 (sow): expected a time after the previous line's " + std::to_string(out.back().t_s) +
                           " s, found " + std::to_string(v[0]) + " s");
    out.push_back({v[0], v[1]});
  }
  if (out.empty()) throw InputError(path, 0, "expected odometer samples 'sow speed_mps', found none");
  return out;
}

void write_odometer_text(const std::string& path, const std::vector<OdometerSample>& samples) {
  OutputFile f(path);
  std::string buf;
  buf.reserve(static_cast<size_t>(1) << 16);
  char line[2 * kFormatFixedMaxChars + 4];
  long row = 0;
  for (const OdometerSample& s : samples) {
    ++row;
    if (!std::isfinite(s.t_s) || !std::isfinite(s.speed_mps))
      throw InputError(path, row, "cannot write a non-finite odometer sample (t " + std::to_string(s.t_s) + " s)");
    int n = format_fixed(line, s.t_s, 6);
    line[n++] = ' ';
    n += format_fixed(line + n, s.speed_mps, 6);
    line[n++] = '\n';
    buf.append(line, static_cast<size_t>(n));
    if (buf.size() > (static_cast<size_t>(1) << 16) - 256) {
      f.write(buf);
      buf.clear();
    }
  }
  f.write(buf);
  f.close();
}

}  // namespace ldv
