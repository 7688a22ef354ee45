// One fuzz case for the mesh loader (issue "Hard cases stay numerically
// stable", input hygiene): byte 0 picks the format (OBJ, OFF or PLY), the
// rest is the file. It is written to a temporary file and loaded with
// LoadMesh; the syntax check (mesh_syntax.h) also runs on the bytes directly.
// Used by the libFuzzer target mesh_fuzzer.cc and the smoke test
// mesh_fuzz_test.cc.
#ifndef KDTREE_CC_IO_MESH_FUZZ_H_
#define KDTREE_CC_IO_MESH_FUZZ_H_

#include <cstddef>
#include <cstdint>
#include <string>

namespace kdtree {

// "obj", "off", "ply", "obj.gz" (the bytes written gzip-compressed) or
// "ply.gz" (the bytes written as they are) for the selector byte.
const char* FuzzFormat(uint8_t selector);

// Returns the number of broken promises: a loaded soup with a triangle that
// is not finite, absurd or degenerate, a report whose count differs from the
// soup, or an error message that does not name the file. Never crashes or
// hangs on any input (what the fuzzer checks). `tmp_dir` holds the file.
size_t MeshFuzzCase(const uint8_t* data, size_t size, const std::string& tmp_dir);

}  // namespace kdtree

#endif  // KDTREE_CC_IO_MESH_FUZZ_H_
