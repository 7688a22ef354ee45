// 8-bit RGB PNG output through libpng (its simplified png_image API).
#ifndef KDTREE_CC_RENDER_PNG_H_
#define KDTREE_CC_RENDER_PNG_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"

namespace kdtree {

// Writes `rgb` (width * height * 3 bytes, top row first) to `path`.
// Errors (bad size, libpng or file errors) name the file.
absl::Status WritePngRgb8(const std::string& path, int width, int height,
                          const std::vector<uint8_t>& rgb);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_PNG_H_
