#pragma once
// Small state files that a restart reads back (fusion's warm start, imu_acq's PPS fit): written to
// PATH.tmp and renamed over PATH, so a reader never sees half a file, whatever moment a crash comes.
#include <string>

namespace ldv {

// False when the directory is not writable (callers carry on: a state file is an optimisation), or
// when PATH exists and is not a regular file (a device, a FIFO, a symbolic link): never replaced.
bool write_file_atomically(const std::string& path, const std::string& text);

}  // namespace ldv
