#!/usr/bin/env python3
"""Every repository path that a comment or a doc names exists (docs/design.md, README.md, the
docs/ pages, results/*.md, and the comments of every source, shader, script and CMake file).

A path is a token like `analytic/region_faces.h` or `docs/harness.md`: folders of this
repository, then a file name with an extension. Paths with placeholders (<scene>, {name}, *)
and those under the git-ignored outputs (build/, out/, build-fuzz/) are skipped. A path may be
written relative to the repository root or to the file that names it. Exits 1 listing each
missing path with the file and line that names it."""
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
files = subprocess.run(["git", "-C", str(root), "ls-files", "-co", "--exclude-standard"],
                       capture_output=True, text=True, check=True).stdout.split()
folders = {p.split("/")[0] for p in files if "/" in p}
skip_roots = {"build", "out", "build-fuzz"}
extensions = "h|cpp|md|toml|glsl|frag|vert|comp|sh|py|json|csv|txt|cmake|png|exr|ply|off|obj"
path = re.compile(r"(?<![\w./-])((?:\.\./)?(?:[A-Za-z0-9_.-]+/)+[A-Za-z0-9_.-]+\.(?:%s))(?![\w/])"
                  % extensions)
comment_of = {
    ".h": r"//(.*)", ".cpp": r"//(.*)", ".glsl": r"//(.*)", ".frag": r"//(.*)",
    ".vert": r"//(.*)", ".comp": r"//(.*)", ".sh": r"#(.*)", ".py": r"#(.*)",
    ".cmake": r"#(.*)", ".txt": r"#(.*)", ".toml": r"#(.*)",
}
missing = []
for name in files:
    file = root / name
    suffix = file.suffix
    if name.startswith(("tests/data/", "tests/fuzz/corpus/")) or not file.is_file():
        continue
    if suffix == ".md":
        pattern = None
    elif suffix in comment_of or file.name == "CMakeLists.txt":
        pattern = re.compile(comment_of.get(suffix, r"#(.*)"))
    else:
        continue
    try:
        lines = file.read_text(encoding="utf-8").splitlines()
    except UnicodeDecodeError:
        continue
    for number, line in enumerate(lines, 1):
        text = line
        if pattern:
            match = pattern.search(line)
            if not match:
                continue
            text = match.group(1)
        for token in path.findall(text):
            if any(c in token for c in "<>{}*"):
                continue
            first = token.split("/")[0]
            if first in skip_roots or (first not in folders and first != ".."):
                continue
            if (root / token).exists() or (file.parent / token).exists():
                continue
            missing.append(f"{name}:{number}: {token}")
for entry in missing:
    print(entry)
if missing:
    print(f"check_paths: {len(missing)} paths named in comments or docs do not exist",
          file=sys.stderr)
    sys.exit(1)
print(f"check_paths: every path named in comments and docs of {len(files)} files exists")
