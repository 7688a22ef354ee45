"""Validates data/manifest.json (no network, no cache needed)."""

import json
import math
import os
import re
import subprocess
import sys
import unittest
from pathlib import Path

# Not resolved: under bazel the runfiles copy of manifest.json is beside us.
HERE = Path(__file__).absolute().parent
sys.path.insert(0, str(HERE))

import fetch  # noqa: E402  (data/fetch.py: the code that reads the manifest)
import sources  # noqa: E402  (data/sources.py: where scenes come from)

MANIFEST = HERE / "manifest.json"
# The framing rule's tool (cc/render/framing.h): in the runfiles under bazel,
# else bazel-bin's (run as a script after `bazel build //cc/render:auto_view`).
if os.environ.get("TEST_SRCDIR"):
    AUTO_VIEW = (Path(os.environ["TEST_SRCDIR"]) / os.environ.get("TEST_WORKSPACE", "")
                 / "cc" / "render" / "auto_view")
else:
    AUTO_VIEW = HERE.parent / "bazel-bin" / "cc" / "render" / "auto_view"


def auto_view(bounds, up_axis, framing):
    """(camera, light) the framing rule gives for these bounds."""
    lo, hi = bounds
    out = subprocess.run([str(AUTO_VIEW), "--bounds=" + ",".join(repr(float(x)) for x in lo + hi),
                          f"--up_axis={up_axis}", f"--framing={framing}"],
                         stdout=subprocess.PIPE, text=True, check=True).stdout
    line = json.loads(out)
    return line["camera"], line["light"]

REPORT_SCENES = {
    1: "A10", 2: "Armadillo", 3: "asianDragon", 4: "city2", 5: "city", 6: "conference",
    7: "fforest", 8: "park", 9: "sibenik", 10: "teapots", 11: "buddha", 12: "hairball",
    13: "lost.empire", 14: "powerplant", 15: "rungholt", 16: "san-miguel", 17: "sponza",
    18: "suzanne",
}
KINDS = {"package", "npm", "generator", "blender", "url"}
ROLES = {"original", "stand-in", "variant", "extra"}
GENERATOR_KINDS = {"hairball", "voxel", "teapots", "city", "forest", "subdivide", "refine", "plant",
                   "courtyard"}
FIELDS = {
    "name", "report_scene", "report_name", "role", "kind", "package", "npm_version", "path",
    "member", "url", "convert", "skip_nodes", "generator", "format", "licence", "source",
    "expected_triangles", "bounds", "up_axis", "framing", "profiles", "optional", "camera",
    "light", "notes",
}
FORMATS = {"obj", "ply", "off", "blend", "glb", "ac"}
# Conversions fetch.py applies (None: the file is used as packaged).
CONVERTS = {None, "teapot-js", "stk-track", "q3-bsp", "assimp-ply"}


def is_vec3(v):
    return (isinstance(v, list) and len(v) == 3
            and all(isinstance(x, (int, float)) and math.isfinite(x) for x in v))


class ManifestTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        with open(MANIFEST, encoding="utf-8") as f:
            cls.manifest = json.load(f)
        cls.scenes = cls.manifest["scenes"]

    def test_top_level(self):
        self.assertEqual(set(self.manifest["profiles"]), set(fetch.PROFILES))
        self.assertIsInstance(self.manifest["missing"], list)
        self.assertGreaterEqual(len(self.scenes), 20)

    def test_every_field_present_and_typed(self):
        for s in self.scenes:
            with self.subTest(scene=s.get("name")):
                self.assertEqual(set(s), FIELDS)
                self.assertRegex(s["name"], r"^[a-z0-9][a-z0-9-]*$")
                self.assertIn(s["kind"], KINDS)
                self.assertIn(s["role"], ROLES)
                self.assertIn(s["format"], FORMATS)
                self.assertIn(s["up_axis"], (1, 2))
                self.assertIn(s["framing"], ("object", "landscape", "interior"))
                self.assertIsInstance(s["optional"], bool)
                self.assertTrue(s["licence"] and isinstance(s["licence"], str))
                self.assertTrue(s["source"] and isinstance(s["source"], str))
                et = s["expected_triangles"]
                self.assertTrue(isinstance(et, int) and et > 0, et)
                skip = s["skip_nodes"]
                if skip is not None:  # node names, for the assimp-ply conversion only
                    self.assertEqual(s["convert"], "assimp-ply")
                    self.assertTrue(skip and all(isinstance(n, str) and n for n in skip), skip)

    def test_names_unique(self):
        names = [s["name"] for s in self.scenes]
        self.assertEqual(len(names), len(set(names)))

    def test_profiles_valid(self):
        for s in self.scenes:
            with self.subTest(scene=s["name"]):
                self.assertTrue(s["profiles"])
                self.assertTrue(set(s["profiles"]) <= set(fetch.PROFILES), s["profiles"])
                self.assertEqual(len(s["profiles"]), len(set(s["profiles"])))
        for profile in fetch.PROFILES:
            self.assertTrue(any(profile in s["profiles"] for s in self.scenes), profile)

    def test_profiles_nest_quick_standard_full(self):
        # quick is a subset of standard, standard of full.
        def members(p):
            return {s["name"] for s in self.scenes if p in s["profiles"]}
        self.assertLessEqual(members("quick"), members("standard"))
        self.assertLessEqual(members("standard"), members("full"))

    def test_test_profile_is_tiny(self):
        test = [s for s in self.scenes if "test" in s["profiles"]]
        names = {s["name"] for s in test}
        self.assertIn("bunny", names)
        self.assertIn("suzanne", names)
        self.assertTrue(any(s["kind"] == "generator" for s in test))
        self.assertLessEqual(sum(s["expected_triangles"] for s in test), 150000)
        self.assertFalse(any(s["kind"] == "url" for s in test))

    def test_report_scene_references(self):
        for s in self.scenes:
            with self.subTest(scene=s["name"]):
                rs = s["report_scene"]
                if rs is None:
                    self.assertIsNone(s["report_name"])
                    self.assertEqual(s["role"], "extra")
                else:
                    self.assertIn(rs, REPORT_SCENES)
                    self.assertEqual(s["report_name"], REPORT_SCENES[rs])
                    self.assertNotEqual(s["role"], "extra")

    def test_one_original_and_one_stand_in_per_report_scene(self):
        for role in ("original", "stand-in"):
            seen = {}
            for s in self.scenes:
                if s["role"] == role:
                    self.assertNotIn(s["report_scene"], seen,
                                     f"{role} of scene {s['report_scene']}: "
                                     f"{seen.get(s['report_scene'])} and {s['name']}")
                    seen[s["report_scene"]] = s["name"]

    def test_all_18_report_scenes_referenced_or_missing(self):
        referenced = {s["report_scene"] for s in self.scenes if s["report_scene"]}
        missing = {}
        for m in self.manifest["missing"]:
            self.assertEqual(set(m), {"report_scene", "report_name", "what", "reason"})
            self.assertEqual(m["report_name"], REPORT_SCENES[m["report_scene"]])
            self.assertGreater(len(m["reason"]), 20)
            missing.setdefault(m["report_scene"], []).append(m["what"])
        for n in REPORT_SCENES:
            self.assertTrue(n in referenced or n in missing, f"report scene {n} not covered")
        # A report scene with no stand-in nor original entry must say why.
        for n in REPORT_SCENES:
            roles = {s["role"] for s in self.scenes if s["report_scene"] == n}
            if not roles & {"stand-in", "original"}:
                self.assertIn(n, missing)

    def test_source_fields_by_kind(self):
        debian_name = re.compile(r"^[a-z0-9][a-z0-9+.-]+$")
        names = {s["name"]: s for s in self.scenes}
        for s in self.scenes:
            with self.subTest(scene=s["name"]):
                k = s["kind"]
                self.assertIn(s["convert"], CONVERTS)
                if k == "package":
                    self.assertRegex(s["package"], debian_name)
                    self.assertTrue(s["path"] and not s["path"].startswith("/"))
                    if s["member"]:
                        self.assertTrue(s["path"].endswith((".tar.gz", ".zip", ".pk3")))
                    if s["convert"] == "stk-track":  # a track's scene.xml -> PLY
                        self.assertEqual(s["package"], "supertuxkart-data")
                        self.assertRegex(s["path"], r"^" + re.escape(sources.STK_DATA)
                                         + r"tracks/[a-z0-9_]+/scene\.xml$")
                        self.assertIsNone(s["member"])
                        self.assertEqual(s["format"], "ply")
                    elif s["convert"] == "q3-bsp":  # a map inside a .pk3 -> PLY (our reader)
                        self.assertTrue(s["path"].endswith(".pk3"))
                        self.assertRegex(s["member"], r"^maps/[^/]+\.bsp$")
                        self.assertEqual(s["format"], "ply")
                    elif s["convert"] == "assimp-ply":  # any assimp format -> PLY
                        self.assertEqual(s["format"], "ply")
                    else:
                        self.assertIsNone(s["convert"])
                        target = s["member"] or s["path"]
                        self.assertEqual(target.rsplit(".", 1)[-1].lower(), s["format"])
                    self.assertIn(s["package"], s["licence"])  # read from its copyright file
                elif k == "npm":
                    self.assertTrue(s["package"] and s["npm_version"])
                    self.assertTrue(s["path"].startswith("package/"))
                elif k == "generator":
                    g = s["generator"]
                    self.assertIn(g["kind"], GENERATOR_KINDS)
                    self.assertIsInstance(g["seed"], int)
                    self.assertGreater(g["triangles"], 0)
                    self.assertEqual(s["format"], "ply")
                    if g["kind"] in ("teapots", "subdivide", "refine"):
                        self.assertIn(g.get("input"), names)
                        # The input is fetched in every profile that needs it.
                        self.assertTrue(set(s["profiles"]) <= set(names[g["input"]]["profiles"]))
                    if g["kind"] in ("plant", "courtyard"):
                        self.assertTrue(g["parts"])
                        roles = {p["role"] for p in g["parts"]}
                        self.assertIn("machine" if g["kind"] == "plant" else "tree", roles)
                        for p in g["parts"]:
                            self.assertGreater(p["height"], 0)
                            if "scene" in p:
                                self.assertIn(p["scene"], names)
                                self.assertTrue(set(s["profiles"])
                                                <= set(names[p["scene"]]["profiles"]))
                            else:
                                self.assertRegex(p["package"], debian_name)
                                self.assertIn(p["package"], s["licence"] + " " + p["package"])
                                self.assertFalse(p["path"].startswith("/"))
                    if g["kind"] in ("refine", "plant", "courtyard"):  # exact by construction
                        self.assertEqual(s["expected_triangles"], g["triangles"])
                    if g["kind"] in ("hairball", "city", "forest"):  # these hit their target
                        self.assertLessEqual(abs(s["expected_triangles"] - g["triangles"]),
                                             0.01 * g["triangles"])
                elif k == "url":
                    self.assertTrue(s["url"].startswith("https://casual-effects.com/"))
                    self.assertTrue(s["member"])
                    self.assertTrue(s["optional"])
                    self.assertEqual(s["role"], "original")
                elif k == "blender":
                    self.assertEqual(s["name"], "suzanne")
                    self.assertEqual(s["expected_triangles"], 968)
                if k != "generator":
                    self.assertIsNone(s["generator"])

    def test_big_packages_only_in_full(self):
        for s in self.scenes:
            parts = (s["generator"] or {}).get("parts", [])
            if s["package"] == "flightgear-data-base" or any(
                    p.get("package") == "flightgear-data-base" for p in parts):
                self.assertEqual(s["profiles"], ["full"], s["name"])
            # SuperTuxKart (628 MB) holds the real forest, city, interior and plants
            # tracks, Nexuiz (267 MB) the sponza stand-in: standard and full only.
            if s["package"] in ("supertuxkart-data", "nexuiz-data"):
                self.assertEqual(s["profiles"], ["standard", "full"], s["name"])
            if s["kind"] == "url":
                self.assertEqual(s["profiles"], ["full"], s["name"])

    def test_sizes_per_profile(self):
        for s in self.scenes:
            if "quick" in s["profiles"] or "test" in s["profiles"]:
                self.assertLessEqual(s["expected_triangles"], 250000, s["name"])
            if "standard" in s["profiles"]:
                self.assertLessEqual(s["expected_triangles"], 1500000, s["name"])

    def test_camera_and_light(self):
        if not AUTO_VIEW.exists():
            self.skipTest(f"{AUTO_VIEW} is not built (bazel build //cc/render:auto_view)")
        for s in self.scenes:
            with self.subTest(scene=s["name"]):
                cam, light, bounds = s["camera"], s["light"], s["bounds"]
                if cam is None:
                    self.assertIsNone(light)
                    self.assertEqual(s["kind"], "url")  # only unmeasured originals
                    continue
                self.assertEqual(set(cam), {"position", "look_at", "up", "fov_deg"})
                for key in ("position", "look_at", "up"):
                    self.assertTrue(is_vec3(cam[key]), key)
                self.assertTrue(0 < cam["fov_deg"] < 180)
                self.assertEqual(set(light), {"position"})
                self.assertTrue(is_vec3(light["position"]))
                self.assertTrue(is_vec3(bounds[0]) and is_vec3(bounds[1]))
                # The default is what the framing rule gives for these bounds.
                want_cam, want_light = auto_view(bounds, s["up_axis"], s["framing"])
                self.assertEqual(cam, want_cam)
                self.assertEqual(light, want_light)
                # Camera outside the box, looking at its centre.
                lo, hi = bounds
                inside = all(a <= p <= b for a, p, b in zip(lo, cam["position"], hi))
                self.assertFalse(inside)

    def test_selection_orders_inputs_first(self):
        for profile in fetch.PROFILES:
            order = [s["name"] for s in fetch.select(self.manifest, profile, [])]
            for s in fetch.select(self.manifest, profile, []):
                g = s["generator"] or {}
                if g.get("input"):
                    self.assertLess(order.index(g["input"]), order.index(s["name"]))
        names = [s["name"] for s in fetch.select(self.manifest, "full", ["teapots"])]
        self.assertEqual(names, ["teapot", "teapots"])
        # A generator's parts that are scenes come first too.
        for s in self.scenes:
            for name in fetch.parts.part_scenes(s):
                order = [e["name"] for e in fetch.select(self.manifest, "full", [s["name"]])]
                self.assertLess(order.index(name), order.index(s["name"]))

    def test_source_key_follows_skip_nodes(self):
        # A cached scene is made again when the nodes its conversion leaves
        # out change; entries without any keep the key they had before
        # skip_nodes counted (no refetch of every cached scene).
        morse = next(s for s in self.scenes if s["name"] == "morse-trees")
        without = dict(morse, skip_nodes=None)
        self.assertNotEqual(fetch.source_key(morse), fetch.source_key(without))
        self.assertNotEqual(fetch.source_key(morse),
                            fetch.source_key(dict(morse, skip_nodes=["Other"])))
        absent = {k: v for k, v in without.items() if k != "skip_nodes"}
        self.assertEqual(fetch.source_key(without), fetch.source_key(absent))
        bunny = next(s for s in self.scenes if s["name"] == "bunny")
        self.assertEqual(fetch.source_key(bunny), "c84052b1c216a567")  # as before

    def test_every_report_scene_has_a_stand_in_in_full(self):
        # The full profile's Table 1: one stand-in (or the original) per report
        # scene, obtainable offline (not a url).
        for n in REPORT_SCENES:
            rows = [s for s in self.scenes if s["report_scene"] == n and "full" in s["profiles"]
                    and s["role"] in ("stand-in", "original") and s["kind"] != "url"]
            self.assertTrue(rows, f"report scene {n} has no offline stand-in in full")


class TeapotConverterTest(unittest.TestCase):
    """sources.py's writer of the npm teapot's JS arrays as binary PLY."""

    def test_binary_ply_layout(self):
        js = ("exports.positions=[[0,0,0],[1,0,0],[0,1,0],[0,0,1]];"
              "exports.cells=[[0,1,2],[0,2,3]];")
        p = Path(os.environ.get("TEST_TMPDIR", "/tmp")) / "t.ply"
        sources.teapot_js_to_ply(js, p)
        header, body = p.read_bytes().split(b"end_header\n")
        self.assertIn(b"element vertex 4", header)
        self.assertIn(b"element face 2", header)
        # 4 vertices of 3 floats, 2 faces of a count byte and 3 ints.
        self.assertEqual(len(body), 4 * 12 + 2 * 13)


class PartsTest(unittest.TestCase):
    """data/parts.py: the pieces that need no package or tool."""

    def setUp(self):
        self.dir = Path(os.environ.get("TEST_TMPDIR", "/tmp"))

    def test_part_key_depends_on_source_only(self):
        a = {"role": "tree", "height": 5, "package": "p", "path": "x.sh3f", "member": "a/a.obj"}
        b = dict(a, role="plant", height=1)
        self.assertEqual(fetch.parts.part_key(a), fetch.parts.part_key(b))
        self.assertNotEqual(fetch.parts.part_key(a),
                            fetch.parts.part_key(dict(a, member="b/b.obj")))

    def test_model_and_its_materials_taken_out_of_a_catalogue(self):
        import zipfile
        archive = self.dir / "cat.sh3f"
        with zipfile.ZipFile(archive, "w") as z:
            z.writestr("lib/tree/tree.obj", "v 0 0 0\n")
            z.writestr("lib/tree/tree.mtl", "newmtl a\n")
            z.writestr("lib/tree/sub/skip.png", "x")
            z.writestr("lib/other/other.obj", "v 1 1 1\n")
        out = fetch.parts.extract_model_dir(archive, "/lib/tree/tree.obj", self.dir / "tree",
                                            fetch.SceneError)
        self.assertEqual(out.read_text(), "v 0 0 0\n")
        self.assertEqual(sorted(p.name for p in out.parent.iterdir()), ["tree.mtl", "tree.obj"])
        with self.assertRaises(fetch.SceneError):
            fetch.parts.extract_model_dir(archive, "lib/none.obj", self.dir / "n",
                                          fetch.SceneError)


if __name__ == "__main__":
    unittest.main()
