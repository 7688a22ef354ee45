"""The report's scene 18 (Blender's Suzanne), ours next to the report's.

Inputs: results/row18.jsonl (written by //cc/seed:row18_tool: one record per
report column and mode, "seed" = seed-compatible, "default") and
data/seed/row18.csv (the report's row 18, transcribed once; also read by
//cc/seed:row18_test).
Output: row18.tex and macros on how many columns match.
"""

import csv
import os

from analysis import latex

ROW18_FILE = "row18.jsonl"
SEED_CSV = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))), "data", "seed", "row18.csv")
FIELDS = ["N_I", "N_L", "N_TP", "N_AP", "R_E", "D_max", "D_avg", "N_CL",
          "N_PR"]
HEADERS = ["$N_I$", "$N_L$", "$N_{TP}$", "$N_{AP}$", "$R_E$", "$D_{max}$",
           "$D_{avg}$", "$N_{CL}$", "$N_{PR}$"]


MACROS = ["RowEighteenExactColumns", "RowEighteenColumns", "RowEighteenClipNCL",
          "RowEighteenClipPruneNCL", "RowEighteenClipPruneNPR",
          "RowEighteenPruneNPR", "RowEighteenPruneDefaultNPR"]


def read_seed_rows(path=SEED_CSV):
    with open(path, encoding="utf-8") as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    return list(csv.DictReader(lines))


def matches(ours, printed):
    """True when `ours` rounds to the report's printed value (half a unit of
    its last digit)."""
    if printed in (None, ""):
        return None
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return abs(float(ours) - float(printed)) <= 0.5 * 10 ** -decimals + 1e-12


def fmt(field, value):
    if field in ("N_AP", "R_E", "D_avg"):
        return latex.fmt_float(value, 3)
    return latex.fmt_int(int(value))


def build(seed_rows, records):
    """[(column, report_cells, seed_cells, default_cells, n_match, n_known)]."""
    by_key = {(r["column"], r["mode"]): r for r in records}
    out = []
    for row in seed_rows:
        seed_rec = by_key.get((row["column"], "seed"))
        default_rec = by_key.get((row["column"], "default"))
        report_cells = [row[f] if row[f] else latex.DASH for f in FIELDS]
        n_match = n_known = 0
        seed_cells, default_cells = [], []
        for f in FIELDS:
            if seed_rec is None:
                seed_cells.append(latex.DASH)
            else:
                v = seed_rec["stats"][f]
                m = matches(v, row[f])
                cell = fmt(f, v)
                if m is not None:
                    n_known += 1
                    n_match += int(m)
                    cell = ("\\textbf{%s}" % cell) if m else cell
                seed_cells.append(cell)
            default_cells.append(latex.DASH if default_rec is None
                                 else fmt(f, default_rec["stats"][f]))
        out.append((row, report_cells, seed_cells, default_cells, n_match,
                    n_known))
    return out


def render(rows):
    header = ["Column", "Source"] + HEADERS + ["Match"]
    body = []
    for i, (row, rep, seed, default, n_match, n_known) in enumerate(rows):
        if i:
            body.append("midrule")
        body.append([latex.escape(row["column"]), "report"] + rep + [""])
        body.append(["", "ours, seed mode"] + seed +
                    ["%d/%d" % (n_match, n_known)])
        body.append(["", "ours, default"] + default + [""])
    caption = (
        "Scene 18 (Blender's Suzanne, 968 triangles): the report's row of "
        "Tables 5--10 against ours. Bold: our seed-compatible value equals "
        "the report's as printed. The seed-compatible ``Pruning'' column is "
        "built on Binning 32 (all axes), as the report's numbers show it "
        "was; the report's Table~7 stops before row 18, so the clipping "
        "columns have no $N_I$ to compare.")
    return latex.booktabs(header, body, align="ll" + "r" * 9 + "r",
                          caption=caption, label="tab:row18",
                          size="footnotesize")


def generate(ctx):
    records = ctx.results(ROW18_FILE)
    if not records:
        ctx.write("row18.tex", "\\emph{Scene 18 was not run: no "
                  "results/row18.jsonl (Blender missing?).}\n")
        return {name: (latex.DASH, True) for name in MACROS}
    rows = build(read_seed_rows(), records)
    ctx.write("row18.tex", render(rows))
    exact = [r for r in rows if r[5] and r[4] == r[5]]
    macros = {
        "RowEighteenExactColumns": (str(len(exact)), False),
        "RowEighteenColumns": (str(len(rows)), False),
    }
    stats = {(r["column"], r["mode"]): r["stats"] for r in records}
    wanted = {  # keep in sync with MACROS
        "RowEighteenClipNCL": ("Clipping", "seed", "N_CL"),
        "RowEighteenClipPruneNCL": ("Clipping pruning", "seed", "N_CL"),
        "RowEighteenClipPruneNPR": ("Clipping pruning", "seed", "N_PR"),
        "RowEighteenPruneNPR": ("Pruning", "seed", "N_PR"),
        "RowEighteenPruneDefaultNPR": ("Pruning", "default", "N_PR"),
    }
    for name, (column, mode, field) in wanted.items():
        if (column, mode) in stats:
            macros[name] = (latex.fmt_int(stats[(column, mode)][field]), False)
        else:
            macros[name] = (latex.DASH, True)
    return macros
