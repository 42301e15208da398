#include "common/plot/gnuplot.hpp"

#include "common/io/run_program.hpp"

namespace ldv::plot {
namespace {

std::string quoted(std::string_view text, bool enhanced) {
  std::string o = "'";
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {  // line breaks, NUL and other controls: never part of a literal
      o += ' ';
      continue;
    }
    if (c == '\'') {
      o += "''";
      continue;
    }
    if (enhanced && (c == '_' || c == '^' || c == '{' || c == '}' || c == '@' || c == '&' || c == '~' || c == '\\'))
      o += '\\';
    o += c;
  }
  return o + "'";
}

}  // namespace

std::string gnuplot_label(std::string_view text) { return quoted(text, true); }
std::string gnuplot_literal(std::string_view text) { return quoted(text, false); }

int run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& work_dir,
                const std::filesystem::path& log_path) {
  // A relative name starting with '-' would read as an option.
  const std::string script_arg = script.is_absolute() ? script.string() : "./" + script.string();
  return run_program({"gnuplot", script_arg}, work_dir, "/dev/null", log_path);
}

}  // namespace ldv::plot
