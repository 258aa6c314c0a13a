"""Every ```python example of docs/python.md runs as written (issue: the
documented examples must work, e.g. the names res[...] takes).

The blocks are read from the page at test time (whatever sections it has)
and run in order in one namespace, as a reader typing them into one Python
session would: a later block uses the names of earlier ones (sc, res, mc).
The working folder is a temporary one holding links to the source tree's
scenarios/ and examples/, so the relative paths of the page resolve and
the files the examples write (runs/...) go nowhere else.

Markers, HTML comments in the page just before a block (invisible on the
rendered page):
  <!-- doc-test: OLD => NEW -->   replace the text OLD by NEW in the next
                                  block (shorten a long run: runs=100 => runs=4);
                                  the test fails if OLD is not in the block
  <!-- doc-test: skip REASON -->  do not run the next block
Environment (ctest): PYTHONPATH at the build's python/ folder,
KESTREL_SOURCE_DIR; MPLBACKEND=Agg for the plotting examples.
"""
import os
import re
import tempfile
import unittest

SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
PAGE = os.path.join(SRC, "docs", "python.md")

_FENCE = re.compile(r"^```(\w*)\s*$")
_MARK = re.compile(r"^<!--\s*doc-test:\s*(.*?)\s*-->\s*$")


def python_blocks(text):
    """[(line, code, [markers])]: the ```python blocks of a Markdown text
    (line: the 1-based line of the opening fence),
    each with the doc-test markers written just before it."""
    blocks, marks, lines = [], [], text.splitlines()
    i = 0
    while i < len(lines):
        m = _FENCE.match(lines[i])
        mk = _MARK.match(lines[i])
        if mk:
            marks.append(mk.group(1))
        elif m:
            lang, start, body = m.group(1), i + 1, []
            i += 1
            while i < len(lines) and not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            if lang == "python":
                blocks.append((start, "\n".join(body) + "\n", marks))
            marks = []
        elif lines[i].strip():
            marks = []  # a marker applies to the block right after it (blank lines between are fine)
        i += 1
    return blocks


def apply_markers(code, marks):
    """The code with the markers' replacements; None if a marker skips it."""
    for mk in marks:
        if mk.startswith("skip"):
            return None
        if "=>" not in mk:
            raise ValueError("doc-test marker '%s': 'OLD => NEW' or 'skip REASON'" % mk)
        old, new = (s.strip() for s in mk.split("=>", 1))
        if old not in code:
            raise ValueError("doc-test marker '%s': '%s' is not in the block" % (mk, old))
        code = code.replace(old, new)
    return code


class ExtractorTest(unittest.TestCase):
    """The extractor on a page written here (what it must find and apply)."""

    def test_blocks_markers_and_other_languages(self):
        page = ("# T\n\n```python\na = 1\n```\n\n```sh\nexit 1\n```\n\n"
                "<!-- doc-test: runs=100 => runs=3 -->\n\n```python\nb = f(runs=100)\n```\n"
                "<!-- doc-test: skip needs hardware -->\ntext between\n```python\nc = 3\n```\n"
                "<!-- doc-test: skip needs hardware -->\n```python\nraise SystemExit\n```\n")
        blocks = python_blocks(page)
        # the 1-based line of each ```python fence (counted in the page above)
        self.assertEqual([b[0] for b in blocks], [3, 13, 18, 22])
        self.assertEqual(apply_markers(blocks[0][1], blocks[0][2]), "a = 1\n")
        self.assertEqual(apply_markers(blocks[1][1], blocks[1][2]), "b = f(runs=3)\n")
        self.assertEqual(blocks[2][2], [])  # text between: the marker does not reach
        self.assertIsNone(apply_markers(blocks[3][1], blocks[3][2]))

    def test_marker_that_does_not_match_fails(self):
        with self.assertRaises(ValueError):
            apply_markers("x = 1\n", ["runs=100 => runs=3"])
        with self.assertRaises(ValueError):
            apply_markers("x = 1\n", ["runs=100"])


class DocsExamplesTest(unittest.TestCase):
    def test_every_python_block_runs(self):
        with open(PAGE, encoding="utf-8") as f:
            blocks = python_blocks(f.read())
        self.assertGreater(len(blocks), 5, "docs/python.md has its examples")
        ns = {"__name__": "__docs__"}
        cwd = os.getcwd()
        with tempfile.TemporaryDirectory() as tmp:
            for d in ("scenarios", "examples"):
                os.symlink(os.path.join(os.path.abspath(SRC), d), os.path.join(tmp, d))
            os.chdir(tmp)
            try:
                for line, code, marks in blocks:
                    code = apply_markers(code, marks)
                    if code is None:
                        continue
                    with self.subTest(block="docs/python.md:%d" % line):
                        # line numbers of a traceback are the page's
                        exec(compile("\n" * line + code, PAGE, "exec"), ns)
            finally:
                os.chdir(cwd)


if __name__ == "__main__":
    unittest.main()
