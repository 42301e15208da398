#include "estimator/smooth/rts_epoch_store.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ldv::est {
namespace {

std::string temp_dir() {
  const char* d = std::getenv("TMPDIR");
  return d && *d ? d : "/tmp";
}

[[noreturn]] void fail(const char* what) {
  throw std::runtime_error("the smoother's temporary file in " + temp_dir() + " ($TMPDIR): " + what + ": " +
                           std::strerror(errno));
}

// An unnamed file: created in $TMPDIR (or /tmp) and unlinked at once, so it goes when the process does.
std::FILE* unnamed_temp_file() {
  std::string path = temp_dir() + "/ldv_smooth_XXXXXX";
  const int fd = mkstemp(path.data());
  if (fd < 0) return nullptr;
  unlink(path.c_str());
  std::FILE* f = fdopen(fd, "w+b");
  if (!f) close(fd);
  return f;
}

// Symmetric matrices are stored as their upper triangle.
std::size_t tri(int n) { return static_cast<std::size_t>(n) * (n + 1) / 2; }

}  // namespace

RtsEpochStore::RtsEpochStore(int n, int m)
    : n_(n), m_(m), record_doubles_(1 + static_cast<std::size_t>(n) * n + 2 * tri(n) + n + m) {
  file_ = unnamed_temp_file();
  if (!file_) fail("cannot create it");
  buf_.resize(record_doubles_);
}

RtsEpochStore::~RtsEpochStore() {
  if (file_) std::fclose(file_);
}

void RtsEpochStore::seek_to(std::size_t k) const {
  if (fseeko(file_, static_cast<off_t>(k * record_doubles_ * sizeof(double)), SEEK_SET) != 0) fail("seek");
}

void RtsEpochStore::write_at(std::size_t k, const RtsEpoch& e) {
  if (e.Phi.rows() != n_ || e.Phi.cols() != n_ || e.P_prior.rows() != n_ || e.P_post.rows() != n_ ||
      e.dx.size() != n_ || e.x_eff.size() != m_)
    throw std::invalid_argument("RtsEpochStore: an epoch of the wrong size");
  double* p = buf_.data();
  *p++ = e.t_s;
  p = std::copy(e.Phi.data(), e.Phi.data() + static_cast<std::size_t>(n_) * n_, p);
  for (const Eigen::MatrixXd* M : {&e.P_prior, &e.P_post})
    for (int c = 0; c < n_; ++c)
      for (int r = 0; r <= c; ++r) *p++ = (*M)(r, c);
  p = std::copy(e.dx.data(), e.dx.data() + n_, p);
  std::copy(e.x_eff.data(), e.x_eff.data() + m_, p);
  seek_to(k);
  if (std::fwrite(buf_.data(), sizeof(double), record_doubles_, file_) != record_doubles_) fail("write (disk full?)");
}

void RtsEpochStore::append(const RtsEpoch& e) {
  write_at(t_s_.size(), e);
  t_s_.push_back(e.t_s);
}

void RtsEpochStore::truncate(std::size_t count) {
  if (count < t_s_.size()) t_s_.resize(count);  // later writes overwrite the dropped records
}

RtsEpoch RtsEpochStore::read(std::size_t k) const {
  if (k >= t_s_.size()) throw std::out_of_range("RtsEpochStore::read");
  if (std::fflush(file_) != 0) fail("write (disk full?)");
  seek_to(k);
  if (std::fread(buf_.data(), sizeof(double), record_doubles_, file_) != record_doubles_) fail("read");
  RtsEpoch e;
  const double* p = buf_.data();
  e.t_s = *p++;
  e.Phi = Eigen::Map<const Eigen::MatrixXd>(p, n_, n_);
  p += static_cast<std::size_t>(n_) * n_;
  for (Eigen::MatrixXd* M : {&e.P_prior, &e.P_post}) {
    M->resize(n_, n_);
    for (int c = 0; c < n_; ++c)
      for (int r = 0; r <= c; ++r) (*M)(r, c) = (*M)(c, r) = *p++;
  }
  e.dx = Eigen::Map<const Eigen::VectorXd>(p, n_);
  p += n_;
  e.x_eff = Eigen::Map<const Eigen::VectorXd>(p, m_);
  return e;
}

}  // namespace ldv::est
