#include "services/runtime/log_rotation.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <system_error>

#include <lcm/lcm-cpp.hpp>

#include "common/logging.hpp"

namespace ldv {
namespace fs = std::filesystem;

namespace {
constexpr double kMiB = 1024.0 * 1024.0;
constexpr size_t kStampLength = 16;  // 20250131T120000Z
// An event on disk: sync word, event number, timestamp, channel length, data length, channel, data.
constexpr uint64_t kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;

std::string utc_stamp(double t_s) {
  const time_t t = static_cast<time_t>(std::floor(t_s));
  tm u{};
  gmtime_r(&t, &u);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%dT%H%M%SZ", &u);
  return buf;
}

// The index of `name` if it is `<stem>.<digits>.<stamp><ext>`, else -1.
int64_t index_of(const std::string& name, const std::string& stem, const std::string& ext) {
  const std::string prefix = stem + ".";
  if (name.size() <= prefix.size() + 1 + kStampLength + ext.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  if (name.compare(name.size() - ext.size(), ext.size(), ext) != 0) return -1;
  size_t i = prefix.size(), digits_end = i;
  while (digits_end < name.size() && std::isdigit(static_cast<unsigned char>(name[digits_end]))) ++digits_end;
  if (digits_end - i < 6 || digits_end - i > 18 || digits_end >= name.size() || name[digits_end] != '.') return -1;
  const std::string stamp = name.substr(digits_end + 1, name.size() - ext.size() - digits_end - 1);
  if (stamp.size() != kStampLength || stamp[8] != 'T' || stamp[15] != 'Z') return -1;
  return std::stoll(name.substr(i, digits_end - i));
}
}  // namespace

void LogRotationOptions::validate() const {
  if (path.empty()) throw std::invalid_argument("log path is empty");
  for (const double v : {max_file_mb, max_file_min, max_total_mb, max_age_h, min_free_mb})
    if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument("log rotation limits must be finite and >= 0");
  if (!rotating() && (max_total_mb > 0 || max_age_h > 0 || min_free_mb > 0))
    throw std::invalid_argument("--max-total-mb, --max-age-h and --min-free-mb delete completed files: give --max-file-mb or "
                                "--max-file-min too (one file that is never completed cannot be deleted)");
  if (max_total_mb > 0 && max_file_mb > 0 && max_total_mb < max_file_mb)
    throw std::invalid_argument("--max-total-mb (" + std::to_string(max_total_mb) + ") is smaller than --max-file-mb (" +
                                std::to_string(max_file_mb) + ")");
}

RotatingLogWriter::RotatingLogWriter(LogRotationOptions options, std::function<double()> now_s)
    : o_(std::move(options)), now_s_(std::move(now_s)) {
  o_.validate();
  const fs::path p(o_.path);
  dir_ = p.has_parent_path() ? p.parent_path().string() : ".";
  stem_ = p.stem().string();
  ext_ = p.extension().string();
  if (!o_.rotating()) {
    log_ = std::make_unique<lcm::LogFile>(o_.path, "w");
    if (!log_->good()) throw std::runtime_error("cannot open " + o_.path + " for writing");
    current_path_ = o_.path;
    opened_s_ = now_s_();
    return;
  }
  open_next();
}

RotatingLogWriter::~RotatingLogWriter() = default;

std::vector<RotatingLogWriter::LogFileInfo> RotatingLogWriter::files() const {
  std::vector<LogFileInfo> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir_, ec)) {
    const int64_t index = index_of(entry.path().filename().string(), stem_, ext_);
    if (index < 0) continue;
    struct stat st{};
    if (::stat(entry.path().c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    out.push_back({entry.path().string(), index, static_cast<uint64_t>(st.st_size), st.st_mtim.tv_sec + 1e-9 * st.st_mtim.tv_nsec});
  }
  std::sort(out.begin(), out.end(), [](const LogFileInfo& a, const LogFileInfo& b) { return a.index < b.index; });
  return out;
}

void RotatingLogWriter::open_next() {
  int64_t next = current_index_ + 1;
  if (current_index_ < 0)
    for (const auto& f : files()) next = std::max(next, f.index + 1);
  const double now = now_s_();
  char index[32];
  std::string path;
  for (;; ++next) {  // never reuse a name, whatever else lies in the directory
    std::snprintf(index, sizeof index, "%06lld", static_cast<long long>(next));
    path = (fs::path(dir_) / (stem_ + "." + index + "." + utc_stamp(now) + ext_)).string();
    std::error_code ec;  // a name the system cannot look up is not taken: the open below names it
    if (!fs::exists(path, ec)) break;
  }
  auto log = std::make_unique<lcm::LogFile>(path, "w");
  if (!log->good()) throw std::runtime_error("cannot open " + path + " for writing");
  if (log_) {
    std::fflush(log_->getFilePtr());
    ++rotations_;
  }
  log_ = std::move(log);  // closes the completed file
  current_path_ = path;
  current_index_ = next;
  current_bytes_ = 0;
  opened_s_ = now;
  spdlog::info("ldv_logger: writing {}", path);
  enforce_retention();
}

bool RotatingLogWriter::write(const std::string& channel, const uint8_t* data, int size, int64_t timestamp_us) {
  if (o_.rotating()) {
    const bool full = o_.max_file_mb > 0 && current_bytes_ >= static_cast<uint64_t>(o_.max_file_mb * kMiB);
    const bool old = o_.max_file_min > 0 && now_s_() - opened_s_ >= o_.max_file_min * 60.0;
    if (full || old) {
      try {
        open_next();
      } catch (const std::exception& e) {  // e.g. the directory vanished: keep writing the current file
        spdlog::error("ldv_logger: cannot start the next file: {}", e.what());
      }
    }
  }
  lcm::LogEvent e{};
  e.eventnum = event_number_++;
  e.timestamp = timestamp_us;
  e.channel = channel;
  e.datalen = size;
  e.data = const_cast<uint8_t*>(data);
  if (log_->writeEvent(&e) != 0) return false;
  current_bytes_ += kEventHeaderBytes + channel.size() + static_cast<uint64_t>(size);
  return true;
}

void RotatingLogWriter::flush() { std::fflush(log_->getFilePtr()); }

void RotatingLogWriter::enforce_retention() {
  if (!o_.rotating()) return;
  std::vector<LogFileInfo> all = files();
  uint64_t total = 0;
  for (const auto& f : all) total += f.index == current_index_ ? current_bytes_ : f.bytes;
  const double now = now_s_();
  auto remove = [&](const LogFileInfo& f, const char* why) {
    std::error_code ec;
    if (!fs::remove(f.path, ec) && ec) {
      spdlog::warn("ldv_logger: cannot delete {}: {}", f.path, ec.message());
      return false;
    }
    ++files_deleted_;
    total -= std::min(total, f.bytes);
    spdlog::info("ldv_logger: deleted {} ({:.1f} MiB, {})", f.path, f.bytes / kMiB, why);
    return true;
  };
  auto free_mb = [&]() {
    struct statvfs v{};
    if (::statvfs(dir_.c_str(), &v) != 0) return std::numeric_limits<double>::infinity();
    return static_cast<double>(v.f_bavail) * v.f_frsize / kMiB;
  };
  // Oldest first; the file being written is never a candidate.
  for (const auto& f : all) {
    if (f.index >= current_index_) break;
    bool too_old = o_.max_age_h > 0 && now - f.mtime_s > o_.max_age_h * 3600.0;
    bool over_total = o_.max_total_mb > 0 && total > static_cast<uint64_t>(o_.max_total_mb * kMiB);
    bool low_space = o_.min_free_mb > 0 && free_mb() < o_.min_free_mb;
    if (!too_old && !over_total && !low_space) continue;
    remove(f, too_old ? "older than --max-age-h" : over_total ? "over --max-total-mb" : "under --min-free-mb");
  }
}

}  // namespace ldv
