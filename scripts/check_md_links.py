#!/usr/bin/env python3
"""Checks the relative links of markdown files: each [text](path#anchor) must name an existing file
(or folder) and, for a .md target with an anchor, a heading of that file, by GitHub's anchor rules.
Links in code (fenced blocks, inline spans) and to other sites are not links. Prints each broken
link as FILE:LINE: LINK: PROBLEM and exits 1 if there is one.
  scripts/check_md_links.py [FILE.md ...]   (default: the repository's README.md and docs/*.md)
"""
import glob
import os
import re
import sys

FENCE = re.compile(r"^```.*?^```[^\n]*$", re.MULTILINE | re.DOTALL)
INLINE_CODE = re.compile(r"`[^`\n]*(?:\n[^`\n]+)*`")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$", re.MULTILINE)
EXTERNAL = re.compile(r"^[a-z][a-z0-9+.-]*:", re.IGNORECASE)  # http:, https:, mailto:


def blank_out(pattern, text):
    """The text with pattern's matches replaced by blanks, newlines kept so line numbers hold."""
    return pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def prose(text):
    return blank_out(INLINE_CODE, blank_out(FENCE, text))


def slug(heading):
    """GitHub's anchor of a heading: its text without markup, lowercase, punctuation but - and _
    dropped, blanks to -."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading).replace("`", "")
    text = re.sub(r"[^\w\- ]", "", text.lower())
    return text.replace(" ", "-")


def anchors(path):
    with open(path, encoding="utf-8") as f:
        text = blank_out(FENCE, f.read())
    seen, result = {}, set()
    for heading in HEADING.findall(text):
        base = slug(heading)
        n = seen.get(base, 0)
        seen[base] = n + 1
        result.add(base if n == 0 else f"{base}-{n}")
    return result


def problems(path):
    with open(path, encoding="utf-8") as f:
        text = prose(f.read())
    for match in LINK.finditer(text):
        link = match.group(1)
        if EXTERNAL.match(link):
            continue
        target, _, anchor = link.partition("#")
        target_path = os.path.normpath(os.path.join(os.path.dirname(path), target)) if target else path
        line = text.count("\n", 0, match.start()) + 1
        if not os.path.exists(target_path):
            yield line, link, f"no file {target_path}"
        elif anchor and target_path.endswith(".md") and anchor not in anchors(target_path):
            yield line, link, f"{target_path} has no heading with anchor #{anchor}"


def main():
    repo = os.path.relpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    files = sys.argv[1:] or [os.path.join(repo, "README.md")] + sorted(
        glob.glob(os.path.join(repo, "docs", "*.md")))
    broken = 0
    for path in files:
        for line, link, problem in problems(path):
            print(f"{path}:{line}: {link}: {problem}")
            broken += 1
    if broken:
        print(f"check_md_links: {broken} broken links", file=sys.stderr)
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
