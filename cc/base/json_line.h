// One JSON record as one line: how every tool and bench writes its records
// (kdrt, scene_info, the benches, the robustness checks, the scene tools).
#ifndef KDTREE_CC_BASE_JSON_LINE_H_
#define KDTREE_CC_BASE_JSON_LINE_H_

#include <string>

#include "nlohmann/json.hpp"

namespace kdtree {

// Compact, no newline; invalid UTF-8 in names replaced, not thrown;
// non-finite numbers are null (nlohmann's rule).
inline std::string JsonLine(const nlohmann::ordered_json& record) {
  return record.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_JSON_LINE_H_
