"""experiments/self_contained.py on files made in the test."""

import os
import subprocess
import tempfile
import unittest

import self_contained


class SelfContainedTest(unittest.TestCase):
    def test_names_every_path_outside_the_repository(self):
        with tempfile.TemporaryDirectory() as root:
            files = {
                "ok.md": "see data/README.md and ./shared/x, a/work/b, ~/work/c\n",
                "notes.md": "as ../shared/notes/seed-facts.md says\n",
                "rc": "line one\n# see /work/main/out\n",
                "home.sh": "cp /root/.cache/x .\n",
                "seed.py": "# shared/seed/000.txt\n",
                "blob.bin": "\0../shared/notes",
            }
            for name, text in files.items():
                with open(os.path.join(root, name), "w") as f:
                    f.write(text)
            hits = self_contained.outside_references(root, sorted(files) + ["gone.txt"])
            self.assertEqual([(n, line) for n, line, _ in hits],
                             [("home.sh", 1), ("notes.md", 1), ("rc", 2), ("seed.py", 1)])

    def test_main_reads_git_and_fails_on_a_hit(self):
        with tempfile.TemporaryDirectory() as root:
            subprocess.run(["git", "init", "-q", root], check=True)
            with open(os.path.join(root, "a.md"), "w") as f:
                f.write("fine\n")
            subprocess.run(["git", "-C", root, "add", "a.md"], check=True)
            self.assertEqual(self_contained.main([root]), 0)
            with open(os.path.join(root, "b.md"), "w") as f:
                f.write("read ../shared/notes/x.md\n")
            subprocess.run(["git", "-C", root, "add", "b.md"], check=True)
            self.assertEqual(self_contained.main([root]), 1)


    def test_a_copy_without_git_is_walked(self):
        with tempfile.TemporaryDirectory() as root:
            os.makedirs(os.path.join(root, "out"))
            os.makedirs(os.path.join(root, "cc"))
            with open(os.path.join(root, "out", "log.txt"), "w") as f:
                f.write("/work/main/out\n")  # generated: not scanned
            with open(os.path.join(root, "cc", "a.h"), "w") as f:
                f.write("// fine\n")
            self.assertEqual(sorted(self_contained.tracked_files(root)),
                             [os.path.join("cc", "a.h")])
            self.assertEqual(self_contained.main([root]), 0)


if __name__ == "__main__":
    unittest.main()
