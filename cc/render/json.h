// Reading the small JSON files the renderer reads (data/manifest.json: scene
// cameras and lights; data/cache/scenes/index.json: where each scene's mesh
// is) with nlohmann-json.
//
// Numbers are nlohmann numbers (integer or double); strings UTF-8. A repeated
// key keeps its last value. Errors name the file, the line and column where
// nlohmann stopped (the last character it read) and nlohmann's reason:
//   "data/manifest.json: line 3, column 1: syntax error while parsing value -
//    unexpected '}'; expected '[', '{', or a literal".
#ifndef KDTREE_CC_RENDER_JSON_H_
#define KDTREE_CC_RENDER_JSON_H_

#include <string>

#include "absl/status/statusor.h"
#include "nlohmann/json.hpp"

namespace kdtree {

// Parses one JSON document (surrounding whitespace allowed, nothing else).
// `filename` is only used in error messages.
absl::StatusOr<nlohmann::json> ParseJson(const std::string& text, const std::string& filename);

// Reads (cc/base/read_file.h: once, a directory or device refused) and parses
// a file; errors name the file (NotFound when it does not exist).
absl::StatusOr<nlohmann::json> LoadJsonFile(const std::string& path);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_JSON_H_
