#!/usr/bin/env bash
# Every relative link in README.md and docs/**/*.md names a file that exists,
# and a `#anchor` names a heading of that file (GitHub's anchors: lower case,
# punctuation dropped, spaces as '-', a repeated heading gets -1, -2, ...).
# Links to web pages (http:, https:, mailto:) are not followed.
# Prints one line per broken link (FILE:LINE: link: reason) and exits 1 if
# there is one, else prints how many links it checked and exits 0.
# Usage: bash scripts/check_doc_links.sh [REPO_ROOT]
set -euo pipefail
root="$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/..}" && pwd)"
python3 - "$root" <<'PY'
import os, re, sys

root = sys.argv[1]
files = [os.path.join(root, "README.md")]
for folder, _, names in os.walk(os.path.join(root, "docs")):
    files += [os.path.join(folder, n) for n in sorted(names) if n.endswith(".md")]

def slug(heading):
    text = re.sub(r"`|\*\*|\*", "", heading.strip()).lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = re.sub(r"[^\w\- ]", "", text)                  # \w keeps letters of any script
    return text.replace(" ", "-")

anchors = {}
def anchors_of(path):
    if path not in anchors:
        seen, found, fence = {}, set(), False
        for line in open(path, encoding="utf-8"):
            if line.lstrip().startswith("```"):
                fence = not fence
            m = None if fence else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
            if m:
                s = slug(m.group(1))
                n = seen.get(s, 0)
                seen[s] = n + 1
                found.add(s if n == 0 else f"{s}-{n}")
        anchors[path] = found
    return anchors[path]

link = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
bad, checked = [], 0
for path in files:
    fence = False
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        if fence:
            continue
        for target in link.findall(re.sub(r"`[^`]*`", "", line)):
            if re.match(r"^[a-z]+:", target):
                continue
            checked += 1
            name, _, anchor = target.partition("#")
            where = os.path.normpath(os.path.join(os.path.dirname(path), name)) if name else path
            rel = os.path.relpath(path, root)
            if not os.path.exists(where):
                bad.append(f"{rel}:{number}: {target}: no such file")
            elif anchor and where.endswith(".md") and anchor not in anchors_of(where):
                bad.append(f"{rel}:{number}: {target}: no heading '{anchor}' in {os.path.relpath(where, root)}")
for line in bad:
    print(line)
if bad:
    sys.exit(1)
print(f"check_doc_links: {checked} links in {len(files)} files, all found")
PY
