#pragma once
// The one exception type for bad input: it names the file, the line (0 when not line-based),
// the field, and what was expected, so a user can fix the input without reading our code.
#include <stdexcept>
#include <string>

namespace ldv {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, long line, std::string what_was_expected)
      : std::runtime_error(compose(file, line, what_was_expected)),
        file_(std::move(file)),
        line_(line) {}
  const std::string& file() const { return file_; }
  long line() const { return line_; }

 private:
  static std::string compose(const std::string& file, long line, const std::string& msg) {
    return file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + msg;
  }
  std::string file_;
  long line_;
};

}  // namespace ldv
