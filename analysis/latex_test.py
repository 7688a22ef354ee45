import os
import tempfile
import unittest

from analysis import latex


class EscapeTest(unittest.TestCase):
    def test_specials(self):
        self.assertEqual(latex.escape("a_b & c% #1"),
                         r"a\_b \& c\% \#1")
        self.assertEqual(latex.escape("$x^2$ {y} ~z"),
                         r"\$x\textasciicircum{}2\$ \{y\} "
                         r"\textasciitilde{}z")
        self.assertEqual(latex.escape("C:\\dir"), r"C:\textbackslash{}dir")

    def test_backslash_not_double_escaped(self):
        # the braces the backslash replacement adds must not be escaped again
        self.assertEqual(latex.escape("\\_"), r"\textbackslash{}\_")

    def test_none_and_numbers(self):
        self.assertEqual(latex.escape(None), "")
        self.assertEqual(latex.escape(42), "42")

    def test_plain_text_unchanged(self):
        self.assertEqual(latex.escape("Stanford bunny (CC0)"),
                         "Stanford bunny (CC0)")


class NumberTest(unittest.TestCase):
    def test_fmt_int(self):
        self.assertEqual(latex.fmt_int(0), "0")
        self.assertEqual(latex.fmt_int(968), "968")
        self.assertEqual(latex.fmt_int(69666), "69,666")
        self.assertEqual(latex.fmt_int(12759246), "12,759,246")
        self.assertEqual(latex.fmt_int(-1234), "-1,234")
        self.assertEqual(latex.fmt_int(3.0), "3")
        self.assertEqual(latex.fmt_int(None), latex.DASH)
        self.assertEqual(latex.fmt_int(float("nan")), latex.DASH)
        with self.assertRaises(ValueError):
            latex.fmt_int(2.5)

    def test_fmt_signed_int(self):
        self.assertEqual(latex.fmt_signed_int(12), "+12")
        self.assertEqual(latex.fmt_signed_int(-1234), "$-$1,234")
        self.assertEqual(latex.fmt_signed_int(0), "0")

    def test_fmt_float(self):
        self.assertEqual(latex.fmt_float(0.04512), "0.0451")
        self.assertEqual(latex.fmt_float(1.5), "1.50")
        self.assertEqual(latex.fmt_float(1234.5), "1,234")
        self.assertEqual(latex.fmt_float(0), "0")
        self.assertEqual(latex.fmt_float(None), latex.DASH)
        self.assertEqual(latex.fmt_float(0.2345, digits=2), "0.23")


class MacroTest(unittest.TestCase):
    def test_newcommand(self):
        self.assertEqual(latex.newcommand("NumScenes", 5),
                         "\\newcommand{\\NumScenes}{5}\n")
        self.assertEqual(latex.newcommand("Cpu", "Intel(R) 50% #1"),
                         "\\newcommand{\\Cpu}{Intel(R) 50\\% \\#1}\n")
        self.assertEqual(latex.newcommand("Mem", "2\\,GiB", raw=True),
                         "\\newcommand{\\Mem}{2\\,GiB}\n")

    def test_bad_names(self):
        for bad in ("Num2", "num_scenes", "", "a b"):
            with self.assertRaises(ValueError):
                latex.newcommand(bad, 1)

    def test_macros_file(self):
        text = latex.macros_file({"A": (1, False), "B": ("x_y", False)},
                                 header="line1\nline2")
        self.assertIn("% line1\n% line2\n", text)
        self.assertIn("\\newcommand{\\A}{1}\n\\newcommand{\\B}{x\\_y}\n",
                      text)


class BooktabsTest(unittest.TestCase):
    def test_structure(self):
        text = latex.booktabs(["a", "b"], [["1", "2"], "midrule", ["3", "4"]],
                              align="lr", caption="Cap", label="tab:x",
                              size="small")
        order = ["\\begin{table}", "\\caption{Cap}", "\\label{tab:x}",
                 "\\small", "\\begin{fittable}{tab:x}", "\\begin{tabular}{lr}",
                 "\\toprule", "a & b \\\\", "\\midrule", "1 & 2 \\\\",
                 "\\midrule", "3 & 4 \\\\", "\\bottomrule", "\\end{tabular}",
                 "\\end{fittable}", "\\end{table}"]
        pos = 0
        for token in order:
            found = text.find(token, pos)
            self.assertGreaterEqual(found, 0, "%r missing after %d in\n%s"
                                    % (token, pos, text))
            pos = found + len(token)

    def test_not_floating_no_fit(self):
        text = latex.booktabs(["a"], [["1"]], align="l", floating=False,
                              fit_width=False)
        self.assertNotIn("\\begin{table}", text)
        self.assertNotIn("fittable", text)
        self.assertTrue(text.startswith("\\begin{tabular}{l}"))

    def test_column_count_checked(self):
        with self.assertRaises(ValueError):
            latex.booktabs(["a", "b"], [["1"]], align="lr")
        with self.assertRaises(ValueError):
            latex.booktabs(["a"], [], align="lr")

    def test_complex_align(self):
        text = latex.booktabs(
            ["a", "b", "c"], [["1", "2", "3"]],
            align="r@{\\,}l>{\\raggedright\\arraybackslash}p{2cm}")
        self.assertIn("1 & 2 & 3 \\\\", text)
        with self.assertRaises(ValueError):
            latex.booktabs(["a"], [["1"]], align="p{2cm")

    def test_groups(self):
        text = latex.booktabs(["#", "x", "y"], [["1", "2", "3"]],
                              align="rrr", groups=[("", 1), ("Both", 2)])
        self.assertIn(" & \\multicolumn{2}{c}{Both} \\\\", text)
        self.assertIn("\\cmidrule(lr){2-3}", text)
        with self.assertRaises(ValueError):
            latex.booktabs(["#", "x", "y"], [], align="rrr",
                           groups=[("", 1), ("Both", 1)])

    def test_notes(self):
        text = latex.booktabs(["a"], [["1"]], align="l",
                              notes=["$^1$ first", "$^2$ second"])
        self.assertIn("$^1$ first\\par\n$^2$ second", text)
        self.assertLess(text.index("\\end{tabular}"),
                        text.index("$^1$ first"))


class WriteTextTest(unittest.TestCase):
    def test_atomic_write(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "sub", "t.tex")
            latex.write_text(path, "hello\n")
            latex.write_text(path, "again\n")
            with open(path, encoding="utf-8") as f:
                self.assertEqual(f.read(), "again\n")
            self.assertEqual(os.listdir(os.path.dirname(path)), ["t.tex"])
            self.assertEqual(os.stat(path).st_mode & 0o777, 0o644)


if __name__ == "__main__":
    unittest.main()
