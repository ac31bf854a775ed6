#!/usr/bin/env python3
"""Fail when the documentation points outside the repository or at nothing.

Checked files: README.md and docs/*.md of the given source tree.

1. Links. Every relative link -- [text](target), ![alt](target), [ref]: target,
   <a href="target">, <img src="target"> -- must resolve inside the tree:
     * the file or folder exists (resolved from the linking file's folder, and
       not outside the tree root);
     * a #fragment into a Markdown file names a heading of that file, as GitHub
       slugs it (lower case; every character that is not a letter, digit,
       space, '-' or '_' dropped; spaces become '-'; the n-th repeat of a slug
       gets '-n'), or an <a id/name="..."> in it.
   Links with a scheme (https:, mailto:) are not followed. Links inside fenced
   code blocks and `code spans` are not links and are not checked.

2. Machine paths. A document must not state where things lie on some
   particular computer: the repository can be checked out anywhere. Flagged,
   anywhere in the text (code blocks included, since readers copy them):
     * any path under /work/, /home/ or /root/ -- no reader has our folders there;
     * a /tmp/ path with more than one component (/tmp/build/bin/x,
       /tmp/base/run11, /tmp/f-ds/report.html): a tree someone built or ran in
       on their machine.
   Not flagged: a single scratch name directly under /tmp (/tmp/etroll-bus,
   /tmp/features.csv) -- a file or link the reader's own command creates, which
   works on every machine; system paths (/dev/i2c-1, /usr/bin/python3, /sys/...).
   Write `~/...` or a relative path (build/bin/...) instead of a machine path.

usage: check_docs.py [SOURCE_DIR]     exit 0 when clean, 1 with one line per problem (file:line: ...)
"""
import os
import re
import sys
import unicodedata

FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
HTML_LINK = re.compile(r"<(?:a|img)\b[^>]*?\b(?:href|src)\s*=\s*\"([^\"]*)\"", re.IGNORECASE)
HTML_ANCHOR = re.compile(r"<a\b[^>]*?\b(?:id|name)\s*=\s*\"([^\"]+)\"", re.IGNORECASE)
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
SETEXT = re.compile(r"^\s{0,3}(=+|-+)\s*$")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
# An absolute path token that is not the tail of a longer path or URL (so
# "https://x/home/y" and "build/tmp/x" are not taken for one).
PATH_TOKEN = re.compile(r"(?<![\w./~:-])/[\w.@%+~-]+(?:/[\w.@%+~-]*)*")
MACHINE_ROOTS = ("work", "home", "root")


def is_machine_path(path):
    parts = [p for p in path.split("/") if p]
    if len(parts) >= 2 and parts[0] in MACHINE_ROOTS:
        return True
    return len(parts) >= 3 and parts[0] == "tmp"


def doc_files(root):
    files = []
    readme = os.path.join(root, "README.md")
    if os.path.isfile(readme):
        files.append(readme)
    docs = os.path.join(root, "docs")
    if os.path.isdir(docs):
        files += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    return files


def prose_lines(lines, blank_code_spans=True):
    """(line number, text) of the lines outside fenced code, code spans blanked unless asked not to."""
    fenced = None
    for n, line in enumerate(lines, 1):
        m = FENCE.match(line)
        if m:
            if fenced is None:
                fenced = m.group(1)
            elif m.group(1) == fenced:
                fenced = None
            continue
        if fenced is None:
            yield n, CODE_SPAN.sub(lambda s: " " * len(s.group(0)), line) if blank_code_spans else line


def slug(text):
    """GitHub's anchor for a heading text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = re.sub(r"<[^>]+>", "", text).replace("`", "")
    out = []
    for ch in text.strip().lower():
        cat = unicodedata.category(ch)
        if ch in "-_" or ch == " " or cat[0] in ("L", "N") or cat == "Mn":
            out.append("-" if ch == " " else ch)
    return "".join(out)


def anchors_of(path, cache):
    if path in cache:
        return cache[path]
    with open(path, encoding="utf-8") as fh:
        lines = fh.read().split("\n")
    seen = {}
    anchors = set()
    previous = ""
    for _, line in prose_lines(lines, blank_code_spans=False):
        m = HEADING.match(line)
        text = m.group(2) if m else None
        if text is None and SETEXT.match(line) and previous.strip() and not previous.lstrip().startswith(("|", "-", "*")):
            text = previous.strip()
        if text is not None:
            base = slug(text)
            count = seen.get(base, 0)
            anchors.add(base if count == 0 else f"{base}-{count}")
            seen[base] = count + 1
        anchors.update(HTML_ANCHOR.findall(line))
        previous = line
    cache[path] = anchors
    return anchors


def check_link(root, doc, lineno, target, cache, problems):
    if not target or SCHEME.match(target) or target.startswith("//"):
        return
    rel_doc = os.path.relpath(doc, root)
    path_part, _, fragment = target.partition("#")
    path_part = path_part.split("?", 1)[0]
    if path_part.startswith("/"):
        problems.append(f"{rel_doc}:{lineno}: link '{target}' is an absolute path; "
                        "link relative to this file so it works in any checkout")
        return
    dest = os.path.normpath(os.path.join(os.path.dirname(doc), path_part)) if path_part else doc
    if os.path.relpath(dest, root).startswith(".."):
        problems.append(f"{rel_doc}:{lineno}: link '{target}' leaves the repository; "
                        "bring the page into docs/ or link a public URL")
        return
    if not os.path.exists(dest):
        problems.append(f"{rel_doc}:{lineno}: link '{target}' names {os.path.relpath(dest, root)}, "
                        "which does not exist; fix the path or add the file")
        return
    if fragment and dest.endswith(".md") and os.path.isfile(dest):
        anchors = anchors_of(dest, cache)
        if fragment not in anchors:
            close = sorted(a for a in anchors if fragment.split("-")[0] in a)[:5]
            hint = f" (headings there: {', '.join(close)})" if close else ""
            problems.append(f"{rel_doc}:{lineno}: link '{target}': {os.path.relpath(dest, root)} has no heading "
                            f"with anchor '#{fragment}'{hint}; fix the anchor or the heading")


def check_file(root, doc, cache, problems):
    with open(doc, encoding="utf-8") as fh:
        lines = fh.read().split("\n")
    rel_doc = os.path.relpath(doc, root)
    for n, line in enumerate(lines, 1):
        for m in PATH_TOKEN.finditer(line):
            path = m.group(0).rstrip(".")  # a sentence's full stop is not part of the path
            if is_machine_path(path):
                problems.append(f"{rel_doc}:{n}: '{path}' is a path on one particular machine; "
                                "use a path relative to the repository or the build folder, or a single "
                                "scratch name under /tmp (see tools/check_docs.py)")
    for n, line in prose_lines(lines):
        targets = INLINE_LINK.findall(line) + HTML_LINK.findall(line)
        m = REFERENCE_DEF.match(line)
        if m:
            targets.append(m.group(1))
        for t in targets:
            check_link(root, doc, n, t, cache, problems)


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    docs = doc_files(root)
    if not docs:
        print(f"check_docs: no README.md or docs/*.md under {root}; pass the source tree as the argument")
        return 1
    problems = []
    cache = {}
    for doc in docs:
        check_file(root, doc, cache, problems)
    for p in problems:
        print(p)
    print(f"check_docs: {len(docs)} files, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
