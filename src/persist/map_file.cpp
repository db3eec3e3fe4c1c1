#include "persist/map_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace eco::detail {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  throw std::runtime_error(path + ": " + what + ": " + std::strerror(error));
}

/// Closes a file descriptor when it goes out of scope.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

FileBytes::FileBytes(FileBytes&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

FileBytes& FileBytes::operator=(FileBytes&& other) noexcept {
  std::swap(data_, other.data_);
  std::swap(size_, other.size_);
  return *this;
}

FileBytes::~FileBytes() {
  if (size_ > 0) ::munmap(const_cast<void*>(data_), size_);  // NOLINT: mapped read-only by us
}

FileBytes read_whole_file(const std::string& path) {
  Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) fail(path, "cannot open", errno);
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) fail(path, "cannot read", errno);
  if (!S_ISREG(info.st_mode)) throw std::runtime_error(path + ": not a regular file");
  const auto size = std::size_t(info.st_size);
  if (size == 0) return {};  // nothing to map (and mmap refuses a length of 0)
  void* data = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
  if (data == MAP_FAILED) fail(path, "cannot read", errno);
  return {data, size};
}

void write_replacing(const std::string& path, std::string_view bytes) {
  std::string temporary = path + ".XXXXXX";
  Descriptor file{::mkstemp(temporary.data())};
  if (file.fd < 0) fail(path, "cannot create a file beside it", errno);
  const auto give_up = [&](const char* what) {
    const int error = errno;
    ::close(std::exchange(file.fd, -1));
    ::unlink(temporary.c_str());
    fail(path, what, error);
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(file.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) give_up("cannot write");
    done += std::size_t(n);
  }
  if (::fchmod(file.fd, 0644) != 0) give_up("cannot set the file's permissions");
  if (::fsync(file.fd) != 0) give_up("cannot flush to the disk");
  if (::close(std::exchange(file.fd, -1)) != 0) give_up("cannot close");
  if (::rename(temporary.c_str(), path.c_str()) != 0) give_up("cannot replace");
}

}  // namespace eco::detail
