"""Tests of experiments/provenance.py's machine fields: the cases and the
expected strings of cc/base/provenance_test.cc (CpuIdentity, CpuCaches), so
that the Python runners' records name a CPU as the C++ records do."""

import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import provenance  # noqa: E402


class MachineTest(unittest.TestCase):
    def setUp(self):
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        self.tmp = tmp.name

    def file(self, name, text):
        path = os.path.join(self.tmp, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        return path

    def test_cpu_named_by_family_model_and_stepping(self):
        cpuinfo = self.file(
            "cpuinfo",
            "processor\t: 0\nvendor_id\t: GenuineIntel\ncpu family\t: 6\nmodel\t\t: 106\n"
            "model name\t: Intel(R) Xeon(R) Processor @ 2.80GHz\nstepping\t: 6\n\n"
            "processor\t: 1\nvendor_id\t: GenuineIntel\ncpu family\t: 6\nmodel\t\t: 143\n")
        self.assertEqual(provenance.cpu_id(cpuinfo), "GenuineIntel family 6 model 106 stepping 6")
        self.assertEqual(provenance.cpu_value("model name", cpuinfo),
                         "Intel(R) Xeon(R) Processor @ 2.80GHz")
        # "model name" first: "model" must match the key exactly, not a prefix.
        self.assertEqual(provenance.cpu_id(self.file(
            "name_first", "model name\t: X @ 1GHz\ncpu family\t: 25\nmodel\t\t: 17\n")),
            "family 25 model 17")
        self.assertIsNone(provenance.cpu_id(self.file("no_model", "vendor_id\t: GenuineIntel\n")))
        self.assertIsNone(provenance.cpu_id("/nonexistent/cpuinfo"))
        # As CpuInfoValue: the first line with the key decides, even empty;
        # the value keeps its trailing blanks; a key with leading blanks is
        # another key.
        odd = self.file("odd", "model name\t:\nmodel name\t: B\nx\t:  tail  \n model\t: 1\n")
        self.assertIsNone(provenance.cpu_value("model name", odd))
        self.assertEqual(provenance.cpu_value("x", odd), "tail  ")
        self.assertIsNone(provenance.cpu_value("model", odd))
        self.assertIsNone(provenance.cpu_value("model name", "/nonexistent/cpuinfo"))

    def test_caches_listed_by_level_and_type(self):
        rows = [("1", "Data", "48K"), ("1", "Instruction", "32K"), ("2", "Unified", "1280K"),
                ("3", "Unified", "49152K")]
        for i, (level, kind, size) in enumerate(rows):
            self.file("cache/index%d/level" % i, level + "\n")
            self.file("cache/index%d/type" % i, kind + "\n")
            self.file("cache/index%d/size" % i, size + "\n")
        self.assertEqual(provenance.cpu_caches(os.path.join(self.tmp, "cache")),
                         "L1d 48K, L1i 32K, L2 1280K, L3 49152K")
        # A cache without a type file is named by its level alone; a gap ends the list.
        self.file("odd/index0/level", "2\n")
        self.file("odd/index0/size", "1024K\n")
        self.file("odd/index2/level", "3\n")
        self.file("odd/index2/size", "8192K\n")
        self.assertEqual(provenance.cpu_caches(os.path.join(self.tmp, "odd")), "L2 1024K")
        self.assertIsNone(provenance.cpu_caches("/nonexistent/cache"))

    def test_machine_has_the_records_fields(self):
        m = provenance.machine()
        self.assertEqual(set(m), {"cpu_model", "cpu_id", "cpu_caches", "cores"})
        self.assertGreaterEqual(m["cores"], 1)


if __name__ == "__main__":
    unittest.main()
