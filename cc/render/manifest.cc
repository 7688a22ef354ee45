#include "cc/render/manifest.h"

#include <sys/stat.h>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "cc/render/json.h"
#include "nlohmann/json.hpp"

namespace kdtree {
namespace {

using Json = nlohmann::json;

// Object member `key`; nullptr when absent or when `obj` is not an object.
const Json* Member(const Json& obj, const std::string& key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

absl::Status Vec3Field(const Json& obj, const std::string& key, const std::string& where,
                       bool required, Vec3* out) {
  const Json* v = Member(obj, key);
  if (v == nullptr || v->is_null()) {
    if (!required) return absl::OkStatus();
    return absl::InvalidArgumentError(absl::StrCat(where, ": missing '", key, "'"));
  }
  if (!v->is_array() || v->size() != 3 || !(*v)[0].is_number() || !(*v)[1].is_number() ||
      !(*v)[2].is_number()) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": '", key, "' must be an array of three numbers"));
  }
  *out = Vec3((*v)[0].get<float>(), (*v)[1].get<float>(), (*v)[2].get<float>());
  return absl::OkStatus();
}

bool FileExists(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0;
}

}  // namespace

absl::StatusOr<View> ViewFromManifestEntry(const Json& entry, const std::string& where) {
  const Json* cam = Member(entry, "camera");
  if (cam == nullptr || !cam->is_object()) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": no 'camera' object"));
  }
  const std::string cw = absl::StrCat(where, " camera");
  View view;
  absl::Status st = Vec3Field(*cam, "position", cw, true, &view.camera.position);
  if (st.ok()) st = Vec3Field(*cam, "look_at", cw, true, &view.camera.look_at);
  if (st.ok()) st = Vec3Field(*cam, "up", cw, false, &view.camera.up);
  if (!st.ok()) return st;
  if (const Json* fov = Member(*cam, "fov_deg"); fov != nullptr && !fov->is_null()) {
    if (!fov->is_number()) return absl::InvalidArgumentError(absl::StrCat(cw, ": 'fov_deg' must be a number"));
    view.camera.fov_deg = fov->get<float>();
  }
  const Json* light = Member(entry, "light");
  if (light != nullptr && !light->is_null()) {
    if (!light->is_object()) {
      return absl::InvalidArgumentError(absl::StrCat(where, ": 'light' must be an object or null"));
    }
    PointLight l;
    st = Vec3Field(*light, "position", absl::StrCat(where, " light"), true, &l.position);
    if (!st.ok()) return st;
    view.lights.push_back(l);
  }
  st = view.Validate(where);
  if (!st.ok()) return st;
  return view;
}

absl::StatusOr<SceneRef> ResolveScene(const std::string& repo_root, const std::string& name) {
  const std::string root = repo_root.empty() ? "." : repo_root;
  const std::string index_path = absl::StrCat(root, "/data/cache/scenes/index.json");
  const std::string hint = absl::StrCat(" (fetch it: /usr/bin/python3 data/fetch.py --scene ", name, ")");
  absl::StatusOr<Json> index = LoadJsonFile(index_path);
  if (!index.ok()) {
    return absl::NotFoundError(absl::StrCat(index.status().message(), hint));
  }
  const Json* scenes = Member(*index, "scenes");
  const Json* rec = scenes != nullptr ? Member(*scenes, name) : nullptr;
  const Json* file = rec != nullptr ? Member(*rec, "file") : nullptr;
  if (file == nullptr || !file->is_string()) {
    return absl::NotFoundError(absl::StrCat(index_path, ": no scene '", name, "'", hint));
  }
  SceneRef ref;
  ref.name = name;
  ref.mesh_path = file->get<std::string>();
  if (!ref.mesh_path.empty() && ref.mesh_path[0] != '/') ref.mesh_path = absl::StrCat(root, "/", ref.mesh_path);
  if (!FileExists(ref.mesh_path)) {
    return absl::NotFoundError(absl::StrCat(index_path, ": scene '", name, "' file ", ref.mesh_path,
                                            " is missing", hint));
  }
  absl::StatusOr<bool> has = LoadManifestView(root, name, &ref.view);
  if (!has.ok()) return has.status();
  ref.has_view = *has;
  if (ref.has_view) ref.view_source = "manifest";
  return ref;
}

absl::StatusOr<bool> LoadManifestView(const std::string& repo_root, const std::string& name,
                                      View* view) {
  const std::string manifest_path =
      absl::StrCat(repo_root.empty() ? "." : repo_root, "/data/manifest.json");
  if (!FileExists(manifest_path)) return false;
  absl::StatusOr<Json> manifest = LoadJsonFile(manifest_path);
  if (!manifest.ok()) return manifest.status();
  const Json* entries = Member(*manifest, "scenes");
  if (entries == nullptr || !entries->is_array()) {
    return absl::InvalidArgumentError(absl::StrCat(manifest_path, ": no 'scenes' array"));
  }
  for (const Json& e : *entries) {
    const Json* n = Member(e, "name");
    if (n == nullptr || !n->is_string() || n->get<std::string>() != name) continue;
    const Json* cam = Member(e, "camera");
    if (cam == nullptr || cam->is_null()) return false;
    absl::StatusOr<View> v =
        ViewFromManifestEntry(e, absl::StrCat(manifest_path, ": scene '", name, "'"));
    if (!v.ok()) return v.status();
    *view = *std::move(v);
    return true;
  }
  return false;
}

}  // namespace kdtree
