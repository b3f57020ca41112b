#include "p4/io/line_appender.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "p4/core/error.h"

namespace p4 {
namespace {

// The file's size up to and including its last '\n' (0 when it has none).
std::uintmax_t WholeLinesSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  std::streamoff end = in.tellg();
  constexpr std::streamoff kChunk = 4096;
  std::string chunk;
  while (end > 0) {
    const std::streamoff from = std::max<std::streamoff>(0, end - kChunk);
    chunk.resize(static_cast<std::size_t>(end - from));
    in.seekg(from);
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const auto last = chunk.rfind('\n');
    if (last != std::string::npos) return static_cast<std::uintmax_t>(from) + last + 1;
    end = from;
  }
  return 0;
}

}  // namespace

LineAppender::LineAppender(const std::string& path, bool resume) : path_(path) {
  namespace fs = std::filesystem;
  int flags = O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC;
  if (resume && fs::exists(path)) {
    std::error_code ec;
    const std::uintmax_t whole = WholeLinesSize(path);
    if (whole != fs::file_size(path, ec)) fs::resize_file(path, whole, ec);
    if (ec) throw Error(path + ": cannot drop its incomplete last line (" + ec.message() + ")");
    existing_.open(path, std::ios::binary);
    if (!existing_) throw Error(path + ": cannot read");
    if (existing_.peek() == std::ifstream::traits_type::eof()) existing_.close();
  } else {
    flags |= O_TRUNC;
  }
  fd_ = ::open(path.c_str(), flags, 0644);
  if (fd_ < 0) throw Error(path + ": cannot create the file (" + std::strerror(errno) + ")");
}

LineAppender::~LineAppender() {
  if (fd_ >= 0) ::close(fd_);
}

void LineAppender::Append(std::string_view lines) {
  std::string line;
  while (existing_.is_open() && !lines.empty()) {
    const std::size_t end = lines.find('\n');
    const std::string_view next = lines.substr(0, end);
    if (!std::getline(existing_, line)) {
      existing_.close();
      break;
    }
    if (line != next) {
      throw Error(fmt::format(
          "{}: line {} differs from the run made again ('{}' there, '{}' now): resume with the "
          "P4, options and sources that began the run",
          path_, found_ + 1, line, next));
    }
    ++found_;
    lines.remove_prefix(end == std::string_view::npos ? lines.size() : end + 1);
    if (existing_.peek() == std::ifstream::traits_type::eof()) existing_.close();
  }
  if (!lines.empty()) Write(lines);
}

void LineAppender::Write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(path_ + ": write failed (" + std::strerror(errno) + ")");
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace p4
