#!/usr/bin/env python3
"""The repository is self-contained (issue 61): no tracked file reads or names the folder that
sat beside the repository during development (the project's physics is docs/physics.md, the
Evrard reference data tests/data/evrard/). Usage: check_self_contained.py SOURCE_DIR. Prints
every file and line that names it; exit 1 if there is any."""
import pathlib
import subprocess
import sys

OUTSIDE = ".." + "/" + "shared"  # spelt in two parts so that this file does not name it
SKIPPED_DIRS = {".git", "__pycache__"}


def tracked_files(root):
    """The files git tracks; without git (a source archive), every file outside build folders."""
    try:
        out = subprocess.run(["git", "-C", str(root), "ls-files", "-z"], capture_output=True,
                             check=True).stdout
        return [root / name for name in out.decode().split("\0") if name]
    except (OSError, subprocess.CalledProcessError):
        return [p for p in root.rglob("*") if p.is_file() and not
                (SKIPPED_DIRS & set(p.parts) or any(d.startswith("build") for d in
                                                    p.relative_to(root).parts[:1]))]


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    files = tracked_files(root)
    found = 0
    for path in files:
        if not path.is_file():
            continue
        try:
            text = path.read_text(errors="strict")
        except (UnicodeDecodeError, OSError):
            continue  # binary files (images, HDF5)
        for number, line in enumerate(text.split("\n"), 1):
            if OUTSIDE in line:
                print(f"{path.relative_to(root)}:{number}: names {OUTSIDE}: {line.strip()}")
                found += 1
    print(f"check_self_contained: {len(files)} files, {found} naming {OUTSIDE}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
