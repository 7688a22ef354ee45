"""Analysis of the reproduction's raw results: tables, figures and the
macros report/main.tex quotes. Entry point: analysis/make_all.py."""
