// Reading an input once: a regular file, a pipe or a process substitution
// (/dev/fd/N), opened once and read to its end. A directory or a device given
// where a file is expected is refused by name, and so is an input longer than
// a budget, before more than the budget is read (issue 24: files that are not
// files).
#ifndef KDTREE_CC_BASE_READ_FILE_H_
#define KDTREE_CC_BASE_READ_FILE_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/status/statusor.h"

namespace kdtree {

// The default budget of ReadTextInput: 64 MiB, far above any environment or
// view file.
inline constexpr size_t kTextInputBudget = size_t{64} << 20;

// An input opened once for reading; the descriptor is closed with the object.
class InputFile {
 public:
  // Opens `path` (a pipe blocks here until it has a writer, as `cat` does).
  // `what` names the input in messages ("environment file"):
  // "PATH: the WHAT is a directory", "PATH: the WHAT is a device",
  // "PATH: cannot open WHAT: REASON" (NotFound when it does not exist,
  // PermissionDenied when it may not be read).
  static absl::StatusOr<InputFile> Open(const std::string& path, const std::string& what);

  InputFile(InputFile&& o) noexcept;
  InputFile& operator=(InputFile&&) = delete;
  InputFile(const InputFile&) = delete;
  ~InputFile();

  // A regular file (else a pipe, socket or process substitution: read once,
  // never reopened by name).
  bool regular() const { return regular_; }
  // Bytes of a regular file (0 for the others: unknown before reading).
  uint64_t size() const { return size_; }
  int fd() const { return fd_; }

  // The remaining bytes: "PATH: WHAT is longer than N bytes"
  // (ResourceExhausted) past the budget (a regular file is refused by its
  // size before anything is read),
  // "PATH: read error: REASON".
  absl::StatusOr<std::string> ReadAll(size_t max_bytes);

 private:
  InputFile(std::string path, std::string what, int fd, bool regular, uint64_t size)
      : path_(std::move(path)), what_(std::move(what)), fd_(fd), regular_(regular), size_(size) {}

  std::string path_, what_;
  int fd_ = -1;
  bool regular_ = false;
  uint64_t size_ = 0;
};

// Open + ReadAll.
absl::StatusOr<std::string> ReadTextInput(const std::string& path, const std::string& what,
                                          size_t max_bytes = kTextInputBudget);

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_READ_FILE_H_
