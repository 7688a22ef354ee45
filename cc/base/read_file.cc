#include "cc/base/read_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace kdtree {

absl::StatusOr<InputFile> InputFile::Open(const std::string& path, const std::string& what) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    const std::string msg = absl::StrCat(path, ": cannot open ", what, ": ", std::strerror(err));
    if (err == ENOENT || err == ENOTDIR) return absl::NotFoundError(msg);
    return err == EACCES ? absl::PermissionDeniedError(msg) : absl::InvalidArgumentError(msg);
  }
  InputFile in(path, what, fd, false, 0);
  struct stat st;
  if (fstat(fd, &st) != 0) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": cannot stat ", what, ": ", std::strerror(errno)));
  }
  if (S_ISDIR(st.st_mode)) return absl::InvalidArgumentError(absl::StrCat(path, ": the ", what, " is a directory"));
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": the ", what, " is a device"));
  }
  in.regular_ = S_ISREG(st.st_mode);
  in.size_ = in.regular_ ? static_cast<uint64_t>(st.st_size) : 0;
  return in;
}

InputFile::InputFile(InputFile&& o) noexcept
    : path_(std::move(o.path_)), what_(std::move(o.what_)), fd_(std::exchange(o.fd_, -1)),
      regular_(o.regular_), size_(o.size_) {}

InputFile::~InputFile() {
  if (fd_ >= 0) close(fd_);
}

absl::StatusOr<std::string> InputFile::ReadAll(size_t max_bytes) {
  const auto too_long = [&] {
    return absl::ResourceExhaustedError(absl::StrCat(path_, ": ", what_, " is longer than ", max_bytes, " bytes"));
  };
  if (regular_ && size_ > max_bytes) return too_long();
  std::string out;
  if (regular_) out.reserve(size_);
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = read(fd_, buf, sizeof(buf));
    if (n == 0) return out;
    if (n < 0) {
      if (errno == EINTR) continue;
      return absl::DataLossError(absl::StrCat(path_, ": read error: ", std::strerror(errno)));
    }
    if (out.size() + static_cast<size_t>(n) > max_bytes) return too_long();
    out.append(buf, static_cast<size_t>(n));
  }
}

absl::StatusOr<std::string> ReadTextInput(const std::string& path, const std::string& what,
                                          size_t max_bytes) {
  absl::StatusOr<InputFile> in = InputFile::Open(path, what);
  if (!in.ok()) return in.status();
  return in->ReadAll(max_bytes);
}

}  // namespace kdtree
