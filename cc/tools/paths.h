// Paths of the tools and benchmarks: the checkout they run on, and paths given
// on the command line of a tool started with `bazel run`.
#ifndef KDTREE_CC_TOOLS_PATHS_H_
#define KDTREE_CC_TOOLS_PATHS_H_

#include <cstdlib>
#include <string>

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

}  // namespace kdtree

#endif  // KDTREE_CC_TOOLS_PATHS_H_
