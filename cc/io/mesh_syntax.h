// A strict structural check of OBJ, OFF and PLY files before assimp reads
// them (issue "Hard cases stay numerically stable", input hygiene).
//
// assimp 5.2 accepts some malformed files silently (an OFF face index past
// the vertex count is clamped), aborts on others (an OFF file announcing more
// faces than it holds trips an ai_assert in Triangulate) and names no line in
// its messages. This check runs first and rejects, with "file:line: reason"
// (binary PLY: "file: byte N: reason"):
//  - OBJ: a `v` line without three numbers; a face (`f`) with fewer than three
//    vertices, a malformed reference, index 0, or an index outside the
//    vertices defined (negative indices count back from the last vertex so
//    far, positive ones may refer to any vertex of the file).
//  - OFF: a missing or bad count line, counts larger than the file can
//    hold, a vertex without three numbers, a face with fewer than 3 vertices,
//    a bad vertex count or an index outside [0, vertices), a file ending
//    before its last face.
//  - PLY: a bad magic, format, element or property line, no end_header,
//    element counts larger than the body can hold, a body (ASCII or binary,
//    either endianness) ending early or holding a non-number, a face with
//    fewer than 3 vertices (assimp's Triangulate aborts on empty faces), and
//    a face index outside [0, vertices) (how a wrong endianness usually
//    shows).
//    The first line must be the header OFF, COFF, NOFF or CNOFF (ASCII);
//    other variants, header-less and binary OFF files and comment lines
//    (which assimp's reader does not skip) are refused.
// Other formats are left to assimp (Ok). The file format references: Wavefront OBJ (Alias
// "Object Files (.obj)" appendix B1), Princeton/Geomview OFF, Turk's PLY.
#ifndef KDTREE_CC_IO_MESH_SYNTAX_H_
#define KDTREE_CC_IO_MESH_SYNTAX_H_

#include <string>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace kdtree {

// `format` is the lower-case extension ("obj", "off", "ply"; anything else is
// Ok). `name` is used in messages only. InvalidArgument on malformed input.
absl::Status CheckMeshSyntax(absl::string_view data, absl::string_view format,
                             const std::string& name);

}  // namespace kdtree

#endif  // KDTREE_CC_IO_MESH_SYNTAX_H_
