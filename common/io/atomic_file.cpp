#include "common/io/atomic_file.hpp"

#include <filesystem>
#include <fstream>

namespace ldv {

bool write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::error_code ec;
  // The rename would replace whatever is there: a device (/dev/zero given as an output), a directory
  // entry of another kind. Only a regular file, or nothing, may be replaced.
  const auto status = std::filesystem::symlink_status(path, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) return false;
  ec.clear();
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    const bool written = out && (out << text) && out.flush();
    out.close();  // checked too: the rename must never put an incomplete file in place of a good one
    if (!written || out.fail()) {
      std::filesystem::remove(tmp, ec);
      return false;
    }
  }
  std::filesystem::rename(tmp, path, ec);
  return !ec;
}

}  // namespace ldv
