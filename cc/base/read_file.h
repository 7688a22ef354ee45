// Reading a whole text input once: a regular file, a pipe or a process
// substitution (/dev/fd/N), opened once and read to its end. A directory or a
// device given where a file is expected is refused by name, and so is an
// input longer than a budget, before more than the budget is read (issue 24:
// files that are not files).
#ifndef KDTREE_CC_BASE_READ_FILE_H_
#define KDTREE_CC_BASE_READ_FILE_H_

#include <cstddef>
#include <string>

#include "absl/status/statusor.h"

namespace kdtree {

// The default budget of ReadTextInput: 64 MiB, far above any environment or
// view file.
inline constexpr size_t kTextInputBudget = size_t{64} << 20;

// The bytes of `path`. `what` names the input in messages ("environment
// file"): "PATH: the WHAT is a directory", "PATH: the WHAT is a device",
// "PATH: cannot open WHAT: REASON" (NotFound when it does not exist),
// "PATH: WHAT is longer than N bytes", "PATH: read error: REASON".
absl::StatusOr<std::string> ReadTextInput(const std::string& path, const std::string& what,
                                          size_t max_bytes = kTextInputBudget);

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_READ_FILE_H_
