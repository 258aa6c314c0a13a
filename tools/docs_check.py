#!/usr/bin/env python3
"""Checks that the documentation stands on its own.

  docs_check.py citations --root DIR   no tracked file cites a document that is
                                       not in the repository (the maths lives in
                                       docs/, see docs/dynamics.md "Topic marks")
  docs_check.py links --root DIR       every relative link in README.md and in
                                       every tracked .md file under docs/ names
                                       an existing file, and its #anchor (if any)
                                       names a heading of that file
  docs_check.py index --root DIR       README.md names every top-level folder of
                                       the tracked files (as `name/`) and links
                                       every tracked .md page under docs/
  docs_check.py self-test              shows each check failing on planted faults

Files are the ones `git ls-files` lists when DIR is a git checkout, otherwise
every file under DIR outside build/ and results/.  Exit status 0 = clean,
1 = findings (printed as file:line: message), 2 = usage error.
"""
import os
import re
import subprocess
import sys
import tempfile

# Documents that are not part of the repository.  Written as pieces so that
# this file does not match its own patterns.
_OUTSIDE = [
    r"fsw-algo" r"rithms(\.md)?",
    r"plant-dyn" r"amics(\.md)?",
    r"style[- ]gu" r"ide",
    r"harness-sh" r"ape\.md",
    r"shared/sp" r"ec",
    r"\bsp" r"ec(ification)? ?§",
    r"\bsp" r"ec [0-9]+(\.[0-9]+)?\b",
    r"\bsp" r"ec K[0-9]\b",
]
CITATION = re.compile("|".join("(?:%s)" % p for p in _OUTSIDE), re.IGNORECASE)

SKIP_DIRS = {".git", "build", "results", "node_modules", "__pycache__"}


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True, check=True)
        files = [f for f in out.stdout.decode("utf-8", "replace").split("\0") if f]
        if files:
            return files
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if d not in SKIP_DIRS]
        for name in filenames:
            files.append(os.path.relpath(os.path.join(dirpath, name), root))
    return sorted(files)


def read_text(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except (UnicodeDecodeError, OSError):
        return None  # binary or unreadable: nothing to cite


def check_citations(root, files, me):
    findings = []
    for rel in files:
        full = os.path.join(root, rel)
        if os.path.abspath(full) == me or not os.path.isfile(full):
            continue
        text = read_text(full)
        if text is None:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            m = CITATION.search(line)
            if m:
                findings.append("%s:%d: cites a document outside the repository: '%s'" % (rel, n, m.group(0)))
    return findings


FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
HTML_ID = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
# [text](target) or [text](target "title"); images too.  Not inside `code`.
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REF_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(\s|$)")


def slug(text):
    """GitHub's heading anchor: lower case, punctuation dropped, spaces -> '-'."""
    text = re.sub(r"`|\*\*|__", "", text).lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link keeps its text
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def prose_lines(text):
    """(line number, line) outside fenced code blocks, inline code removed."""
    inside = False
    for n, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield n, re.sub(r"`[^`]*`", "", line), line


def anchors_of(text):
    seen, out = {}, set()
    for _, _, raw in prose_lines(text):
        for a in HTML_ID.findall(raw):
            out.add(a)
        m = HEADING.match(raw)
        if not m:
            continue
        base = slug(m.group(2))
        k = seen.get(base, 0)
        seen[base] = k + 1
        out.add(base if k == 0 else "%s-%d" % (base, k))
    return out


def check_links(root, files):
    pages = [f for f in files if f == "README.md" or (f.startswith("docs/") and f.endswith(".md"))]
    tracked = set(files)
    findings, cache = [], {}
    for rel in pages:
        text = read_text(os.path.join(root, rel))
        if text is None:
            continue
        for n, line, _ in prose_lines(text):
            targets = LINK.findall(line)
            m = REF_DEF.match(line)
            if m:
                targets.append(m.group(1))
            for target in targets:
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.IGNORECASE):
                    continue  # http:, https:, mailto:, file: ...
                path, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(rel), path)) if path else rel
                full = os.path.join(root, dest)
                if dest.startswith(".."):
                    findings.append("%s:%d: link '%s' leaves the repository" % (rel, n, target))
                    continue
                if not os.path.exists(full) or (dest not in tracked and os.path.isfile(full)):
                    findings.append("%s:%d: link '%s': %s does not exist" % (rel, n, target, dest))
                    continue
                if anchor and dest.endswith(".md"):
                    if dest not in cache:
                        cache[dest] = anchors_of(read_text(full) or "")
                    if anchor not in cache[dest]:
                        findings.append("%s:%d: link '%s': no heading '#%s' in %s" % (rel, n, target, anchor, dest))
    return findings


def check_index(root, files):
    text = read_text(os.path.join(root, "README.md")) or ""
    linked = set()
    for _, line, _ in prose_lines(text):
        for target in LINK.findall(line):
            linked.add(os.path.normpath(target.partition("#")[0]))
    findings = []
    for folder in sorted({f.split("/")[0] for f in files if "/" in f}):
        if "`%s/`" % folder not in text:
            findings.append("README.md: the top-level folder %s/ is not in the folder table" % folder)
    for page in sorted(f for f in files if f.startswith("docs/") and f.endswith(".md")):
        if page not in linked:
            findings.append("README.md: the page %s is not in the page index" % page)
    return findings


def self_test():
    ok = True
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "docs", "sub"))
        cite = "// see " + "fsw-algo" "rithms.md 2 for the law\n"
        files = {
            "README.md": "[good](docs/a.md) [anchor](docs/a.md#the-law-k1) [bad](docs/missing.md)\n"
                         "[bad anchor](docs/a.md#nowhere) [web](https://example.org) `[code](x.md)`\n",
            "docs/a.md": "# Page\n## The law (`K1`)\n[up](../README.md) [self](#page) [out](../../x.md)\n"
                         "```\n[fenced](nothing.md)\n```\n",
            "docs/sub/b.md": "[sibling](../a.md#page)\n",
            "src.c": cite,
            "clean.c": "/* docs/fsw/mrp_fb.md */\n",
        }
        for rel, text in files.items():
            with open(os.path.join(d, rel), "w", encoding="utf-8") as f:
                f.write(text)
        listed = sorted(files)
        c = check_citations(d, listed, "")
        links = check_links(d, listed)
        idx = check_index(d, listed + ["tools/x.py"])
        expect_i = ["README.md: the top-level folder docs/", "README.md: the top-level folder tools/",
                    "README.md: the page docs/sub/b.md"]
        expect_c = ["src.c:1:"]
        expect_l = ["README.md:1: link 'docs/missing.md'", "README.md:2: link 'docs/a.md#nowhere'",
                    "docs/a.md:3: link '../../x.md' leaves"]
        for label, got, want in (("citations", c, expect_c), ("links", links, expect_l), ("index", idx, expect_i)):
            if len(got) != len(want) or not all(any(g.startswith(w) for g in got) for w in want):
                print("self-test %s: expected %s, got %s" % (label, want, got))
                ok = False
    if slug("The plant (`sim::Plant`)") != "the-plant-simplant" or slug("Thrusters (§5.1–§5.4)") != "thrusters-5154":
        print("self-test: slug rule wrong")
        ok = False
    print("self-test passed" if ok else "self-test FAILED")
    return 0 if ok else 1


def main(argv):
    if len(argv) >= 1 and argv[0] == "self-test":
        return self_test()
    if len(argv) != 3 or argv[0] not in ("citations", "links", "index") or argv[1] != "--root":
        print(__doc__)
        return 2
    root = os.path.abspath(argv[2])
    files = tracked_files(root)
    if argv[0] == "citations":
        findings = check_citations(root, files, os.path.abspath(__file__))
    elif argv[0] == "links":
        findings = check_links(root, files)
    else:
        findings = check_index(root, files)
    for f in findings:
        print(f)
    print("%s: %d finding(s) in %d files" % (argv[0], len(findings), len(files)))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
