#include "cc/scenes/stk_track.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "cc/base/read_file.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "cc/scenes/spm.h"
#include "cc/scenes/xml.h"

namespace kdtree {
namespace scenes {
namespace {

constexpr float kPi = 3.14159265358979323846f;

// p -> linear * p + offset.
struct Affine {
  Mat3 linear;
  Vec3 offset{0, 0, 0};
};

Affine Compose(const Affine& outer, const Affine& inner) {
  return {outer.linear * inner.linear, outer.linear * inner.offset + outer.offset};
}

// A parsed scene.xml or library node.xml and its level-of-detail groups.
struct SceneFile {
  std::string path;
  std::string dir;  // searched first for the models it names
  XmlElement root;
  std::map<std::string, std::vector<const XmlElement*>> lod_groups;
};

// The files enclosing the one being read: LOD groups are looked up outwards.
struct Scope {
  const SceneFile* file;
  const Scope* outer;
};

// true / false for the conditions a race decides; nullopt: unknown.
std::optional<bool> EvaluateCondition(const std::string& c, bool reverse) {
  if (c == "true") return true;
  if (c == "false") return false;
  if (c == "isTrackReverse" || c == "isReverse") return reverse;
  if (c == "isTrackNotReverse" || c == "isNotReverse") return !reverse;
  if (c == "isCTF" || c == "isNetworking" || c == "isEasterEgg") return false;
  if (c == "isNotCTF" || c == "isNotNetworking") return true;
  return std::nullopt;
}

absl::StatusOr<std::string> ReadFile(const std::string& path) {
  return ReadTextInput(path, "track file", kSceneInputBudget);
}

class TrackBuilder {
 public:
  TrackBuilder(const StkTrackOptions& options, std::string track_dir, std::string data_dir,
               StkTrackStats& stats)
      : options_(options),
        track_dir_(std::move(track_dir)),
        data_dir_(std::move(data_dir)),
        stats_(stats) {}

  absl::StatusOr<Mesh> Build() {
    absl::StatusOr<const SceneFile*> scene =
        Load(track_dir_ + "/scene.xml", track_dir_);
    if (!scene.ok()) return scene.status();
    const Scope scope{*scene, nullptr};
    const XmlElement* track = nullptr;
    for (const XmlElement& e : (*scene)->root.children) {
      if (e.name != "track") continue;
      if (track != nullptr) return Error(**scene, e, "a second <track> element");
      track = &e;
    }
    if (track == nullptr || track->Attribute("model") == nullptr) {
      return absl::InvalidArgumentError(
          absl::StrCat((*scene)->path, ": no <track model=...> element (the main mesh)"));
    }
    const Affine identity;
    if (absl::Status s = PlaceModel(*track->Attribute("model"), **scene, *track, identity);
        !s.ok()) {
      return s;
    }
    if (absl::Status s = PlaceChildren(*track, scope, identity, 0); !s.ok()) return s;
    if (absl::Status s = PlaceChildren((*scene)->root, scope, identity, 0); !s.ok()) return s;
    if (options_.right_handed) {
      for (Vec3& p : mesh_.vertices) p.z = -p.z;
    }
    stats_.models = static_cast<int64_t>(models_.size());
    return std::move(mesh_);
  }

 private:
  absl::Status Error(const SceneFile& file, const XmlElement& e, absl::string_view what) const {
    return absl::InvalidArgumentError(absl::StrCat(file.path, ":", e.line, ": ", what));
  }

  void Skip(const std::string& reason) { ++stats_.skipped[reason]; }

  // Parses `path` once; later calls return the same file.
  absl::StatusOr<const SceneFile*> Load(const std::string& path, const std::string& dir) {
    auto it = files_.find(path);
    if (it != files_.end()) return it->second.get();
    absl::StatusOr<std::string> text = ReadFile(path);
    if (!text.ok()) return text.status();
    absl::StatusOr<XmlElement> root = ParseXml(*text);
    if (!root.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(path, ": ", root.status().message()));
    }
    auto file = std::make_unique<SceneFile>();
    file->path = path;
    file->dir = dir;
    file->root = *std::move(root);
    for (const XmlElement& lod : file->root.children) {
      if (lod.name != "lod") continue;
      for (const XmlElement& group : lod.children) {
        if (group.name != "group") continue;
        const std::string* name = group.Attribute("name");
        if (name == nullptr) return Error(*file, group, "<group> without a name");
        std::vector<const XmlElement*>& members = file->lod_groups[*name];
        for (const XmlElement& m : group.children) {
          if (m.name == "static-object" || m.name == "object") members.push_back(&m);
        }
      }
    }
    const SceneFile* result = file.get();
    files_[path] = std::move(file);
    return result;
  }

  // Reads attribute `key` as three floats; `fallback` when absent.
  absl::StatusOr<Vec3> Triple(const SceneFile& file, const XmlElement& e, absl::string_view key,
                              const Vec3& fallback) const {
    const std::string* value = e.Attribute(key);
    if (value == nullptr) return fallback;
    std::vector<absl::string_view> parts =
        absl::StrSplit(*value, absl::ByAnyChar(" \t\r\n,"), absl::SkipEmpty());
    Vec3 v;
    if (parts.size() != 3) {
      return Error(file, e, absl::StrCat(key, "=\"", *value, "\": not three numbers"));
    }
    for (int a = 0; a < 3; ++a) {
      if (!absl::SimpleAtof(parts[a], &v[a]) || !std::isfinite(v[a])) {
        return Error(file, e, absl::StrCat(key, "=\"", *value, "\": not three numbers"));
      }
    }
    return v;
  }

  absl::StatusOr<Affine> Transform(const SceneFile& file, const XmlElement& e) const {
    absl::StatusOr<Vec3> xyz = Triple(file, e, "xyz", {0, 0, 0});
    if (!xyz.ok()) return xyz.status();
    absl::StatusOr<Vec3> hpr = Triple(file, e, "hpr", {0, 0, 0});
    if (!hpr.ok()) return hpr.status();
    absl::StatusOr<Vec3> scale = Triple(file, e, "scale", {1, 1, 1});
    if (!scale.ok()) return scale.status();
    const float to_radians = kPi / 180.0f;
    const Mat3 rotation = Mat3::Rotation(2, hpr->z * to_radians) *
                          Mat3::Rotation(1, hpr->y * to_radians) *
                          Mat3::Rotation(0, hpr->x * to_radians);
    Mat3 s;
    s.m[0][0] = scale->x;
    s.m[1][1] = scale->y;
    s.m[2][2] = scale->z;
    return Affine{rotation * s, *xyz};
  }

  // False (and counted) when `e` is not drawn: condition, interaction, type.
  bool Drawn(const XmlElement& e) {
    if (const std::string* c = e.Attribute("if"); c != nullptr && options_.evaluate_conditions) {
      if (!EvaluateCondition(*c, options_.reverse).value_or(true)) {
        Skip("if=" + *c);
        return false;
      }
    }
    if (const std::string* i = e.Attribute("interaction"); i != nullptr) {
      const auto& skip = options_.skip_interactions;
      if (std::find(skip.begin(), skip.end(), *i) != skip.end()) {
        Skip("interaction=" + *i);
        return false;
      }
    }
    if (const std::string* t = e.Attribute("type"); t != nullptr && *t == "cutscene_camera") {
      Skip("type=" + *t);
      return false;
    }
    return true;
  }

  absl::Status PlaceChildren(const XmlElement& parent, const Scope& scope, const Affine& world,
                             int depth) {
    for (const XmlElement& e : parent.children) {
      absl::Status s;
      if (e.name == "object" || e.name == "static-object" || e.name == "water") {
        s = PlaceObject(e, scope, world);
      } else if (e.name == "library") {
        s = PlaceLibrary(e, scope, world, depth);
      }
      if (!s.ok()) return s;
    }
    return absl::OkStatus();
  }

  absl::Status PlaceObject(const XmlElement& e, const Scope& scope, const Affine& world) {
    if (!Drawn(e)) return absl::OkStatus();
    const SceneFile& file = *scope.file;
    absl::StatusOr<Affine> local = Transform(file, e);
    if (!local.ok()) return local.status();
    const Affine placed = Compose(world, *local);
    const std::string* lod_instance = e.Attribute("lod_instance");
    if (lod_instance != nullptr && *lod_instance == "true") {
      const std::string* group = e.Attribute("lod_group");
      if (group == nullptr) return Error(file, e, "lod_instance without a lod_group");
      for (const Scope* s = &scope; s != nullptr; s = s->outer) {
        auto it = s->file->lod_groups.find(*group);
        if (it == s->file->lod_groups.end()) continue;
        const XmlElement* best = nullptr;
        float best_distance = 0;
        for (const XmlElement* m : it->second) {
          const std::string* interaction = m->Attribute("interaction");
          const auto& skip = options_.skip_interactions;
          if (interaction != nullptr &&
              std::find(skip.begin(), skip.end(), *interaction) != skip.end()) {
            continue;
          }
          float distance = 0;
          const std::string* d = m->Attribute("lod_distance");
          if (d != nullptr && !absl::SimpleAtof(*d, &distance)) {
            return Error(*s->file, *m, absl::StrCat("lod_distance=\"", *d, "\": not a number"));
          }
          if (m->Attribute("model") == nullptr) {
            return Error(*s->file, *m, "LOD group member without a model");
          }
          if (best == nullptr || distance < best_distance) {
            best = m;
            best_distance = distance;
          }
        }
        if (best == nullptr) {
          Skip("LOD group without a drawn member");
          return absl::OkStatus();
        }
        ++stats_.lod_instances;
        return PlaceModel(*best->Attribute("model"), *s->file, *best, placed);
      }
      return Error(file, e, absl::StrCat("unknown LOD group '", *group, "'"));
    }
    if (const std::string* model = e.Attribute("model"); model != nullptr) {
      return PlaceModel(*model, file, e, placed);
    }
    const std::string* type = e.Attribute("type");
    Skip(absl::StrCat("no mesh: ", e.name, type != nullptr ? " type=" + *type : ""));
    return absl::OkStatus();
  }

  absl::Status PlaceLibrary(const XmlElement& e, const Scope& scope, const Affine& world,
                            int depth) {
    if (!Drawn(e)) return absl::OkStatus();
    const SceneFile& file = *scope.file;
    const std::string* name = e.Attribute("name");
    if (name == nullptr || name->empty() || name->find('/') != std::string::npos) {
      return Error(file, e, "<library> needs a plain name");
    }
    if (depth >= options_.max_library_depth) {
      return Error(file, e, absl::StrCat("libraries nested deeper than ",
                                         options_.max_library_depth, " (a cycle?)"));
    }
    absl::StatusOr<Affine> local = Transform(file, e);
    if (!local.ok()) return local.status();
    const std::string dir = absl::StrCat(data_dir_, "/library/", *name);
    absl::StatusOr<const SceneFile*> node = Load(dir + "/node.xml", dir);
    if (!node.ok()) {
      return Error(file, e, absl::StrCat("library '", *name, "': ", node.status().message()));
    }
    ++stats_.libraries;
    const Scope inner{*node, &scope};
    return PlaceChildren((*node)->root, inner, Compose(world, *local), depth + 1);
  }

  absl::Status PlaceModel(const std::string& name, const SceneFile& file, const XmlElement& e,
                          const Affine& placed) {
    const std::string dirs[] = {file.dir, track_dir_, data_dir_ + "/models"};
    std::string path;
    for (const std::string& dir : dirs) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(dir + "/" + name, ec)) {
        path = dir + "/" + name;
        break;
      }
    }
    if (path.empty()) {
      return Error(file, e, absl::StrCat("model '", name, "' not found in ",
                                         absl::StrJoin(dirs, ", ")));
    }
    auto it = models_.find(path);
    if (it == models_.end()) {
      absl::StatusOr<Mesh> model = ReadSpm(path);
      if (!model.ok()) {
        return Error(file, e, absl::StrCat("model '", name, "': ", model.status().message()));
      }
      it = models_.emplace(path, *std::move(model)).first;
    }
    mesh_.Append(it->second, placed.linear, placed.offset);
    ++stats_.placed;
    return absl::OkStatus();
  }

  const StkTrackOptions& options_;
  const std::string track_dir_;
  const std::string data_dir_;
  StkTrackStats& stats_;
  std::map<std::string, std::unique_ptr<SceneFile>> files_;
  std::map<std::string, Mesh> models_;  // by path
  Mesh mesh_;
};

}  // namespace

absl::StatusOr<Mesh> ReadStkTrack(const std::string& track_dir, const StkTrackOptions& options,
                                  StkTrackStats* stats) {
  std::string dir = track_dir;
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  std::string data_dir = options.data_dir;
  if (data_dir.empty()) {
    data_dir = std::filesystem::path(dir).lexically_normal().parent_path().parent_path().string();
    if (data_dir.empty()) data_dir = ".";
  }
  StkTrackStats local;
  TrackBuilder builder(options, dir, data_dir, stats != nullptr ? *stats : local);
  return builder.Build();
}

}  // namespace scenes
}  // namespace kdtree
