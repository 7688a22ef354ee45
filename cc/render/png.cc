#include "cc/render/png.h"

#include <png.h>

#include <cerrno>
#include <cstring>

#include "absl/strings/str_cat.h"

namespace kdtree {

absl::Status WritePngRgb8(const std::string& path, int width, int height,
                          const std::vector<uint8_t>& rgb) {
  if (width < 1 || height < 1 || rgb.size() != static_cast<size_t>(width) * height * 3) {
    return absl::InvalidArgumentError(
        absl::StrCat(path, ": image buffer of ", rgb.size(), " bytes does not match ", width, "x",
                     height, " RGB"));
  }
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  errno = 0;
  if (png_image_write_to_file(&image, path.c_str(), /*convert_to_8bit=*/0, rgb.data(),
                              /*row_stride=*/width * 3, /*colormap=*/nullptr) == 0) {
    const int err = errno;
    std::string reason = image.message;
    png_image_free(&image);
    if (err != 0) absl::StrAppend(&reason, " (", std::strerror(err), ")");
    return absl::InternalError(absl::StrCat(path, ": cannot write PNG: ", reason));
  }
  return absl::OkStatus();
}

}  // namespace kdtree
