#pragma once
// Writing that cannot fail silently: every write, the flush and the close are checked, and an error (a full
// disk, /dev/full, a vanished NFS mount) raises InputError naming the file, so a tool never reports a
// truncated file as written. A file not closed by close() (an exception unwinding) is flushed and closed by
// the destructor, which only logs an error: what was recorded before the exception stays on disk.
#include <cstdio>
#include <fstream>
#include <string>

namespace ldv {

class OutputFile {
 public:
  explicit OutputFile(const std::string& path);  // throws InputError if it cannot be created
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  void write(const char* data, size_t n);  // throws InputError on a write error
  void write(const std::string& s) { write(s.data(), s.size()); }
  void close();  // flushes and closes; throws InputError on an error (a second call does nothing)
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

// For writers built on std::ofstream: flushes and closes `out`, throws InputError naming `path` if any write,
// the flush or the close failed.
void close_checked(std::ofstream& out, const std::string& path);
// The same for a C stream: flushes and closes `f` (always), throws InputError naming `path` on any error.
void close_checked(std::FILE* f, const std::string& path);

}  // namespace ldv
