"""experiments/self_contained.py on files made in the test."""

import os
import subprocess
import tempfile
import unittest

import self_contained


# Paths outside a repository, assembled so that this file names none.
SHARED_NOTE = "/".join(["..", "shared", "notes", "seed-facts.md"])
WORKSPACE_OUT = "/" + "/".join(["work", "main", "out"])
HOME_CACHE = "/" + "/".join(["root", ".cache", "x"])
SEED_TEXT = "/".join(["shared", "seed", "000.txt"])


class SelfContainedTest(unittest.TestCase):
    def test_names_every_path_outside_the_repository(self):
        with tempfile.TemporaryDirectory() as root:
            files = {
                "ok.md": "see data/README.md and ./shared/x, a/work/b, ~/work/c\n",
                "notes.md": "as %s says\n" % SHARED_NOTE,
                "rc": "line one\n# see %s\n" % WORKSPACE_OUT,
                "home.sh": "cp %s .\n" % HOME_CACHE,
                "seed.py": "# %s\n" % SEED_TEXT,
                "blob.bin": "\0" + SHARED_NOTE,
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
                f.write("read %s\n" % SHARED_NOTE)
            subprocess.run(["git", "-C", root, "add", "b.md"], check=True)
            self.assertEqual(self_contained.main([root]), 1)


    def test_a_copy_without_git_is_walked(self):
        with tempfile.TemporaryDirectory() as root:
            os.makedirs(os.path.join(root, "out"))
            os.makedirs(os.path.join(root, "cc"))
            with open(os.path.join(root, "out", "log.txt"), "w") as f:
                f.write(WORKSPACE_OUT + "\n")  # generated: not scanned
            with open(os.path.join(root, "cc", "a.h"), "w") as f:
                f.write("// fine\n")
            self.assertEqual(sorted(self_contained.tracked_files(root)),
                             [os.path.join("cc", "a.h")])
            self.assertEqual(self_contained.main([root]), 0)


if __name__ == "__main__":
    unittest.main()
