"""What every generator gets: where the inputs are and where to write.

A generator is a module with `generate(ctx) -> dict` that writes its files
under `ctx.out_dir` (via `ctx.write`) and returns the LaTeX macros it defines
as {MacroName: (value, raw)} (`raw` = value is LaTeX already, not escaped).
make_all.py calls the generators in order and writes all macros to
macros.tex.

The override flags of make_all's command line ride along as attributes:
allow_mixed_provenance, allow_mixed_cpus and allow_unoptimized_timings
(analysis/provenance.py's checks read them).
"""

import os

from analysis import inputs
from analysis import latex
from experiments import jsonl  # the results files' one reader (strict)


class Context:
    def __init__(self, results_dir, manifest_path, out_dir, seed_dir=None,
                 allow_mixed_provenance=False, allow_mixed_cpus=False,
                 allow_unoptimized_timings=False):
        self.allow_mixed_provenance = allow_mixed_provenance
        self.allow_mixed_cpus = allow_mixed_cpus
        self.allow_unoptimized_timings = allow_unoptimized_timings
        self.results_dir = results_dir
        self.manifest_path = manifest_path
        self.out_dir = out_dir
        self.seed_dir = seed_dir or inputs.SEED_DIR
        self._cache = {}
        self.written = []

    def _get(self, key, load):
        if key not in self._cache:
            self._cache[key] = load()
        return self._cache[key]

    @property
    def manifest(self):
        """Manifest scenes (list of dicts with "number"); [] when the
        manifest file does not exist."""
        def load():
            if not os.path.exists(self.manifest_path):
                return []
            return inputs.load_manifest(self.manifest_path)
        return self._get("manifest", load)

    def results(self, name):
        """Raw records of results/<name> (a .jsonl file)."""
        return self._get(
            "results:" + name,
            lambda: jsonl.read(os.path.join(self.results_dir, name)))

    @property
    def machine(self):
        return self._get("machine",
                         lambda: inputs.load_machine(self.results_dir))

    @property
    def seed_table1(self):
        return self._get("seed1", lambda: inputs.load_seed_table1(
            os.path.join(self.seed_dir, "table1.csv")))

    def path(self, filename):
        return os.path.join(self.out_dir, filename)

    def write(self, filename, text):
        latex.write_text(self.path(filename), text)
        self.written.append(filename)
