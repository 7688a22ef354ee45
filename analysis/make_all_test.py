import os
import re
import tempfile
import unittest

from analysis import accuracy
from analysis import make_all
from analysis import robustness
from analysis import row18
from analysis import seed_tables
from analysis import testdata

# Every \newcommand that report/main.tex relies on must be generated.
EXPECTED_MACROS = [
    "MachineCPU", "MachineCores", "MachineMemory", "MachineOS",
    "MachineCompiler", "GitCommit", "GitCommitFull", "GitDirty",
    "ResultsDate", "NumScenes", "NumScenesTried", "NumScenesFailed",
    "NumScenesWithExpected", "NumScenesMatchExpected", "TotalTriangles",
    "LargestScene", "LargestSceneTriangles", "NumReportScenesCovered",
    "NumReportScenes", "Profile",
] + row18.MACROS + [
    "KdCpus", "NumKdScenes", "NumKdRuns", "TimingRepeats", "TimingBudget",
    "TimingMinRuns", "TimingJobs", "ClaimsTotal", "ClaimsConfirmed",
    "ClaimsRefuted", "ClaimsMixed", "PlanarScene", "PlanarWorstVariant",
    "PlanarWorstLost", "PlanarWorstPixels", "PlanarDefaultLost",
    "PlanarTriangles", "EmbreeScenes", "EmbreeRatioMedian", "EmbreeRatioMin",
    "EmbreeRatioMax", "EmbreePacketScenes", "EmbreePacketRatioMedian",
    "EmbreePacketRatioMin", "EmbreePacketRatioMax", "EmbreePacketBigScenes",
    "EmbreePacketBigAtLeastSeventy", "EmbreeFastScenes", "EmbreeFastRatioMedian",
    "EmbreeFastRatioMin", "EmbreeFastRatioMax", "EmbreeFastBigScenes",
    "EmbreeFastBigAtLeastSeventy", "EmbreeOtherDisagreements", "EmbreeGrazingDisagreements",
    "EmbreeAtOriginDisagreements", "EmbreeKdWrong", "EmbreeEmbreeWrong",
    "BinnedScenes", "BinnedBuildOverEmbreeMedian", "BinnedPerfOverEmbreeMedian",
    "BinnedBuildOverReportMedian", "BinnedPerfOverReportMedian", "BinnedBeatsReportBoth",
    "BinnedComparedWithReport", "GalleryImages"
] + robustness.MACROS + accuracy.MACROS + seed_tables.COMPARE_MACROS


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
