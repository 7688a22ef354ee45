// Reader of SuperTuxKart tracks: one triangle list of everything the game
// draws, at the highest level of detail.
//
// A track directory (data/tracks/NAME of Debian's supertuxkart-data) holds a
// scene.xml that places .spm meshes (spm.h). What is read:
//   <track model="M.spm">     the main mesh, at the origin (exactly one).
//   <object>, <static-object>, <water> with model="M.spm": M placed by the
//       element's transform. With lod_instance="true" lod_group="G": the
//       member of level-of-detail group G with the smallest lod_distance (the
//       most detailed one). Groups are defined in <lod><group name="G">
//       <static-object model=...>, in the same file or an enclosing one; the
//       members' own xyz/hpr/scale are where the artist left the template and
//       are not used (the game shows them at the instance's transform).
//   <library name="L">        data/library/L/node.xml read with the same rules
//       and placed by the element's transform (libraries nest).
//   These may be children of the scene or of <track>. Everything else
//   (lights, items, check lines, particle emitters, sounds, curves of
//   animated objects, billboards: textured sprites without a mesh) adds no
//   triangles. Animated objects are taken at their xyz/hpr/scale.
// What is skipped:
//   - interaction in options.skip_interactions: collision-only proxies
//     (both spellings occur: "physics-only" in tracks, "physicsonly" in the
//     library, e.g. the invisible cylinder of every pine tree);
//   - type="cutscene_camera" (the camera's model, cut-scenes only);
//   - an `if` condition false in the race the options describe (forward
//     unless options.reverse, single player, no network, no capture-the-flag;
//     "false" is never drawn). Unknown conditions are kept.
//   geometry-level (the player's detail setting) is ignored: all is kept.
// Transforms (Irrlicht's convention, which the game uses): a point p of a
// mesh goes to xyz + R * (scale * p), R = Rz(hpr[2]) * Ry(hpr[1]) *
// Rx(hpr[0]), angles in degrees, then through the enclosing library's
// transform. Models are looked for in the directory of the file that names
// them, then the track directory, then data/models.
//
// Errors (missing or malformed file, unknown LOD group, missing model, bad
// number) name the file and line.
#ifndef KDTREE_CC_SCENES_STK_TRACK_H_
#define KDTREE_CC_SCENES_STK_TRACK_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/scenes/mesh.h"

namespace kdtree {
namespace scenes {

struct StkTrackOptions {
  // The data directory holding library/ and models/; empty: two levels above
  // the track directory (data/tracks/NAME).
  std::string data_dir;
  // false: keep every object whatever its `if` condition (both the forward
  // and the reverse start gates, for instance).
  bool evaluate_conditions = true;
  // The race direction conditions are evaluated for.
  bool reverse = false;
  // Objects (and LOD members) with these `interaction` values are skipped.
  std::vector<std::string> skip_interactions = {"physics-only", "physicsonly"};
  // The game's frame is Irrlicht's: y up, left-handed. true negates z, giving
  // a right-handed y-up frame in which the track is not mirrored.
  bool right_handed = true;
  // Deepest nesting of libraries (guards against a library including itself).
  int max_library_depth = 8;
};

struct StkTrackStats {
  int64_t placed = 0;         // meshes placed, the main track mesh included
  int64_t lod_instances = 0;  // of which chosen from a LOD group
  int64_t libraries = 0;      // library nodes instanced
  int64_t models = 0;         // distinct .spm files read
  // Objects not placed, by reason: "interaction=physicsonly",
  // "if=isTrackReverse", "type=cutscene_camera", "no mesh: type=billboard".
  std::map<std::string, int64_t> skipped;
};

absl::StatusOr<Mesh> ReadStkTrack(const std::string& track_dir,
                                  const StkTrackOptions& options = {},
                                  StkTrackStats* stats = nullptr);

}  // namespace scenes
}  // namespace kdtree

#endif  // KDTREE_CC_SCENES_STK_TRACK_H_
