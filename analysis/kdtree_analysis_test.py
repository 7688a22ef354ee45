"""Tables 2-10 and figures 1-2 on kdrt records of the real shape
(analysis/testdata.py), and the provenance checks they apply."""

import os
import unittest

from analysis import claims
from analysis import context
from analysis import kdtree_figures
from analysis import kdtree_results as kr
from analysis import kdtree_tables
from analysis import provenance
from analysis import seed_tables
from analysis import testdata


class KdtreeAnalysisTest(testdata.KdtreeFixtureTest):

    def append(self, *records):
        testdata.write_kdtree(self.ctx.results_dir, records)

    def test_frame_keeps_successful_records_in_manifest_order(self):
        df = kr.frame(self.ctx.results(kr.KDTREE_FILE), self.ctx.manifest)
        self.assertEqual(len(df), 27)
        self.assertEqual(kr.scenes_in_order(df), ["gamma", "alpha", "beta"])
        self.assertEqual(df.loc[("alpha", "clipping")]["N_CL"], 3000)
        self.assertEqual(df.loc[("alpha", "binning-8")]["T_B"], 0.5)
        self.assertEqual(df.loc[("alpha", "clipping")]["T_R_runs"], [1.0] * 5)
        self.assertEqual(df.loc[("alpha", "clipping")]["provenance"]["commit"],
                         testdata.COMMIT)

    def test_every_field_is_where_kdrt_writes_it(self):
        """Each FIELDS path is one member of a real-shaped record (no
        aliases), except the Embree and fast-render ones when not run."""
        rec = testdata.kdrt_record(
            "alpha", "sah-packet", embree=testdata.embree(),
            fast_render=testdata.fast_render(
                [1.2], best=[0.9], robust=([0.8], [0.9], 0), single=[0.8],
                passes={p: [0.7] for p in ("camera_single", "shadow_single",
                                           "camera_packets", "shadow_packets")},
                tri=([0.8], [1.0], 4000)))
        missing = [name for name in kr.FIELDS
                   if kr.field(rec, name) is None]
        self.assertEqual(missing, [])
        self.assertTrue(all(isinstance(p, str) for p in kr.FIELDS.values()))

    def test_nine_tables_with_three_variants_each(self):
        macros = kdtree_tables.generate(self.ctx)
        self.assertEqual(macros["NumKdScenes"][0], "3")
        for n in range(2, 11):
            text = self.read("table%d.tex" % n)
            self.assertIn("tab:t%d" % n, text)
        self.assertIn("Spatial median 16/2", self.read("table2.tex"))
        self.assertIn("3,000", self.read("table10.tex"))
        self.assertIn("0.010", self.read("table5.tex"))
        rays = self.read("table1_rays.tex")
        self.assertIn("340", rays)
        self.assertEqual(macros["KdCpus"][0], "Fixture CPU @ 1.00GHz")

    def test_timing_macros_come_from_the_records(self):
        macros = kdtree_tables.generate(self.ctx)
        self.assertEqual(macros["TimingRepeats"][0], "5")
        self.assertIn("took 30\\,s in all", macros["TimingBudget"][0])
        self.assertEqual(macros["TimingMinRuns"][0], "1")
        self.assertEqual(macros["TimingJobs"][0], "2")

    def test_two_provenances_stop_every_table_unless_allowed(self):
        dirty = testdata.provenance(dirty=True, source_tree="fedcba98" * 5)
        self.append(testdata.kdrt_record("beta", "binning-8", provenance=dirty))
        for gen in (kdtree_tables, kdtree_figures, claims, seed_tables):
            with self.assertRaises(provenance.ProvenanceError) as cm:
                gen.generate(self.ctx)
            message = str(cm.exception)
            self.assertIn("0123456789ab, opt", message)
            self.assertIn("0123456789ab +dirty fedcba98fedc, opt", message)
            self.assertIn("--allow_mixed_provenance", message)
        self.ctx.allow_mixed_provenance = True
        self.assertEqual(kdtree_tables.generate(self.ctx)["NumKdScenes"][0], "3")
        kdtree_figures.generate(self.ctx)

    def test_a_record_without_provenance_is_another_provenance(self):
        rec = testdata.kdrt_record("beta", "binning-8")
        del rec["provenance"]
        self.append(rec)
        with self.assertRaisesRegex(provenance.ProvenanceError,
                                    "unknown provenance.*beta/binning-8"):
            kdtree_tables.generate(self.ctx)

    def test_timings_from_two_cpus_are_refused_unless_allowed(self):
        self.append(testdata.kdrt_record(
            "alpha", "binning-8", provenance=testdata.provenance(cpu_model="CPU A")))
        with self.assertRaisesRegex(provenance.MixedCpuError, "--allow_mixed_cpus"):
            kdtree_tables.generate(self.ctx)
        self.ctx.allow_mixed_cpus = True
        macros = kdtree_tables.generate(self.ctx)
        self.assertEqual(macros["KdCpus"][0], "CPU A; Fixture CPU @ 1.00GHz")

    def test_unoptimised_timings_are_refused_unless_allowed(self):
        slow = testdata.provenance(optimized=False, ndebug=False,
                                   timing_build=False)
        path = os.path.join(self.ctx.results_dir, kr.KDTREE_FILE)
        os.unlink(path)
        self.append(*[testdata.kdrt_record("alpha", v, provenance=slow)
                      for v in kr.VARIANTS])
        for gen in (kdtree_tables, kdtree_figures, claims):
            with self.assertRaises(provenance.UnoptimizedTimingError) as cm:
                gen.generate(self.ctx)
            self.assertIn("alpha/median-16-2", str(cm.exception))
            self.assertIn("--allow_unoptimized_timings", str(cm.exception))
        # Statistics without timings may come from any build of one code.
        seed_tables.generate(self.ctx)
        self.ctx.allow_unoptimized_timings = True
        self.assertEqual(kdtree_tables.generate(self.ctx)["NumKdRuns"][0], "9")

    def test_figures_are_written(self):
        kdtree_figures.generate(self.ctx)
        for name in ("fig1_build.pdf", "fig2_render.pdf"):
            with open(os.path.join(self.out, name), "rb") as f:
                self.assertEqual(f.read(4), b"%PDF")

    def test_no_runs_still_makes_every_file(self):
        empty = context.Context(os.path.join(self.tmp.name, "none"),
                                os.path.join(self.tmp.name, "none.json"),
                                self.out)
        kdtree_tables.generate(empty)
        kdtree_figures.generate(empty)
        claims.generate(empty)
        self.assertIn("no kd-tree runs", self.read("table3.tex"))
        self.assertIn("not tested", self.read("claims.tex"))


if __name__ == "__main__":
    unittest.main()
