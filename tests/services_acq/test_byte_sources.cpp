// The byte sources: a serial port (through a pty, raw mode), a TCP client that reconnects after
// the server drops it, a file that finishes. Loopback only.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "services/input/file_source.hpp"
#include "services/input/serial_port.hpp"
#include "services/input/tcp_client.hpp"
#include "services/input/wait_readable.hpp"
#include "services/runtime/service_runtime.hpp"

using namespace ldv;
using namespace ldv::io;

namespace {
// Reads from `src` until `want` bytes arrived or timeout_s passed.
std::string read_for(ByteSource& src, std::size_t want, double timeout_s) {
  std::string got;
  std::vector<std::uint8_t> buf(4096);
  const double end = host_time_s() + timeout_s;
  while (got.size() < want && host_time_s() < end) {
    src.maintain(host_time_s());
    const auto ready = wait_readable<1>({src.fd()}, 10);
    if (ready[0]) {
      const std::size_t n = src.read_some(buf, host_time_s());
      got.append(reinterpret_cast<const char*>(buf.data()), n);
    }
  }
  return got;
}
}  // namespace

TEST(SerialPort, GivenAPty_ThenRawBytesIncludingControlCharactersArriveUnchanged) {
  int master = -1, slave = -1;
  char name[256];
  ASSERT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
  SerialPort port({name, 460800});
  port.maintain(host_time_s());
  ASSERT_GE(port.fd(), 0);
  // CR, LF, ^C, ^S, 0xFF: a cooked tty would translate or eat these.
  const std::string bytes("\r\n\x03\x13\xff\x00$GPGGA", 12);
  ASSERT_EQ(::write(master, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  EXPECT_EQ(read_for(port, bytes.size(), 2.0), bytes);
  ::close(slave);
  ::close(master);  // hang-up: the port closes and keeps retrying, never throws
  read_for(port, 1, 0.3);
  EXPECT_EQ(port.fd(), -1);
  EXPECT_EQ(port.counters().disconnects, 1u);
}

TEST(SerialPort, GivenAMissingDeviceOrABadBaud_ThenItRetriesQuietly) {
  SerialPort missing({"/dev/does-not-exist", 115200, 0.01, 0.02});
  for (int i = 0; i < 5; ++i) {
    missing.maintain(host_time_s());
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
  }
  EXPECT_EQ(missing.fd(), -1);
  EXPECT_GE(missing.counters().open_failures, 2u);
  EXPECT_EQ(baud_constant(12345), 0u);
}

TEST(TcpClient, GivenAServerThatDropsTheConnection_ThenItReconnectsWithBackoff) {
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&addr), &len);
  ::listen(listener, 1);
  const int port = ntohs(addr.sin_port);

  TcpClient client({"127.0.0.1", port, 0.05, 0.2});
  for (const std::string msg : {"first connection\n", "second connection\n"}) {
    std::thread server([&] {
      const int c = ::accept(listener, nullptr, nullptr);
      ::send(c, msg.data(), msg.size(), 0);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      ::close(c);
    });
    EXPECT_EQ(read_for(client, msg.size(), 3.0), msg);
    server.join();
    read_for(client, 1, 0.2);  // sees the close
  }
  EXPECT_GE(client.counters().opens, 2u);  // a third: the listen backlog accepts without accept()
  EXPECT_GE(client.counters().disconnects, 1u);
  ::close(listener);
}

TEST(FileSource, GivenAFile_ThenAllBytesThenFinished) {
  const auto path = std::filesystem::temp_directory_path() / ("ldv_file_source_" + std::to_string(::getpid()));
  std::ofstream(path) << std::string(10000, 'x');
  FileSource f(path.string());
  EXPECT_EQ(read_for(f, 20000, 0.2).size(), 10000u);
  EXPECT_TRUE(f.finished());
  EXPECT_EQ(f.fd(), -1);
  std::filesystem::remove(path);
}

// Issue 46 (6): a service's file input that is a folder read as "end of file after 0 bytes", and a FIFO with no
// writer yet held the service in open() before READY. A folder is said for what it is and retried; a FIFO opens at
// once, hands out what a writer sends, and waits for the next writer instead of ending.
TEST(FileSource, GivenAFolderOrAFifo_ThenNothingBlocksAndNothingEndsInSilence) {
  const auto dir = std::filesystem::temp_directory_path() / ("ldv_file_source_dir_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  FileSource folder(dir.string());
  folder.maintain(0.0);
  EXPECT_FALSE(folder.finished());
  EXPECT_EQ(folder.counters().opens, 0u);
  EXPECT_GE(folder.counters().open_failures, 1u);

  const auto fifo = dir / "stream.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  FileSource source(fifo.string());
  const auto t0 = std::chrono::steady_clock::now();
  source.maintain(0.0);  // no writer: must not block
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(500));
  EXPECT_EQ(source.counters().opens, 1u);
  const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  ASSERT_GE(writer, 0);
  ASSERT_EQ(::write(writer, "abcdef", 6), 6);
  ::close(writer);
  std::array<std::uint8_t, 64> buffer{};
  std::size_t got = 0;
  for (int i = 0; i < 10 && got < 6; ++i) got += source.read_some(buffer, 0.0);
  EXPECT_EQ(got, 6u);
  source.read_some(buffer, 0.0);  // the writer is gone
  EXPECT_FALSE(source.finished()) << "a FIFO has no end of file";
  std::filesystem::remove_all(dir);
}
