"""The size each table of the report is set at, against the body font, and
the scale each generated figure is set at (issue 25: no table or figure
below 80 %).

report/main.tex's fittable environment (used by analysis/latex.py for every
table) writes one log line per table:
    FITTABLE <label> font <F> natural <W>pt line <L>pt
F is the table's font size in pt (\\footnotesize is 9 pt in an 11 pt body),
W its natural width, L the line width; a table wider than the line is shrunk
by L / W. A table's effective size is F / body * min(1, L / W).
\generatedfigure writes, for each figure with text in it,
    FITFIGURE <file> natural <N>pt set <S>pt
and a figure's scale is S / N (its fonts are set for its natural size).

    /usr/bin/python3 -m analysis.table_scale report/build/main.log [--body_pt 11]
        [--limit 0.8] [--strict]

prints every table and figure below the limit (all with --all); --strict
exits 1 when there is one. reproduce.sh runs it after the PDF with --strict,
and //analysis:report_pdf_test builds the PDF from the test fixture and
checks it the same way."""

import argparse
import re
import sys

LINE = re.compile(r"^FITTABLE (\S+) font ([0-9.]+) natural ([0-9.]+)pt line ([0-9.]+)pt")
FIGURE = re.compile(r"FITFIGURE (\S+) natural ([0-9.]+)pt set ([0-9.]+)pt")


def parse(log_text):
    """[(label, font_pt, natural_pt, line_pt)] in log order, each label once
    (latexmk runs pdflatex more than once; the last pass wins)."""
    found = {}
    # TeX wraps log lines at 79 characters: join the wrapped pieces first.
    text = log_text.replace("\n", "")
    for m in re.finditer(r"FITTABLE \S+ font [0-9.]+ natural [0-9.]+pt line [0-9.]+pt", text):
        g = LINE.match(m.group(0))
        found[g.group(1)] = (g.group(1), float(g.group(2)), float(g.group(3)), float(g.group(4)))
    return list(found.values())


def parse_figures(log_text):
    """[(file, scale)] in log order, each file once (the last pass wins)."""
    found = {}
    for m in FIGURE.finditer(log_text.replace("\n", "")):
        natural = float(m.group(2))
        found[m.group(1)] = (m.group(1), float(m.group(3)) / natural if natural else 0.0)
    return list(found.values())


def effective(font_pt, natural_pt, line_pt, body_pt):
    """The size a table is set at, as a fraction of the body font."""
    return font_pt / body_pt * min(1.0, line_pt / natural_pt)


def rows(tables, body_pt):
    return sorted(((label, effective(f, w, l, body_pt), f, w / l) for label, f, w, l in tables),
                  key=lambda r: r[1])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("log")
    p.add_argument("--body_pt", type=float, default=11.0)
    p.add_argument("--limit", type=float, default=0.8)
    p.add_argument("--all", action="store_true")
    p.add_argument("--strict", action="store_true")
    args = p.parse_args(argv)
    with open(args.log, errors="replace") as f:
        text = f.read()
    tables = parse(text)
    figures = parse_figures(text)
    small = 0
    for label, eff, font, over in rows(tables, args.body_pt):
        below = eff < args.limit
        small += below
        if below or args.all:
            print("table_scale: %-22s %3.0f %% of the body font (%g pt, %.2fx the line width)%s"
                  % (label, 100 * eff, font, over, "" if below else " ok"))
    print("table_scale: %d of %d tables below %.0f %% of the body font"
          % (small, len(tables), 100 * args.limit))
    shrunk = 0
    for name, scale in sorted(figures, key=lambda f: f[1]):
        below = scale < args.limit
        shrunk += below
        if below or args.all:
            print("table_scale: figure %-22s set at %3.0f %%%s"
                  % (name, 100 * scale, "" if below else " ok"))
    print("table_scale: %d of %d figures below %.0f %% of their size"
          % (shrunk, len(figures), 100 * args.limit))
    return 1 if args.strict and (small or shrunk) else 0


if __name__ == "__main__":
    sys.exit(main())
