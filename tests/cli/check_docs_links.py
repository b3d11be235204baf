#!/usr/bin/env python3
"""Every link of README.md and docs/*.md resolves: a relative link names a file of the repository, and an anchor
(#...) names a heading of the page it points to (GitHub's rule: lower case, punctuation dropped, spaces as dashes)."""
import glob
import os
import re
import sys

SOURCE = sys.argv[1]


def anchors(path):
    """The anchors GitHub makes of a page's headings (outside code blocks), duplicates numbered."""
    found, seen, fence = set(), {}, False
    with open(path) as f:
        for line in f:
            if line.startswith("```"):
                fence = not fence
            m = None if fence else re.match(r"^#{1,6}\s+(.*?)\s*$", line)
            if m:
                slug = re.sub(r"[^\w\- ]", "", m.group(1).lower()).replace(" ", "-")
                n = seen.get(slug, 0)
                seen[slug] = n + 1
                found.add(slug if n == 0 else f"{slug}-{n}")
    return found


def links(path):
    """(line number, target) of every markdown link and image outside code blocks and inline code."""
    fence = False
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if line.startswith("```"):
                fence = not fence
            if not fence:
                for target in re.findall(r"\]\(([^)\s]+)\)", re.sub(r"`[^`]*`", "", line)):
                    yield number, target


pages = [os.path.join(SOURCE, "README.md")] + sorted(glob.glob(os.path.join(SOURCE, "docs", "*.md")))
broken, count = [], 0
for page in pages:
    for number, target in links(page):
        if re.match(r"^[a-z]+:", target):
            continue
        count += 1
        file_part, _, anchor = target.partition("#")
        dest = os.path.normpath(os.path.join(os.path.dirname(page), file_part)) if file_part else page
        where = f"{os.path.relpath(page, SOURCE)}:{number}: {target}"
        if not os.path.exists(dest):
            broken.append(where + " (no such file)")
        elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
            broken.append(where + " (no such heading)")
for line in broken:
    print("FAIL " + line)
print(f"{'FAIL' if broken else 'ok  '} {count} links of {len(pages)} pages, {len(broken)} broken")
sys.exit(1 if broken else 0)
