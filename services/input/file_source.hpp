#pragma once
// A recorded stream read from a file (replay, tests). Pacing in real time is the owner's job (it
// knows the epochs in the data, see RealTimePacer); the file only hands out chunks.
#include <string>

#include "services/input/byte_source.hpp"

namespace ldv::io {

class FileSource : public ByteSource {
 public:
  explicit FileSource(std::string path);
  ~FileSource() override;
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;

  void maintain(double now_s) override;
  int fd() const override { return finished_ ? -1 : fd_; }
  std::size_t read_some(std::span<std::uint8_t> buffer, double now_s) override;
  bool finished() const override { return finished_; }
  std::string describe() const override { return "file " + path_; }

 private:
  std::string path_;
  int fd_ = -1;
  bool finished_ = false;
  bool reported_missing_ = false;
  bool fifo_ = false;  // a FIFO: no end of file, a writer may come again
  double reopen_at_s_ = -1e300;
  static constexpr double kFifoReopen_s = 0.2;
};

}  // namespace ldv::io
