// Scenes by name: the mesh from data/cache/scenes/index.json (written by
// data/fetch.py) and the camera and light from data/manifest.json.
//
// index.json:    {"scenes": {"bunny": {"file": "data/cache/scenes/bunny.obj", ...}}}
//                ("file" relative to the repository root, or absolute)
// manifest.json: {"scenes": [{"name": "bunny",
//                             "camera": {"position": [x, y, z], "look_at": [x, y, z],
//                                        "up": [x, y, z], "fov_deg": 45},
//                             "light": {"position": [x, y, z]} or null, ...}]}
// A manifest `light` of null means a scene without lights (no shadow rays).
#ifndef KDTREE_CC_RENDER_MANIFEST_H_
#define KDTREE_CC_RENDER_MANIFEST_H_

#include <string>

#include "absl/status/statusor.h"
#include "cc/render/view.h"
#include "nlohmann/json_fwd.hpp"

namespace kdtree {

// The view of one manifest entry (an object with `camera` and `light`);
// resolution 800 x 800, no ambient occlusion. `up` defaults to 0 1 0 and
// `fov_deg` to 45 when absent. Errors name `where` and the bad field.
absl::StatusOr<View> ViewFromManifestEntry(const nlohmann::json& entry, const std::string& where);

struct SceneRef {
  std::string name;
  std::string mesh_path;   // absolute, or relative to the working directory
  bool has_view = false;   // the manifest has a camera for this scene
  View view;               // valid when has_view
  std::string view_source; // "manifest" or "" (none)
};

// The manifest's view of scene `name` (data/manifest.json under `repo_root`):
// true and *view set when the manifest exists and has a camera for the scene;
// false when there is no manifest, no such scene or no camera; an error when
// the manifest or the entry is malformed.
absl::StatusOr<bool> LoadManifestView(const std::string& repo_root, const std::string& name,
                                      View* view);

// Looks `name` up under `repo_root` (data/cache/scenes/index.json for the mesh,
// data/manifest.json for camera and light). A scene missing from the index is
// NotFound (with a hint to run data/fetch.py); a missing manifest or entry
// without a camera only leaves has_view false.
absl::StatusOr<SceneRef> ResolveScene(const std::string& repo_root, const std::string& name);

}  // namespace kdtree

#endif  // KDTREE_CC_RENDER_MANIFEST_H_
