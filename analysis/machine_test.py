"""machine: what the records add to the machine's CPU name."""
import unittest

from analysis import machine
from analysis import testdata

MODEL = "Fixture CPU @ 1.00GHz"
FULL = dict(cpu_id="GenuineIntel family 6 model 106 stepping 6", cpu_caches="L2 1280K")


def rec(scene, **prov):
    return testdata.kdrt_record(scene, "clipping", provenance=testdata.provenance(**prov))


class RecordsCpuTest(unittest.TestCase):
    def test_the_records_name_it_in_full(self):
        self.assertEqual(machine.records_cpu([rec("a", **FULL), rec("b", **FULL)], MODEL),
                         " (GenuineIntel family 6 model 106 stepping 6; L2 1280K)")

    def test_two_cpus_or_another_model_leave_the_machine_name(self):
        other = dict(FULL, cpu_id="GenuineIntel family 6 model 143 stepping 8")
        self.assertEqual(machine.records_cpu([rec("a", **FULL), rec("b", **other)], MODEL), "")
        self.assertEqual(machine.records_cpu([rec("a", **FULL)], "Another CPU"), "")
        self.assertEqual(machine.records_cpu([], MODEL), "")

    def test_runs_of_spaces_do_not_matter(self):
        padded = "Intel(R) Xeon(R) CPU           X5650  @ 2.67GHz"
        r = testdata.kdrt_record("a", "clipping",
                                 provenance=testdata.provenance(cpu_model=padded, **FULL))
        self.assertEqual(machine.records_cpu([r], "Intel(R) Xeon(R) CPU X5650 @ 2.67GHz"),
                         " (GenuineIntel family 6 model 106 stepping 6; L2 1280K)")

    def test_older_records_add_nothing(self):
        self.assertEqual(machine.records_cpu([rec("a")], MODEL), "")


if __name__ == "__main__":
    unittest.main()
