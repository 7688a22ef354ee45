// Paths of the tools and benchmarks: the checkout they run on, paths given on
// the command line of a tool started with `bazel run`, and writing a file
// whose directory may not exist yet.
#ifndef KDTREE_CC_TOOLS_PATHS_H_
#define KDTREE_CC_TOOLS_PATHS_H_

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace kdtree {

// The checkout: $BUILD_WORKSPACE_DIRECTORY under `bazel run`, else the current
// directory (the runners start the tools from the repository root).
inline std::string Workspace() {
  const char* ws = std::getenv("BUILD_WORKSPACE_DIRECTORY");
  return ws != nullptr && *ws != '\0' ? ws : ".";
}

// A relative path under the workspace (defaults such as data/cache/soups).
inline std::string FromWorkspace(const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  return absl::StrCat(Workspace(), "/", path);
}

// A relative path is meant relative to where `bazel run` was invoked
// (BUILD_WORKING_DIRECTORY), not to the runfiles directory the tool runs in.
// Absolute paths, empty paths and runs outside `bazel run` are unchanged.
inline std::string FromInvocationDir(const std::string& path) {
  const char* dir = std::getenv("BUILD_WORKING_DIRECTORY");
  if (path.empty() || path[0] == '/' || dir == nullptr || *dir == '\0') return path;
  return absl::StrCat(dir, "/", path);
}

// Creates the file's directory, then writes the file with `write`.
inline absl::Status WriteCreatingDirectory(
    const std::string& path, const std::function<absl::Status(const std::string&)>& write) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) return absl::InternalError(absl::StrCat(dir.string(), ": cannot create directory: ", ec.message()));
  return write(path);
}

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_PATHS_H_
