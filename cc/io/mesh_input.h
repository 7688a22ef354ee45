// How a mesh's bytes reach the importer (issue 24: inputs read once, within a
// budget). The path is opened once (cc/base/read_file.h): a directory or a
// device is refused by name; a regular file larger than the budget is refused
// by its size, before anything is read; gzip data is inflated in memory and
// refused as soon as it passes the budget, so a small file that inflates to
// gigabytes never does. A pipe or a process substitution (/dev/fd/N) is read
// once into memory and its format taken from its name, else from its first
// bytes (gzip, PLY, OFF, binary glTF, OBJ).
#ifndef KDTREE_CC_IO_MESH_INPUT_H_
#define KDTREE_CC_IO_MESH_INPUT_H_

#include <cstddef>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kdtree {

// The default input budget: 768 MiB of file or inflated bytes, twice the
// largest scene of data/manifest.json (san-miguel, 400 MB of binary PLY), and
// under 1 GB in all when a request is refused.
inline constexpr size_t kMeshInputBudget = size_t{768} << 20;

struct MeshInput {
  std::string format;      // lower case, no dot: "obj", "ply", "glb"... ("" unknown)
  bool in_memory = false;  // `bytes` is the whole mesh (gzip, pipes); else the
                           // importer opens the regular file by its path, so
                           // the files beside it (OBJ materials) resolve
  std::string bytes;       // the mesh's bytes when in_memory, or when its format
                           // is checked by CheckMeshSyntax (obj, off, ply)
};

// Errors name the path: "file is empty", "the mesh file is a directory" (or
// "a device"), "cannot open mesh file" (NotFound, PermissionDenied), over the
// budget (ResourceExhausted): "is N bytes, more than the input budget of M
// bytes", "is longer than..." (a pipe), "inflates to more than...";
// "corrupt or truncated gzip data", "name ends in .gz but the file is not
// gzip-compressed", "cannot tell the mesh format".
absl::StatusOr<MeshInput> ReadMeshInput(const std::string& path,
                                        size_t max_bytes = kMeshInputBudget);

// The error of every mesh input problem: "PATH: WHY".
absl::Status FileError(absl::StatusCode code, const std::string& path, const std::string& why);

// The formats whose syntax CheckMeshSyntax checks before assimp reads them
// (mesh_syntax.h): obj, off, ply.
bool NeedsSyntaxCheck(const std::string& format);

// Lower-case extension of the file name without the dot ("" when none).
std::string Extension(absl::string_view path);

// The format of a mesh's first bytes: "ply", "off", "glb", "obj", else "".
std::string SniffMeshFormat(absl::string_view bytes);

}  // namespace kdtree

#endif  // KDTREE_CC_IO_MESH_INPUT_H_
