#include "cc/render/view.h"

#include <cmath>
#include <cstdlib>
#include <set>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cc/base/block_tokens.h"
#include "cc/base/read_file.h"

namespace kdtree {
namespace {

using Token = BlockToken;

class ViewParser {
 public:
  ViewParser(std::vector<Token> tokens, const std::string& file, int last_line)
      : t_(std::move(tokens)), file_(file), last_line_(last_line) {}

  absl::StatusOr<View> Parse() {
    View view;
    bool have_camera = false, have_resolution = false, have_ao = false;
    while (pos_ < t_.size()) {
      const Token& key = t_[pos_++];
      absl::Status st;
      if (key.text == "camera") {
        if (have_camera) return Error(key.line, "second 'camera' block");
        have_camera = true;
        st = CameraBlock(key.line, &view.camera);
      } else if (key.text == "resolution") {
        if (have_resolution) return Error(key.line, "second 'resolution'");
        have_resolution = true;
        int w = 0, h = 0;
        st = Int("resolution width", &w);
        if (st.ok()) st = Int("resolution height", &h);
        if (st.ok() && (w < 1 || h < 1 || w > 16384 || h > 16384)) {
          return Error(key.line, "resolution must be between 1 and 16384");
        }
        view.width = w;
        view.height = h;
      } else if (key.text == "light") {
        PointLight light;
        st = LightBlock(key.line, &light);
        view.lights.push_back(light);
      } else if (key.text == "ambient_occlusion") {
        if (have_ao) return Error(key.line, "second 'ambient_occlusion' block");
        have_ao = true;
        st = AoBlock(key.line, &view.ao);
      } else {
        return Error(key.line, absl::StrCat("unknown keyword '", key.text,
                                            "' (expected camera, resolution, light or "
                                            "ambient_occlusion)"));
      }
      if (!st.ok()) return st;
    }
    if (!have_camera) return Error(last_line_, "no 'camera' block");
    absl::Status valid = view.Validate(file_);
    if (!valid.ok()) return valid;
    return view;
  }

 private:
  absl::Status Error(int line, const std::string& reason) const {
    return absl::InvalidArgumentError(absl::StrCat(file_, ":", line, ": ", reason));
  }
  int Line() const { return pos_ < t_.size() ? t_[pos_].line : last_line_; }

  absl::Status Number(const std::string& what, float* out) {
    if (pos_ >= t_.size()) return Error(last_line_, absl::StrCat("missing ", what));
    const Token& tok = t_[pos_];
    char* end = nullptr;
    const float f = std::strtof(tok.text.c_str(), &end);
    if (end == tok.text.c_str() || *end != '\0') {
      return Error(tok.line, absl::StrCat("expected a number for ", what, ", got '", tok.text, "'"));
    }
    if (!std::isfinite(f)) return Error(tok.line, absl::StrCat(what, " is not finite"));
    ++pos_;
    *out = f;
    return absl::OkStatus();
  }

  absl::Status Int(const std::string& what, int* out) {
    if (pos_ >= t_.size()) return Error(last_line_, absl::StrCat("missing ", what));
    const Token& tok = t_[pos_];
    char* end = nullptr;
    const long v = std::strtol(tok.text.c_str(), &end, 10);
    if (end == tok.text.c_str() || *end != '\0' || v < -1000000 || v > 1000000) {
      return Error(tok.line, absl::StrCat("expected an integer for ", what, ", got '", tok.text, "'"));
    }
    ++pos_;
    *out = static_cast<int>(v);
    return absl::OkStatus();
  }

  absl::Status Vector(const std::string& what, Vec3* out) {
    absl::Status st = Number(what, &out->x);
    if (st.ok()) st = Number(what, &out->y);
    if (st.ok()) st = Number(what, &out->z);
    return st;
  }

  // Runs `entry(key)` for each key of a `{ ... }` block; each key at most once.
  template <typename F>
  absl::Status Block(const std::string& name, int line, F entry) {
    if (pos_ >= t_.size() || t_[pos_].text != "{") {
      return Error(pos_ < t_.size() ? t_[pos_].line : line,
                   absl::StrCat("expected '{' after '", name, "'"));
    }
    ++pos_;
    std::set<std::string> seen;
    for (;;) {
      if (pos_ >= t_.size()) return Error(line, absl::StrCat("unterminated '", name, "' block"));
      const Token& key = t_[pos_++];
      if (key.text == "}") return absl::OkStatus();
      if (!seen.insert(key.text).second) {
        return Error(key.line, absl::StrCat("'", key.text, "' given twice in '", name, "'"));
      }
      absl::Status st = entry(key);
      if (!st.ok()) return st;
    }
  }

  absl::Status CameraBlock(int line, CameraSpec* cam) {
    bool have_position = false, have_look_at = false;
    absl::Status st = Block("camera", line, [&](const Token& key) -> absl::Status {
      if (key.text == "position") {
        have_position = true;
        return Vector("camera position", &cam->position);
      }
      if (key.text == "look_at") {
        have_look_at = true;
        return Vector("camera look_at", &cam->look_at);
      }
      if (key.text == "up") return Vector("camera up", &cam->up);
      if (key.text == "fov") return Number("camera fov", &cam->fov_deg);
      return Error(key.line, absl::StrCat("unknown camera key '", key.text,
                                          "' (expected position, look_at, up or fov)"));
    });
    if (!st.ok()) return st;
    if (!have_position) return Error(line, "camera has no 'position'");
    if (!have_look_at) return Error(line, "camera has no 'look_at'");
    return absl::OkStatus();
  }

  absl::Status LightBlock(int line, PointLight* light) {
    bool have_position = false;
    absl::Status st = Block("light", line, [&](const Token& key) -> absl::Status {
      if (key.text == "position") {
        have_position = true;
        return Vector("light position", &light->position);
      }
      return Error(key.line, absl::StrCat("unknown light key '", key.text, "' (expected position)"));
    });
    if (!st.ok()) return st;
    if (!have_position) return Error(line, "light has no 'position'");
    return absl::OkStatus();
  }

  absl::Status AoBlock(int line, AmbientOcclusion* ao) {
    bool have_samples = false, have_distance = false;
    absl::Status st = Block("ambient_occlusion", line, [&](const Token& key) -> absl::Status {
      if (key.text == "samples") {
        have_samples = true;
        return Int("ambient_occlusion samples", &ao->samples);
      }
      if (key.text == "distance") {
        have_distance = true;
        return Number("ambient_occlusion distance", &ao->distance);
      }
      return Error(key.line, absl::StrCat("unknown ambient_occlusion key '", key.text,
                                          "' (expected samples or distance)"));
    });
    if (!st.ok()) return st;
    if (!have_samples || !have_distance) {
      return Error(line, "ambient_occlusion needs 'samples' and 'distance'");
    }
    if (ao->samples < 1) return Error(line, "ambient_occlusion samples must be at least 1");
    return absl::OkStatus();
  }

  std::vector<Token> t_;
  const std::string& file_;
  int last_line_;
  size_t pos_ = 0;
};

std::string V3(const Vec3& v) { return absl::StrFormat("%.9g %.9g %.9g", v.x, v.y, v.z); }

}  // namespace

absl::Status View::Validate(const std::string& where) const {
  auto bad = [&](const std::string& reason) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": ", reason));
  };
  if (!IsFinite(camera.position) || !IsFinite(camera.look_at) || !IsFinite(camera.up)) {
    return bad("camera vectors must be finite");
  }
  const Vec3 dir = camera.look_at - camera.position;
  if (Length(dir) == 0.0f) return bad("camera position equals look_at");
  if (Length(Cross(Normalize(dir), Normalize(camera.up))) < 1e-6f) {
    return bad("camera up is parallel to the view direction (or zero)");
  }
  if (!(camera.fov_deg > 0.0f && camera.fov_deg < 180.0f)) {
    return bad("camera fov must be between 0 and 180 degrees");
  }
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    return bad("resolution must be between 1 and 16384");
  }
  if (lights.size() > kMaxLights) {
    return bad(absl::StrCat("at most ", kMaxLights, " lights (a ray record's light index has 16 bits); got ",
                            lights.size()));
  }
  for (const PointLight& l : lights) {
    if (!IsFinite(l.position)) return bad("light position must be finite");
  }
  if (ao.samples < 0 || ao.samples > 4096) return bad("ambient_occlusion samples must be 0..4096");
  if (ao.enabled() && !(ao.distance > 0.0f && std::isfinite(ao.distance))) {
    return bad("ambient_occlusion distance must be positive");
  }
  return absl::OkStatus();
}

absl::StatusOr<View> ParseView(const std::string& text, const std::string& filename) {
  int lines = 1;
  for (char c : text) lines += c == '\n';
  return ViewParser(TokenizeBlocks(text), filename, lines).Parse();
}

absl::StatusOr<View> LoadViewFile(const std::string& path) {
  absl::StatusOr<std::string> text = ReadTextInput(path, "view file");
  if (!text.ok()) return text.status();
  return ParseView(*text, path);
}

std::string ViewToText(const View& view) {
  std::string out = absl::StrFormat(
      "camera {\n  position %s\n  look_at %s\n  up %s\n  fov %.9g\n}\nresolution %d %d\n",
      V3(view.camera.position), V3(view.camera.look_at), V3(view.camera.up), view.camera.fov_deg,
      view.width, view.height);
  for (const PointLight& l : view.lights) {
    absl::StrAppendFormat(&out, "light { position %s }\n", V3(l.position));
  }
  if (view.ao.enabled()) {
    absl::StrAppendFormat(&out, "ambient_occlusion { samples %d distance %.9g }\n", view.ao.samples,
                          view.ao.distance);
  }
  return out;
}

absl::Status CheckSceneScale(const AABB& bounds) {
  if (!bounds.Valid()) return absl::InvalidArgumentError("the scene has no bounds (no triangles?)");
  double extent = 0, magnitude = 0;
  for (int a = 0; a < 3; ++a) {
    extent = std::fmax(extent, static_cast<double>(bounds.hi[a]) - bounds.lo[a]);
    magnitude = std::fmax(magnitude, std::fmax(std::fabs(bounds.lo[a]), std::fabs(bounds.hi[a])));
  }
  if (extent < kMinSceneExtent || extent > kMaxSceneExtent) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the scene spans %g, outside [%g, %g], the sizes single-precision ray tracing handles "
        "(products of coordinates would %s): scale the mesh",
        extent, kMinSceneExtent, kMaxSceneExtent, extent < kMinSceneExtent ? "underflow" : "overflow"));
  }
  if (extent < kMinRelativeExtent * magnitude) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the scene spans %g at a distance of %g from the origin, less than %g of it: its "
        "coordinates keep too few bits to trace (translate the mesh towards the origin)",
        extent, magnitude, kMinRelativeExtent));
  }
  return absl::OkStatus();
}

}  // namespace kdtree
