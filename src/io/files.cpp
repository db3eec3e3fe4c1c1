#include "io/files.hpp"

#include <eco/io/error.hpp>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace eco::io::detail {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path.string(), "", "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path.string(), "", "read failed");
  return bytes;
}

void write_file(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(path.string(), "", std::string("cannot create: ") + std::strerror(errno));
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw Error(path.string(), "", "write failed");
}

void require_directory(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path.string(), "", "no such folder");
  if (!fs::is_directory(path, ec)) throw Error(path.string(), "", "is not a folder");
}

}  // namespace eco::io::detail
