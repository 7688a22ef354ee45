"""Table 1: the scene library as obtained and loaded on this machine.

Input : the manifest (what each scene is, where it comes from, how many
        triangles it should have) and results/scenes.jsonl (what scene_info
        actually loaded; written by experiments/run_scenes.py).
Output: table1.tex, table1_sources.tex (each scene's package or generator and
licence, for the appendix), plus the macros the text quotes about the scenes.
"""

from analysis import latex

SCENES_FILE = "scenes.jsonl"

_KIND_LABELS = {
    "package": "Debian",
    "npm": "npm",
    "generator": "generator",
    "blender": "Blender",
    "url": "download",
}


def generator_label(gen):
    """A generator entry in a few words: its kind, seed, input scene and how
    many packaged parts it places ('plant, seed 14, 7 parts'); the manifest
    keeps the rest (the parts' packages and paths would fill a page)."""
    if not isinstance(gen, dict):
        return str(gen)
    words = [str(gen.get("kind") or "?")]
    if gen.get("seed") is not None:
        words.append("seed %s" % gen["seed"])
    if gen.get("input"):
        words.append("from %s" % gen["input"])
    parts = gen.get("parts") or []
    if parts:
        words.append("%d part%s" % (len(parts), "" if len(parts) == 1 else "s"))
    return ", ".join(words)


def licence_label(licence):
    """The licence up to its first parenthesis ('CC0-1.0 (libcgal-demo's ...
    links to ...)' -> 'CC0-1.0'); the parenthesis says where it is stated, and
    the manifest keeps it (in the table it made the rows pages tall)."""
    return (licence or "").split(" (", 1)[0].strip()


def source_label(scene):
    """'Debian \\texttt{pkg}', 'npm \\texttt{pkg}', 'generator \\texttt{kind, seed S}'."""
    kind = scene.get("kind") or ""
    label = latex.escape(_KIND_LABELS.get(kind, kind)) or latex.DASH
    detail = scene.get("package") or scene.get("generator")
    if isinstance(detail, dict):
        detail = generator_label(detail)
    if detail and kind != "url":
        label += " \\texttt{%s}" % latex.escape(detail)
    return label


def stands_in_for(scene, seed):
    """'2 Armadillo' for a scene standing in for a report scene, else a dash.
    The name comes from the manifest, or from the report's own table."""
    number = scene.get("report_scene")
    if number in (None, ""):
        return latex.DASH
    number = int(number)
    name = scene.get("report_name")
    if not name and seed is not None and number in seed.index:
        name = seed.loc[number, "name"]
    return ("%d %s" % (number, latex.escape(name))) if name else str(number)


def build_rows(manifest, records):
    """Joins manifest scenes with their latest scene_info record.

    Returns a list of dicts, one per scene that has a record (obtained and
    tried), ordered by manifest number; scenes with a record but no manifest
    entry come last (number None)."""
    from analysis.inputs import latest_scene_records

    latest = latest_scene_records(records)
    by_name = {s["name"]: s for s in manifest}
    rows = []
    for name, rec in latest.items():
        scene = by_name.get(name, {"name": name, "number": None})
        expected = scene.get("expected_triangles")
        n_tri = rec.get("n_tri") if rec.get("ok") else None
        rows.append({
            "number": scene.get("number"),
            "name": name,
            "scene": scene,
            "record": rec,
            "ok": bool(rec.get("ok")),
            "n_tri": n_tri,
            "expected": expected,
            "diff": (n_tri - expected) if (n_tri is not None
                                           and expected is not None) else None,
        })
    rows.sort(key=lambda r: (r["number"] is None, r["number"] or 0, r["name"]))
    return rows


def render(rows, seed):
    header = ["\\#", "Scene", "Stands in for", "Triangles",
              "Expected", "Check", "From"]
    body, notes, failures = [], [], 0
    for row in rows:
        scene = row["scene"]
        if row["ok"]:
            loaded = latex.fmt_int(row["n_tri"])
        else:
            failures += 1
            loaded = "failed$^{%d}$" % failures
            err = (row["record"].get("error") or "unknown error").strip()
            err = err.splitlines()[-1] if err else "unknown error"
            if len(err) > 160:
                err = err[:157] + "..."
            notes.append("$^{%d}$ %s failed to load: %s"
                         % (failures, latex.escape(row["name"]),
                            latex.escape(err)))
        if row["diff"] is None:
            check = latex.DASH
        elif row["diff"] == 0:
            check = latex.CHECK
        else:
            check = latex.fmt_signed_int(row["diff"])
        body.append([
            str(row["number"]) if row["number"] is not None else latex.DASH,
            latex.escape(row["name"]),
            stands_in_for(scene, seed),
            loaded,
            latex.fmt_int(row["expected"]),
            check,
            latex.escape(_KIND_LABELS.get(scene.get("kind") or "", scene.get("kind") or "")) or latex.DASH,
        ])
    if not body:
        return _render_empty()
    caption = (
        "The scene library as loaded on this machine. \\# is our scene "
        "number (position in \\texttt{data/manifest.json}, stable across "
        "profiles), used by all later tables. \\emph{Stands in for} names "
        "the report's scene (Table~\\ref{tab:seed1}) a scene replaces. "
        "\\emph{Triangles} is the count as loaded by \\texttt{scene\\_info} "
        "(after dropping degenerate and non-finite triangles); "
        "\\emph{Expected} comes from the manifest; \\emph{Check} is "
        "\\checkmark{} when they agree, else the difference. \\emph{From}: "
        "a Debian or npm package, this project's generators, Blender, or a "
        "download; "
        "Table~\\ref{tab:sources} in the appendix names each package and "
        "licence.")
    return latex.booktabs(header, body, align="rllrrrl",
                          caption=caption, label="tab:scenes",
                          notes=notes or None, size="footnotesize")


def render_sources(rows):
    """The appendix's table of where each scene comes from and its licence
    (Table 1 names only the kind of source)."""
    body = [[str(row["number"]) if row["number"] is not None else latex.DASH,
             latex.escape(row["name"]), source_label(row["scene"]),
             latex.escape(licence_label(row["scene"].get("licence"))) or latex.DASH]
            for row in rows]
    if not body:
        return ""
    caption = ("Where each scene of Table~\\ref{tab:scenes} comes from, and its "
               "licence (up to its first parenthesis; \\texttt{data/manifest.json} "
               "says where the licence is stated).")
    wrap = ">{\\raggedright\\arraybackslash}p{%s}"
    return latex.booktabs(["\\#", "Scene", "Source", "Licence"], body,
                          align="rl" + wrap % "6.2cm" + wrap % "5.2cm",
                          caption=caption, label="tab:sources", size="footnotesize")


def _render_empty():
    return ("\\begin{table}[htbp]\n\\centering\n"
            "\\fbox{No scene was obtained: Table~1 is empty.}\n"
            "\\caption{The scene library as loaded on this machine.}\n"
            "\\label{tab:scenes}\n\\end{table}\n")


def macros(rows, seed):
    ok = [r for r in rows if r["ok"]]
    largest = max(ok, key=lambda r: r["n_tri"]) if ok else None
    covered = {int(r["scene"]["report_scene"]) for r in ok
               if r["scene"].get("report_scene") not in (None, "")}
    profiles = sorted({r["record"].get("profile") for r in rows
                       if r["record"].get("profile")})
    with_expected = [r for r in ok if r["expected"] is not None]
    return {
        "NumScenes": (len(ok), False),
        "NumScenesTried": (len(rows), False),
        "NumScenesFailed": (len(rows) - len(ok), False),
        "NumScenesWithExpected": (len(with_expected), False),
        "NumScenesMatchExpected": (
            sum(1 for r in with_expected if r["diff"] == 0), False),
        "TotalTriangles": (latex.fmt_int(sum(r["n_tri"] for r in ok)), False),
        "LargestScene": (largest["name"] if largest else "none", False),
        "LargestSceneTriangles": (
            latex.fmt_int(largest["n_tri"]) if largest else latex.DASH, True),
        "NumReportScenesCovered": (len(covered), False),
        "NumReportScenes": (len(seed) if seed is not None else 18, False),
        "Profile": (", ".join(profiles) or "unknown", False),
    }


def generate(ctx):
    records = ctx.results(SCENES_FILE)
    if not records:
        raise RuntimeError(
            "no scene results in %s/%s: run experiments/run_scenes.py first"
            % (ctx.results_dir, SCENES_FILE))
    seed = ctx.seed_table1
    rows = build_rows(ctx.manifest, records)
    ctx.write("table1.tex", render(rows, seed))
    ctx.write("table1_sources.tex", render_sources(rows))
    return macros(rows, seed)
