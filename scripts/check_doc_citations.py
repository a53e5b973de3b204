#!/usr/bin/env python3
"""Check that every design-doc citation in the repository resolves to docs/.

A citation is `<name>.md`, optionally followed by sections: `mapping.md §7`, `docs/mapping.md §5`,
`volmap-reference.md §7/§9`, `datastructure.md §2-§5`, `predicates.md §2 L4`, `mapping.md §5.1`.
Also recognised:
  * a doc stem without `.md` before a section: `mapping §5`, `volmap-reference §3`, and `reference §9`
    (= volmap-reference);
  * a bare `§N` with no doc in front (`(§3)`, `pre-step of §7`): it refers to the doc cited last
    before it in the same file (inside docs/<name>.md: to that doc itself, whose `## §N` headings
    define the sections); a bare `§N` after the name of an outside work (`paper §5`,
    `Verdict §6.11`, `Shewchuk 1997 §2`) is not ours and is skipped;
  * `quirk N` / `quirks 11 and 12`: rows of the quirk table of volmap-reference.md.
In Markdown files, inline code spans that name no doc (`§7`) are examples and skipped.
A section `§N` must exist as a heading `## §N Title` (any level, `### §N.M` for subsections) in
docs/<name>.md; a layer token after it (`§2 L4`) must appear in that section's text.

Not citations (skipped): URLs, paths under a data folder (`shared/data/README.md`), `.md` files named
with a folder other than docs (`workflow/README.md`, `$O/table.md`) and the bare file names that tools
write or that every folder has (README.md, table.md, index.md, ...) when no section follows them.

Failures (exit 1, one `file:line: citation: reason` per line): a cited doc missing from docs/, a
cited section or layer missing from its doc, a cited quirk missing from the table.
Warnings (exit 0 unless --strict): a bare `§N` in a file that cites no doc before it (unresolvable),
and a citation whose path points outside the repository (`../shared/docs/x.md`): it resolves by
name, but a fresh clone has no such path.

Usage: scripts/check_doc_citations.py [--root DIR] [--strict] [--list] [--self-test] [paths...]
Without paths it scans every text file git tracks (outside git: the source folders, docs/ and the
README), docs/ included, so cross-references between the docs are checked too. Prints the number of
citations checked.
"""

import argparse
import os
import re
import subprocess
import sys

SOURCE_FOLDERS = ["lib", "predicates", "tools", "tests", "bench", "scripts", "fuzz", "workflow", "viewer/src",
                  "cmake", "docs"]
TEXT_SUFFIXES = (".cpp", ".hpp", ".h", ".cc", ".cxx", ".c", ".ipp", ".inl", ".js", ".mjs", ".cjs", ".ts",
                 ".py", ".sh", ".cmake", ".txt", ".md", ".yml", ".yaml", ".in", ".toml", ".cfg")
TEXT_NAMES = ("CMakeLists.txt", "Snakefile", "Makefile", "Dockerfile")
SKIP_PARTS = ("node_modules", "dist", ".git")
SKIP_NAMES = ("package-lock.json",)

# Bare .md names that are files of their own folder or outputs of tools, not design docs.
NON_DOC_NAMES = {"readme", "table", "index", "changelog", "license", "contributing", "developers", "report",
                 "results", "summary", "todo"}
STEM_ALIASES = {"reference": "volmap-reference"}
# Words that name an outside work right before a bare section sign.
OUTSIDE_WORK = re.compile(r"(paper|verdict|sand\d|shewchuk|ericson|collision|detection|\bgeom\b|\b(?:19|20)\d\d\b)",
                          re.IGNORECASE)

SECTION_NUMBER = r"\d+(?:\.\d+)*"
MD_TOKEN = re.compile(r"[\w./@$<>{}~+-]*?([\w+-]+)\.md\b")
SECTION_SIGN = re.compile(r"§\s?(" + SECTION_NUMBER + r")")
QUIRK = re.compile(r"\bquirks?\s+(\d+)((?:\s*(?:,|and|&|/)\s*\d+)*)", re.IGNORECASE)
HEADING = re.compile(r"^#{1,6}\s+§(" + SECTION_NUMBER + r")\b")


class Doc:
    """One docs/<name>.md: its section numbers, the text under each, and its quirk-table rows."""

    def __init__(self, path):
        self.path = path
        self.sections = {}
        self.titles = {}
        current = []
        with open(path, encoding="utf-8") as f:
            for line in f:
                m = HEADING.match(line)
                if m:
                    number = m.group(1)
                    self.sections[number] = []
                    self.titles[number] = line
                    # A subsection's text also belongs to its parents.
                    parts = number.split(".")
                    current = [".".join(parts[:k]) for k in range(1, len(parts) + 1)]
                    current = [c for c in current if c in self.sections]
                for c in current:
                    self.sections[c].append(line)
        self.text = {k: "".join(v) for k, v in self.sections.items()}
        self.quirks = set()
        for number, title in self.titles.items():
            if "quirk" in title.lower():
                self.quirks.update(re.findall(r"^\|\s*(\d+)\s*\|", self.text[number], re.MULTILINE))


class Citation:
    def __init__(self, file, line, text, doc, sections=(), layer=None, kind="doc", outside=False):
        self.file, self.line, self.text = file, line, text
        self.doc, self.sections, self.layer, self.kind, self.outside = doc, list(sections), layer, kind, outside

    def where(self):
        return "%s:%d" % (self.file, self.line)


def parse_section_chain(line, pos):
    """Sections right after pos: `§7`, `§7/§9`, `§2-§5`, `§2, §3 and §4`, `§2 L4`. Returns
    (sections, layer, end)."""
    sections, layer = [], None
    chain = re.compile(r"[`*'\"]*\s*(?:(?:,|/|&|and|or)\s*)?§\s?(" + SECTION_NUMBER + r")")
    rng = re.compile(r"(?:\s*[-–]\s*§\s?|[-–])(" + SECTION_NUMBER + r")")
    lay = re.compile(r"\s+(L\d)\b")
    while True:
        m = chain.match(line, pos)
        if not m or (sections == [] and not re.match(r"[`*'\"]*\s*§", line[pos:])):
            break
        first = m.group(1)
        pos = m.end()
        r = rng.match(line, pos)
        if r and "." not in first and "." not in r.group(1) and int(r.group(1)) > int(first):
            sections.extend(str(k) for k in range(int(first), int(r.group(1)) + 1))
            pos = r.end()
        else:
            sections.append(first)
        lm = lay.match(line, pos)
        if lm:
            layer = lm.group(1)
            pos = lm.end()
    return sections, layer, pos


def is_url_context(line, start):
    before = line[max(0, start - 200):start + 2]
    return re.search(r"[A-Za-z][\w+.-]*:/{2}\S*$", before) is not None


def points_outside(root, path, folder):
    """True when the docs folder a citation names is not this repository's docs/."""
    if folder == "docs":
        return False
    target = os.path.normpath(os.path.join(root, os.path.dirname(path), folder))
    return target != os.path.normpath(os.path.join(root, "docs"))


def scan_line(path, lineno, line, doc_stems, state, out, root="."):
    """Appends the citations of one line to out, in line order; state["last"] is the doc cited last
    in this file (what a bare section sign refers to), state["self"] the doc being scanned when the
    file is one of docs/ (its bare section signs refer to itself; its headings define sections)."""
    if state.get("self") and HEADING.match(line):
        return
    taken = set()  # positions of section signs already attributed
    events = []    # (start, end, citation)

    def take(begin, end):
        for s in re.finditer("§", line[begin:end]):
            taken.add(begin + s.start())

    for m in MD_TOKEN.finditer(line):
        name = m.group(1)
        folder = m.group(0)[: -len(name + ".md")].rstrip("/").replace("\\", "/")
        has_section = re.match(r"[`*'\"]*\s*§", line[m.end():]) is not None
        in_docs = folder == "docs" or folder.endswith("/docs")
        sections, layer, end = parse_section_chain(line, m.end())
        take(m.end(), end)  # sections after a skipped name belong to it, not to the last doc
        if is_url_context(line, m.start()):
            continue
        if folder and not in_docs:
            continue  # a file of another folder: workflow/README.md, $O/table.md, ../shared/data/README.md
        if not folder and not has_section and name.lower() in NON_DOC_NAMES:
            continue  # README.md, table.md, ... used as file names
        outside = in_docs and points_outside(root, path, folder)
        events.append((m.start(), end, Citation(path, lineno, line[m.start():end].strip(), name, sections, layer,
                                                outside=outside)))

    stems = sorted(set(doc_stems) | set(STEM_ALIASES), key=len, reverse=True)
    if stems:
        stem_re = re.compile(r"(?<![\w./-])(" + "|".join(re.escape(s) for s in stems) + r")(?=\s+§)")
        for m in stem_re.finditer(line):
            sections, layer, end = parse_section_chain(line, m.end())
            if not sections:
                continue
            take(m.end(), end)
            doc = STEM_ALIASES.get(m.group(1), m.group(1))
            events.append((m.start(), end, Citation(path, lineno, line[m.start():end].strip(), doc, sections, layer,
                                                    kind="stem")))

    for m in SECTION_SIGN.finditer(line):
        if m.start() in taken:
            continue
        # The words since the previous citation or section sign: an outside work's name there
        # (`paper §5`, `Verdict §6.11`) means the section is not one of ours.
        since = max([0] + [e[1] for e in events if e[1] <= m.start()] + [t + 1 for t in taken if t < m.start()])
        window = line[max(since, m.start() - 40):m.start()]
        if OUTSIDE_WORK.search(window):
            continue
        sections, layer, end = parse_section_chain(line, m.start())
        take(m.start(), end)
        events.append((m.start(), end, Citation(path, lineno, line[m.start():end].strip(), None, sections, layer,
                                                kind="bare")))

    for m in QUIRK.finditer(line):
        numbers = [m.group(1)] + re.findall(r"\d+", m.group(2))
        events.append((m.start(), m.end(), Citation(path, lineno, m.group(0), "volmap-reference", numbers,
                                                    kind="quirk")))

    for _, _, c in sorted(events, key=lambda e: e[0]):
        if c.kind == "bare":
            c.doc = state.get("self") or state.get("last")
        elif c.kind in ("doc", "stem"):
            state["last"] = c.doc
        out.append(c)


def mask_example_spans(line):
    """Markdown: blanks inline code spans that name no doc (`§7`, `## §N Title`): they show text,
    they do not cite."""
    return re.sub(r"`[^`]*`", lambda m: m.group(0) if ".md" in m.group(0) else " " * len(m.group(0)), line)


def load_docs(root):
    docs = {}
    folder = os.path.join(root, "docs")
    if os.path.isdir(folder):
        for name in sorted(os.listdir(folder)):
            if name.endswith(".md"):
                docs[name[:-3]] = Doc(os.path.join(folder, name))
    return docs


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True).stdout
        files = [f for f in out.decode("utf-8", "replace").split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = ["README.md"]
        for folder in SOURCE_FOLDERS:
            for base, dirs, names in os.walk(os.path.join(root, folder)):
                dirs[:] = [d for d in dirs if d not in SKIP_PARTS]
                files += [os.path.relpath(os.path.join(base, n), root) for n in names]
    return files


def wanted(rel):
    parts = rel.replace("\\", "/").split("/")
    if any(p in SKIP_PARTS for p in parts) or parts[-1] in SKIP_NAMES:
        return False
    return parts[-1] in TEXT_NAMES or parts[-1].endswith(TEXT_SUFFIXES)


def check(citations, docs):
    failures, warnings = [], []
    for c in citations:
        if c.kind == "bare" and c.doc is None:
            warnings.append("%s: %s: no doc cited before it in this file (name the doc, e.g. mapping.md %s)"
                            % (c.where(), c.text, c.text))
            continue
        doc = docs.get(c.doc)
        if doc is None:
            failures.append("%s: %s: docs/%s.md does not exist" % (c.where(), c.text, c.doc))
            continue
        if c.kind == "quirk":
            for n in c.sections:
                if n not in doc.quirks:
                    failures.append("%s: %s: no quirk %s in the quirk table of docs/%s.md" % (c.where(), c.text, n, c.doc))
            continue
        for s in c.sections:
            if s not in doc.sections:
                failures.append("%s: %s: docs/%s.md has no section §%s" % (c.where(), c.text, c.doc, s))
            elif c.layer and not re.search(r"\b" + re.escape(c.layer) + r"\b", doc.text[s]):
                failures.append("%s: %s: docs/%s.md §%s does not mention %s" % (c.where(), c.text, c.doc, s, c.layer))
        if c.outside:
            warnings.append("%s: %s: path outside the repository; cite docs/%s.md" % (c.where(), c.text, c.doc))
    return failures, warnings


def scan(root, paths, docs):
    citations, files = [], 0
    myself = os.path.realpath(__file__)
    for rel in paths:
        full = os.path.join(root, rel)
        if not os.path.isfile(full) or not wanted(rel) or os.path.realpath(full) == myself:
            continue  # this script's own examples are not citations
        try:
            with open(full, encoding="utf-8") as f:
                lines = f.readlines()
        except UnicodeDecodeError:
            continue
        files += 1
        parts = rel.replace("\\", "/").split("/")
        state = {"self": parts[1][:-3]} if len(parts) == 2 and parts[0] == "docs" and parts[1].endswith(".md") else {}
        for i, line in enumerate(lines, 1):
            if "md" in line or "§" in line or "quirk" in line.lower():
                text = mask_example_spans(line) if rel.endswith(".md") else line
                scan_line(rel, i, text.rstrip("\n"), docs.keys(), state, citations, root)
    return citations, files


def self_test():
    """The parser on the citation styles found in the code (no files needed)."""
    stems = ["mapping", "volmap-reference", "predicates", "datastructure", "conventions"]

    def parse(lines, self_doc=None):
        out, state = [], ({"self": self_doc} if self_doc else {})
        for i, line in enumerate(lines, 1):
            scan_line("x.cpp", i, line, stems, state, out)
        return [(c.kind, c.doc, c.sections, c.layer, c.outside) for c in out]

    cases = [
        (["// a (docs/mapping.md §7, kept)"], [("doc", "mapping", ["7"], None, False)]),
        (["// x (volmap-reference.md §7/§9: y"], [("doc", "volmap-reference", ["7", "9"], None, False)]),
        (["// mesh (datastructure.md §2-§5)."], [("doc", "datastructure", ["2", "3", "4", "5"], None, False)]),
        (["// see predicates.md §2 L4."], [("doc", "predicates", ["2"], "L4", False)]),
        (["// (see ../shared/docs/predicates.md §5)."], [("doc", "predicates", ["5"], None, True)]),
        (["// (docs/mapping.md §5."], [("doc", "mapping", ["5"], None, False)]),
        (["// top (docs/mapping.md).", "// stage (§3) then (§4, when)", "// pre-step of §7's text"],
         [("doc", "mapping", [], None, False), ("bare", "mapping", ["3"], None, False),
          ("bare", "mapping", ["4"], None, False), ("bare", "mapping", ["7"], None, False)]),
        (["// (volmap-reference.md §4, VOLMAP paper §5 and Fig. 4)"], [("doc", "volmap-reference", ["4"], None, False)]),
        (["// Verdict report SAND2007-1751 §6.11 radius", "// Shewchuk 1997 §2", "// Geom. 18 (1997), §2 (Two",
          "// (Ericson, Real-Time Collision Detection §5.1.5)."], []),
        (["// (reference §9), a fingerprint"], [("stem", "volmap-reference", ["9"], None, False)]),
        (["// mapping §5 and volmap-reference §3"],
         [("stem", "mapping", ["5"], None, False), ("stem", "volmap-reference", ["3"], None, False)]),
        (["// with quirks 11 and 12 fixed"], [("quirk", "volmap-reference", ["11", "12"], None, False)]),
        (["-o table.md", "see workflow/README.md", "$O/table.md", "@OUT/r.md", "../shared/data/README.md",
          "https://example.org/docs/mapping.md §3", "index.md"], []),
        (["// §3 feasibility."], [("bare", None, ["3"], None, False)]),
    ]
    cases_in_docs = [
        (["## §7 B1: star-patch cone repair", "see §5 and `conventions.md` §1 and §2; TODO.md"],
         [("bare", "mapping", ["5"], None, False), ("doc", "conventions", ["1", "2"], None, False)]),
    ]
    bad = 0
    runs = [(lines, expected, None) for lines, expected in cases] + \
           [(lines, expected, "mapping") for lines, expected in cases_in_docs]
    for lines, expected, self_doc in runs:
        got = parse(lines, self_doc)
        if got != expected:
            bad += 1
            print("self-test FAILED on %r:\n  got      %r\n  expected %r" % (lines, got, expected))
    print("self-test: %d/%d cases passed" % (len(runs) - bad, len(runs)))
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="*", help="files to scan (default: every tracked text file)")
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--strict", action="store_true", help="warnings fail too")
    ap.add_argument("--list", action="store_true", help="print every citation found")
    ap.add_argument("--self-test", action="store_true", help="test the parser on built-in lines")
    args = ap.parse_args()
    if args.self_test:
        return self_test()
    root = os.path.abspath(args.root)
    docs = load_docs(root)
    if not docs:
        print("check_doc_citations: no docs/*.md under %s" % root)
        return 1
    paths = [os.path.relpath(os.path.abspath(p), root) for p in args.paths] if args.paths else tracked_files(root)
    citations, files = scan(root, paths, docs)
    failures, warnings = check(citations, docs)
    if args.list:
        for c in citations:
            print("%s: [%s] %s -> %s %s" % (c.where(), c.kind, c.text, c.doc,
                                            " ".join("§" + s for s in c.sections)))
    for w in warnings:
        print("warning: " + w)
    for f in failures:
        print(f)
    sections = sum(max(1, len(c.sections)) for c in citations)
    print("check_doc_citations: %d citations (%d section references) in %d files checked against %d docs: "
          "%d failures, %d warnings" % (len(citations), sections, files, len(docs), len(failures), len(warnings)))
    return 1 if failures or (args.strict and warnings) else 0


if __name__ == "__main__":
    sys.exit(main())
