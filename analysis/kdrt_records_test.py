"""The analysis on records that a real kdrt run made in this test.

//cc/tools:kdrt renders a generated scene of a few dozen triangles for every
variant of experiments/matrix.json (the nine and the beyond_variants, all
with --embree medium, --fast_render for its fast_render_variants), run by
experiments/run_matrix.py's own run_local (which wraps each record as the
matrix does: ok, job, profile, wall_s, node, backend, concurrent_jobs), with
kdrt's --scene replaced by the generated mesh and view. The records must
validate against cc/tools/kdrt_record.schema.json, and their values must land
in the right columns of kdtree_results.frame, the tables, the claims and the
Embree tables.

Under bazel the binary is in the runfiles; run directly (python3 -m unittest
from the checkout) it is $KDRT, else bazel-bin/cc/tools/kdrt (skipped when
there is none: build //cc/tools:kdrt).
"""

import argparse
import contextlib
import copy
import json
import os
import sys
import tempfile
import unittest
from unittest import mock

from analysis import claims
from analysis import context
from analysis import embree
from analysis import embree_build
from analysis import gallery
from analysis import kdtree_results as kr
from analysis import kdtree_tables
from analysis import latex
from analysis import provenance
from analysis import record_schema

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "experiments"))
import run_matrix  # noqa: E402  (experiments/run_matrix.py)

SCENE = "octagrid"
REPEATS = 2
COMMIT, TREE = "c0ffee" * 6 + "c0ff", "7ee" * 13 + "7"


def find_kdrt():
    for path in (os.environ.get("KDRT"), os.path.join(ROOT, "cc", "tools", "kdrt"),
                 os.path.join(ROOT, "bazel-bin", "cc", "tools", "kdrt")):
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    return None


def octahedron(cx, cz, r):
    """Vertices and faces (1-based from 1) of an octahedron at (cx, 0, cz)."""
    vs = [(cx, r, cz), (cx + r, 0, cz), (cx, 0, cz + r), (cx - r, 0, cz),
          (cx, 0, cz - r), (cx, -r, cz)]
    fs = [(1, 3, 2), (1, 4, 3), (1, 5, 4), (1, 2, 5),
          (6, 2, 3), (6, 3, 4), (6, 4, 5), (6, 5, 2)]
    return vs, fs


def write_scene(directory):
    """A 3x2 grid of octahedra of different sizes above a ground quad (50
    triangles) and a lit view of 64x48 pixels; returns (mesh, view)."""
    verts, faces = [(-6, -1.5, -6), (6, -1.5, -6), (6, -1.5, 6), (-6, -1.5, 6)], \
        [(1, 3, 2), (1, 4, 3)]
    for i in range(3):
        for j in range(2):
            vs, fs = octahedron(2.5 * (i - 1), 2.5 * j - 1.5, 0.5 + 0.2 * i + 0.1 * j)
            faces += [tuple(len(verts) + k for k in f) for f in fs]
            verts += vs
    mesh = os.path.join(directory, SCENE + ".obj")
    with open(mesh, "w") as f:
        f.writelines("v %g %g %g\n" % v for v in verts)
        f.writelines("f %d %d %d\n" % t for t in faces)
    view = os.path.join(directory, "lit.view")
    with open(view, "w") as f:
        f.write("camera { position 0.5 3 8 look_at 0 -0.5 0 fov 50 }\n"
                "resolution 64 48\nlight { position -3 6 3 }\n")
    return mesh, view


@contextlib.contextmanager
def kdrt_on_the_mesh(mesh, view, directory):
    """While active, the runner's kdrt commands read the mesh and view (for
    its --scene, which needs the scene cache), time under a lock of their
    own (not the machine's) and record the given code identity
    (cc/base/provenance.h reads these as the runner's key does)."""
    real_run = run_matrix.run_kdrt

    def run(cmd):
        i = cmd.index("--scene")
        return real_run(cmd[:i] + ["--mesh", mesh, "--view", view, "--cache_dir="]
                        + cmd[i + 2:])
    env = {"KDTREE_TIMING_LOCK": os.path.join(directory, "timing.lock"),
           "KDTREE_GIT_COMMIT": COMMIT, "KDTREE_SOURCE_TREE": TREE}
    with mock.patch.object(run_matrix, "run_kdrt", run), \
            mock.patch.object(run_matrix, "_tqdm", None), \
            mock.patch.dict(os.environ, env):
        yield


def matrix_settings():
    """A profile with Embree, as run_matrix makes its settings."""
    matrix = run_matrix.load_matrix()
    return {"repeats": REPEATS, "threads": 1, "embree": "medium",
            "fast_render": matrix["fast_render_variants"],
            "embree_timed": matrix["embree_timed_variants"],
            "triangle_bvh": matrix["triangle_bvh_variants"], "source_tree": TREE}


def run_the_matrix(kdrt, directory):
    """run_matrix.run_local over every variant on the generated scene, as a
    profile with Embree; returns the results file it appended to."""
    mesh, view = write_scene(directory)
    matrix = run_matrix.load_matrix()
    settings = matrix_settings()
    pending = [(SCENE, mesh, v) for v in matrix["variants"] + matrix["beyond_variants"]]
    out = os.path.join(directory, "out")
    os.makedirs(os.path.join(out, "results"))
    path = os.path.join(out, "results", kr.KDTREE_FILE)
    args = argparse.Namespace(kdrt=kdrt, out=out, profile="test")
    with kdrt_on_the_mesh(mesh, view, directory):
        failures = run_matrix.run_local(pending, settings, args, path, 1)
    if failures:
        with open(path) as f:
            raise AssertionError("%d kdrt runs failed: %s" % (failures, f.read()))
    return path


class KdrtRecordsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        kdrt = find_kdrt()
        if kdrt is None:
            raise unittest.SkipTest("no kdrt binary: build //cc/tools:kdrt")
        cls.tmp = tempfile.TemporaryDirectory()
        cls.addClassCleanup(cls.tmp.cleanup)
        cls.results_file = run_the_matrix(kdrt, cls.tmp.name)
        with open(cls.results_file) as f:
            cls.records = {r["preset"]: r for r in map(json.loads, f)}
        cls.manifest = os.path.join(cls.tmp.name, "manifest.json")
        with open(cls.manifest, "w") as f:
            json.dump({"scenes": [{"name": SCENE}]}, f)
        cls.schema = record_schema.load()
        cls.settings = matrix_settings()

    def setUp(self):
        self.out = tempfile.mkdtemp(dir=self.tmp.name)
        # A fastbuild kdrt's timings are not for the report: allowed here,
        # refused in test_a_build_not_for_timing_is_refused.
        self.ctx = context.Context(os.path.dirname(self.results_file),
                                   self.manifest, self.out,
                                   allow_unoptimized_timings=True)
        self.df = kr.frame(self.ctx.results(kr.KDTREE_FILE), self.ctx.manifest)

    def read(self, name):
        with open(os.path.join(self.out, name)) as f:
            return f.read()

    def row(self, variant):
        return self.df.loc[(SCENE, variant)]

    def test_every_variant_ran_and_validates(self):
        self.assertEqual(sorted(self.records), sorted(kr.VARIANTS + kr.BEYOND))
        for variant, rec in self.records.items():
            self.assertEqual(record_schema.validate(rec, self.schema,
                                                    record_schema.MATRIX_RECORD),
                             [], variant)

    def test_the_runner_adds_exactly_its_declared_fields(self):
        for rec in self.records.values():
            added = set(rec) - set(self.schema["kdrt"])
            self.assertEqual(added, set(self.schema["run_matrix"]))
            self.assertEqual(rec["job"][:6], [SCENE, rec["preset"], REPEATS, 1,
                                              run_matrix.embree_mode(rec["preset"], self.settings),
                                              TREE])
            self.assertEqual(rec["job"],
                             list(run_matrix.job_key(SCENE, rec["preset"], self.settings)))
            fast = rec["fast_render"] or {}
            self.assertEqual("triangle_bvh" in fast,
                             run_matrix.wants_triangle_bvh(rec["preset"], self.settings))
            self.assertEqual(rec["provenance"]["source_tree"], TREE)
            self.assertEqual(rec["provenance"]["commit"], COMMIT)

    def test_every_column_is_the_records_field(self):
        for variant, rec in self.records.items():
            row = self.row(variant)
            for name, path in kr.FIELDS.items():
                want = kr._get(rec, path)
                if want is None:
                    self.assertFalse(kr.present(row[name]), (variant, name))
                else:
                    self.assertEqual(row[name], want, (variant, name))

    def test_spot_columns(self):
        rec, row = self.records["clipping-pruning"], self.row("clipping-pruning")
        self.assertEqual(row["T_R"], rec["T_R"])
        self.assertEqual(row["N_I"], rec["N_I"])
        self.assertEqual(row["perf"], rec["perf_krays"])
        self.assertEqual(row["mem"], rec["mem_report_mb"])
        self.assertEqual(row["embree_ratio"], rec["embree"]["paired_ratio"])
        self.assertEqual(len(row["T_R_runs"]), REPEATS)
        self.assertEqual(row["n_tri"], 50)
        fast = self.records["sah-packet"]["fast_render"]
        self.assertEqual(self.row("sah-packet")["T_R_fast"], fast["T_R"])
        self.assertEqual(self.row("sah-packet")["fast_ratio"], fast["paired_ratio"])
        self.assertIsNone(rec["fast_render"])

    def test_tables_print_the_records(self):
        macros = kdtree_tables.generate(self.ctx)
        self.assertEqual(macros["NumKdRuns"][0], "9")
        self.assertEqual(macros["TimingRepeats"][0], str(REPEATS))
        for k, variants in enumerate(kr.GROUPS):
            times, sizes = self.read("table%d.tex" % (2 + k)), self.read("table%d.tex" % (5 + k))
            for v in variants:
                rec = self.records[v]
                self.assertIn(latex.escape(kr.TITLES[v]), times)
                self.assertIn(kdtree_tables.fmt("time", rec["T_R"]), times)
                self.assertIn(kdtree_tables.fmt("f2", rec["N_IT"]), times)
                self.assertIn(kdtree_tables.fmt("int", rec["N_TP"]), sizes)
        rays = self.read("table1_rays.tex")
        rec = self.records[kr.VARIANTS[-1]]
        self.assertIn(" & ".join(latex.fmt_int(rec[c]) for c in
                                 ("n_tri", "P_hit", "P_miss", "S_hit", "S_miss")), rays)

    def test_claims_test_the_records_values(self):
        by_id = {c[0][0]: c[1:] for c in claims.evaluate(self.df)}
        a, b = self.records["median-24-2"], self.records["median-16-2"]
        agrees = a["N_IT"] < b["N_IT"] and a["N_TR"] > b["N_TR"]
        self.assertEqual(by_id["depth"][:3], (int(agrees), 1, 0))
        self.assertAlmostEqual(by_id["depth"][3], a["N_IT"] / b["N_IT"])
        macros = claims.generate(self.ctx)
        self.assertEqual(macros["ClaimsTotal"][0], str(len(claims.CLAIMS)))

    def test_embree_is_timed_on_the_listed_variants_and_compared_on_all(self):
        timed = set(run_matrix.load_matrix()["embree_timed_variants"])
        for v, rec in self.records.items():
            e = rec["embree"]
            self.assertEqual(e["timed"], v in timed, v)
            self.assertEqual(len(e["T_R_runs"]), REPEATS if v in timed else 0, v)
            self.assertEqual(rec["job"][4], "medium" if v in timed else "medium untimed")
            self.assertIsNotNone(rec["disagreements"], v)
            if v not in timed:
                self.assertIsNone(rec["perf_ratio_kd_over_embree"], v)
                self.assertNotIn("paired_ratio", rec["fast_render"] or {}, v)

    def test_embree_tables_use_the_paired_ratios(self):
        nine = {v: self.records[v] for v in kr.VARIANTS}
        best = min(nine, key=lambda v: nine[v]["T_R"])
        row = embree.rows(self.df)[0]
        self.assertEqual(row["best_variant"], best)
        self.assertEqual(row["ratio_final"],
                         nine[embree.FINAL]["perf_ratio_kd_over_embree"])
        self.assertEqual(row["runs_final"],
                         nine[embree.FINAL]["embree"]["paired_ratio_runs"])
        beyond = self.records[embree.BEYOND]
        self.assertEqual(row["ratio_fast"], beyond["fast_render"]["paired_ratio"])
        self.assertEqual(row["kd_wrong"], sum(r["disagreements"]["reference_wrong"]
                                              for r in self.records.values()))
        self.assertEqual(embree.generate(self.ctx)["EmbreeScenes"][0], "1")
        binned = embree_build.rows(self.df)[0]
        self.assertEqual(binned["T_B"], self.records[embree_build.FAST]["T_B"])
        self.assertEqual(binned["report_T_B"], self.records[embree_build.REPORT]["T_B"])
        embree_build.generate(self.ctx)

    def test_the_gallery_shows_the_image_the_runner_asked_for(self):
        images = os.path.join(os.path.dirname(self.ctx.results_dir), "images")
        for variant, rec in self.records.items():
            self.assertEqual(rec["image"], os.path.join(images, "%s_%s.png" % (SCENE, variant)))
        self.assertEqual(gallery.generate(self.ctx)["GalleryImages"][0], "1")

    def test_a_build_not_for_timing_is_refused(self):
        prov = self.records["clipping"]["provenance"]
        if prov["timing_build"]:
            self.skipTest("kdrt was built for timing (-c opt)")
        ctx = context.Context(self.ctx.results_dir, self.manifest, self.out)
        with self.assertRaisesRegex(provenance.UnoptimizedTimingError,
                                    "--allow_unoptimized_timings"):
            kdtree_tables.generate(ctx)

    def append(self, rec):
        """A copy of the results with rec appended; its context."""
        results = tempfile.mkdtemp(dir=self.tmp.name)
        with open(self.results_file) as f, \
                open(os.path.join(results, kr.KDTREE_FILE), "w") as out:
            out.write(f.read() + json.dumps(rec) + "\n")
        return context.Context(results, self.manifest, self.out,
                               allow_unoptimized_timings=True)

    def test_a_record_of_other_code_stops_the_tables(self):
        rec = copy.deepcopy(self.records["binning-8"])
        rec["scene"], rec["provenance"]["source_tree"] = "other", "e" * 40
        with self.assertRaisesRegex(provenance.ProvenanceError,
                                    "2 provenances.*--allow_mixed_provenance"):
            kdtree_tables.generate(self.append(rec))

    def test_a_record_without_provenance_is_of_unknown_provenance(self):
        rec = copy.deepcopy(self.records["binning-8"])
        del rec["provenance"]
        with self.assertRaisesRegex(provenance.ProvenanceError,
                                    "unknown provenance.*octagrid/binning-8"):
            claims.generate(self.append(rec))


if __name__ == "__main__":
    unittest.main()
