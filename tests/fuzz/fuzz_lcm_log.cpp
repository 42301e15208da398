// LCM event logs (ldv export, ldv nav --lcm-log): the reader returns only intact events within the file's
// bytes, never throws past the constructor's InputError, and always reaches the end.
#include "common/bus/lcm_log_reader.hpp"
#include "common/io/input_error.hpp"
#include "tests/fuzz/fuzz_support.hpp"

using namespace ldv;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::input_file(data, size, "lcmlog");
  try {
    LcmLogReader log(path);
    LcmLogEvent ev;
    size_t bytes = 0;
    long events = 0;
    while (log.next(ev)) {
      bytes += ev.channel.size() + ev.data.size();
      fuzz::require(bytes <= size, "events hold more bytes than the file");
      fuzz::require(++events <= static_cast<long>(size / 28 + 1), "more events than the file can hold");
    }
  } catch (const InputError&) {
  }
  return 0;
}
