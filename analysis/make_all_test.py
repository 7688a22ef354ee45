import contextlib
import io
import os
import re
import tempfile
import unittest

from analysis import accuracy
from analysis import clipping_errata
from analysis import embree_passes
from analysis import embree_structure
from analysis import make_all
from analysis import provenance_macros
from analysis import robustness
from analysis import row18
from analysis import seed_tables
from analysis import testdata
from analysis import tree_memory

# Every \newcommand that report/main.tex relies on must be generated.
EXPECTED_MACROS = [
    "MachineCPU", "MachineCPUDetail", "MachineCores", "MachineMemory", "MachineOS",
    "MachineCompiler", "GitCommit", "GitCommitFull", "GitDirty",
    "ResultsDate", "NumScenes", "NumScenesTried", "NumScenesFailed",
    "NumScenesWithExpected", "NumScenesMatchExpected", "TotalTriangles",
    "LargestScene", "LargestSceneTriangles", "NumReportScenesCovered",
    "NumReportScenes", "Profile",
] + row18.MACROS + [
    "KdCpus", "NumKdScenes", "NumKdRuns", "TimingRepeats", "TimingBudget",
    "TimingMinRuns", "TimingJobs", "ClaimsTotal", "ClaimsConfirmed",
    "ClaimsRefuted", "ClaimsMixed", "ClaimsWithinNoise", "PlanarScene", "PlanarWorstVariant",
    "PlanarWorstLost", "PlanarWorstPixels", "PlanarDefaultLost",
    "PlanarTriangles", "EmbreeScenes", "EmbreeRatioMedian", "EmbreeRatioMin",
    "EmbreeRatioMax", "EmbreeBigScenes", "EmbreeBigAtLeastSeventy",
    "EmbreePacketScenes", "EmbreePacketRatioMedian",
    "EmbreePacketRatioMin", "EmbreePacketRatioMax", "EmbreePacketBigScenes",
    "EmbreePacketBigAtLeastSeventy", "EmbreeFastScenes", "EmbreeFastRatioMedian",
    "EmbreeFastRatioMin", "EmbreeFastRatioMax", "EmbreeFastBigScenes",
    "EmbreeFastBigAtLeastSeventy", "EmbreeBestScenes", "EmbreeBestRatioMedian",
    "EmbreeBestRatioMin", "EmbreeBestRatioMax", "EmbreeBestBigScenes",
    "EmbreeBestBigAtLeastSeventy",
    *["EmbreeImage" + s for s in ("Scenes", "RatioMedian", "RatioMin", "RatioMax",
                                  "BigScenes", "BigAtLeastSeventy", "MillionScenes",
                                  "MillionAtLeastOne", "MillionClause", "BinnedScenes")],
    *[p + s for p in ("Embree", "EmbreePacket", "EmbreeFast", "EmbreeBest", "EmbreeImage")
      for s in ("BigAtLeastEighty", "BigAtLeastOne")],
    *[p + s for p in ("EmbreeSingle", "EmbreeRobust", "EmbreeRobustBest")
      for s in ("Scenes", "RatioMedian", "RatioMin", "RatioMax", "BigScenes",
                "BigAtLeastSeventy", "BigAtLeastEighty", "BigAtLeastOne")],
    "EmbreeRobustWrongScenes", "EmbreeRobustAtOriginClause",
    "EmbreeOtherDisagreements", "EmbreeGrazingDisagreements",
    "EmbreeAtOriginDisagreements", "EmbreeKdWrong", "EmbreeEmbreeWrong",
    "BinnedScenes", "BinnedBuildOverEmbreeMedian", "BinnedPerfOverEmbreeMedian",
    "BinnedBuildOverReportMedian", "BinnedPerfOverReportMedian", "BinnedBeatsReportBoth",
    "BinnedComparedWithReport", "GalleryImages",
    "CostImageFigures", "CostImageScenes", "CostImagesRefused",
    "OursOverFinalScenes", "OursOverFinalRatioMedian", "OursOverFinalRatioMin",
    "OursOverFinalRatioMax", "OursFastOverFinalScenes", "OursFastOverFinalRatioMedian",
    "OursFastOverFinalRatioMin", "OursFastOverFinalRatioMax",
] + tree_memory.MACROS + embree_passes.MACROS + embree_structure.MACROS + \
    clipping_errata.MACROS + \
    robustness.MACROS + accuracy.MACROS + seed_tables.COMPARE_MACROS + \
    provenance_macros.MACROS


class MakeAllTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.results, self.manifest = testdata.write_fixture(self.tmp.name)
        self.out = os.path.join(self.tmp.name, "report", "generated")

    def tearDown(self):
        self.tmp.cleanup()

    def read(self, name):
        with open(os.path.join(self.out, name), encoding="utf-8") as f:
            return f.read()

    def test_writes_everything(self):
        self.assertEqual(make_all.main(["--results", self.results,
                                        "--manifest", self.manifest,
                                        "--out", self.out]), 0)
        for name in ("macros.tex", "table1.tex", "seed_table1.tex",
                     "fig_scene_sizes.pdf"):
            self.assertTrue(os.path.getsize(os.path.join(self.out, name)) > 0,
                            name)
        with open(os.path.join(self.out, "fig_scene_sizes.pdf"), "rb") as f:
            self.assertEqual(f.read(5), b"%PDF-")
        macros = re.findall(r"\\newcommand\{\\(\w+)\}", self.read("macros.tex"))
        self.assertEqual(sorted(macros), sorted(EXPECTED_MACROS))
        text = self.read("macros.tex")
        self.assertIn("\\newcommand{\\MachineCPU}{Fixture CPU @ 1.00GHz}", text)
        self.assertIn("\\newcommand{\\GitCommit}{0123456789ab}", text)
        self.assertIn("\\newcommand{\\MachineMemory}{16.0\\,GiB}", text)

    def run_main(self, *flags):
        """make_all.main on the fixture; (exit code, stderr)."""
        err = io.StringIO()
        with contextlib.redirect_stderr(err), \
                contextlib.redirect_stdout(io.StringIO()):
            code = make_all.main(["--results", self.results, "--manifest",
                                  self.manifest, "--out", self.out] + list(flags))
        return code, err.getvalue()

    def kdtree_runs(self, **prov):
        """kdrt records of bunny (the fixture's provenance) and armadillo
        (its provenance changed by prov) for every variant."""
        testdata.write_kdtree(self.results, [
            testdata.kdrt_record(scene, v, provenance=testdata.provenance(
                **(prov if scene == "armadillo" else {})))
            for scene in ("bunny", "armadillo") for v in testdata.NINE])

    def test_states_the_provenance_of_the_runs(self):
        self.kdtree_runs()
        self.assertEqual(self.run_main(), (0, ""))
        text = self.read("macros.tex")
        self.assertIn("\\newcommand{\\ProvCommit}{0123456789ab}", text)
        self.assertIn("\\newcommand{\\ProvRecords}{18}", text)
        self.assertIn("embree_ratio.pdf", os.listdir(self.out))

    def test_two_provenances_stop_with_the_message(self):
        self.kdtree_runs(dirty=True, source_tree="c" * 40)
        code, err = self.run_main()
        self.assertEqual(code, 1)
        self.assertIn("would mix records of 2 provenances: 0123456789ab, opt "
                      "(9 records, e.g. bunny/median-16-2); 0123456789ab "
                      "+dirty cccccccccccc, opt (9 records", err)
        self.assertIn("--allow_mixed_provenance", err)
        self.assertFalse(os.path.exists(self.out))
        self.assertEqual(self.run_main("--allow_mixed_provenance"), (0, ""))
        self.assertIn("\\newcommand{\\ProvSourceTree}{89abcdef0123; cccccccccccc}",
                      self.read("macros.tex"))

    def test_unoptimised_timings_stop_with_the_message(self):
        self.kdtree_runs(compilation_mode="fastbuild", optimized=False,
                         timing_build=False)
        code, err = self.run_main("--allow_mixed_provenance")
        self.assertEqual(code, 1)
        self.assertIn("timings of armadillo/median-16-2 from a binary not "
                      "built for timing", err)
        self.assertEqual(self.run_main("--allow_mixed_provenance",
                                       "--allow_unoptimized_timings"), (0, ""))

    def test_two_cpus_stop_unless_allowed(self):
        self.kdtree_runs(cpu_model="Another CPU")
        code, err = self.run_main()
        self.assertEqual(code, 1)
        self.assertIn("--allow_mixed_cpus", err)
        self.assertEqual(self.run_main("--allow_mixed_cpus"), (0, ""))

    def test_main_tex_uses_only_generated_macros(self):
        """Every macro main.tex uses from macros.tex is generated."""
        here = os.path.dirname(os.path.abspath(__file__))
        main_tex = os.path.join(os.path.dirname(here), "report", "main.tex")
        if not os.path.exists(main_tex):
            self.skipTest("report/main.tex not in runfiles")
        with open(main_tex, encoding="utf-8") as f:
            used = set(re.findall(r"\\([A-Z][A-Za-z]+)", f.read()))
        generated = set(EXPECTED_MACROS)
        # Capitalised macros in main.tex are the generated ones, apart from
        # these few of LaTeX's own; anything else would be undefined.
        latex_own = {"PackageError", "IfFileExists"}
        self.assertEqual(sorted(used - generated - latex_own), [])

    def test_stale_files_removed_and_rerun(self):
        make_all.make_all(self.results, self.manifest, self.out)
        stale = os.path.join(self.out, "table99.tex")
        with open(stale, "w") as f:
            f.write("old")
        make_all.make_all(self.results, self.manifest, self.out)
        self.assertFalse(os.path.exists(stale))
        self.assertTrue(os.path.exists(os.path.join(self.out, "table1.tex")))

    def test_failure_keeps_previous_output(self):
        make_all.make_all(self.results, self.manifest, self.out)
        before = self.read("table1.tex")
        os.unlink(os.path.join(self.results, "machine.json"))
        self.assertEqual(make_all.main(["--results", self.results,
                                        "--manifest", self.manifest,
                                        "--out", self.out]), 1)
        self.assertEqual(self.read("table1.tex"), before)
        self.assertFalse(os.path.exists(self.out + ".new"))

    def test_refuses_foreign_directory(self):
        os.makedirs(self.out)
        with open(os.path.join(self.out, "precious.txt"), "w") as f:
            f.write("mine")
        with self.assertRaises(RuntimeError):
            make_all.make_all(self.results, self.manifest, self.out)
        self.assertTrue(os.path.exists(os.path.join(self.out, "precious.txt")))

    def test_duplicate_macro_is_an_error(self):
        class Gen:
            __name__ = "dup"

            @staticmethod
            def generate(ctx):
                return {"NumScenes": (1, False)}
        with self.assertRaises(RuntimeError):
            make_all.make_all(self.results, self.manifest, self.out,
                              generators=make_all.GENERATORS + [Gen])

    def test_all_failed_still_renders(self):
        recs = [testdata.record("bunny", ok=False, error="nope")]
        results, manifest = testdata.write_fixture(
            os.path.join(self.tmp.name, "failed"), records=recs)
        make_all.make_all(results, manifest, self.out)
        self.assertIn("failed$^{1}$", self.read("table1.tex"))
        self.assertIn("\\newcommand{\\NumScenes}{0}", self.read("macros.tex"))
        self.assertIn("\\newcommand{\\LargestScene}{none}",
                      self.read("macros.tex"))


if __name__ == "__main__":
    unittest.main()
