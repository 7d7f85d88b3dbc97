#!/usr/bin/python3
"""Checks that README.md, docs/*.md and docs/*/*.md (the user guide, docs/guide/) refer only to
files that are in the repository.

Checked: every relative Markdown link and image ([text](target), anchors stripped); every
path-like token in code (inline `…` and fenced blocks): a token with a '/' made of path
characters only, resolved against the document's folder or the repository root; and every bare
file name with a source extension (.md, .py, .sh, .toml, .cpp, .hpp) in code or prose, which
must exist somewhere in the repository. Paths under the folders .gitignore lists (build/, out/,
…: what the programs write) and absolute paths (/usr/bin/python3) are not repository files and
are skipped, as are placeholders (<scene>, {b}). Exit 1 and one line per missing target.

    tools/check_doc_links.py [REPO_ROOT]      (CTest: docs_links)
"""
import os
import re
import sys
from pathlib import Path

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
INLINE_CODE = re.compile(r"`([^`\n]+)`")
PATH_TOKEN = re.compile(r"^(?:\.{1,2}/)*[A-Za-z0-9_.+-]+(?:/[A-Za-z0-9_.+-]+)*/?$")
BARE_FILE = re.compile(r"(?<![\w/.-])([A-Za-z0-9_+-][A-Za-z0-9_.+-]*\.(?:md|py|sh|toml|cpp|hpp))(?![\w/])")
SKIPPED_DIRS = {".git", "__pycache__"}


def ignored_folders(root: Path):
    """Folders .gitignore lists ('build/', 'out/', 'bench/results/', …): generated, never in the repository."""
    gitignore = root / ".gitignore"
    lines = gitignore.read_text().splitlines() if gitignore.is_file() else []
    return {line.strip().strip("/") for line in lines if line.strip().endswith("/")} | SKIPPED_DIRS


def repository_names(root: Path, ignored):
    names = set()
    for folder, subfolders, files in os.walk(root):
        subfolders[:] = [s for s in subfolders if s not in ignored]
        names.update(files)
    return names


def inside(root: Path, path: Path):
    """The path exists and lies in the repository (../shared/x.md may exist beside it)."""
    resolved = path.resolve()
    return resolved.exists() and resolved.is_relative_to(root)


def split_code(text):
    """(prose, code): fenced blocks and inline spans go to code, the rest to prose."""
    prose, code, fenced = [], [], False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            code.append(line)
        else:
            code.extend(INLINE_CODE.findall(line))
            prose.append(INLINE_CODE.sub(" ", line))
    return "\n".join(prose), "\n".join(code)


def problems(document: Path, root: Path, ignored, names):
    text = document.read_text(encoding="utf-8")
    prose, code = split_code(text)
    top_level = {entry.name for entry in root.iterdir()}
    found = []
    for target in LINK.findall(prose):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            continue  # a URL or an anchor in this document
        path = target.split("#", 1)[0]
        if path and not inside(root, document.parent / path):
            found.append(f"link ({target})")
    for token in code.split():
        token = token.strip("()[],;:'\"")
        if "/" not in token or token.startswith("/") or not PATH_TOKEN.match(token):
            continue
        parts = [part for part in token.split("/") if part not in ("", ".")]
        if not parts or any("/".join(parts[:k]) in ignored for k in range(1, len(parts) + 1)):
            continue
        names_a_file = "." in parts[-1].strip(".")
        if not (parts[0] == ".." or parts[0] in top_level or names_a_file):
            continue  # a unit or a ratio (m/s2, 7/7), not a path
        if not (inside(root, document.parent / token) or inside(root, root / token)):
            found.append(f"path `{token}`")
    for name in BARE_FILE.findall(prose + "\n" + code):
        if name not in names:
            found.append(f"file name {name}")
    return found


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent).resolve()
    ignored = ignored_folders(root)
    names = repository_names(root, ignored)
    documents = [root / "README.md"] + sorted((root / "docs").glob("*.md")) + sorted((root / "docs").glob("*/*.md"))
    failures = 0
    for document in documents:
        for problem in problems(document, root, ignored, names):
            print(f"{document.relative_to(root)}: {problem} is not in the repository")
            failures += 1
    print(f"checked {len(documents)} documents: {failures} missing targets")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
