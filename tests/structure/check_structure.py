#!/usr/bin/env python3
"""The structural rules of docs/architecture.md, checked over the source tree (issue 15):
  - no header in include/ over 300 lines;
  - no function (or lambda) over 80 lines in include/, src/, apps/;
  - the layer rules: a layer includes only the layers before it in LAYERS (so cases/ includes
    nothing from sim/, io/ nothing from sim/), gravity/ nothing from sph/, and cases/ calls no
    MPI function.
Usage: check_structure.py SOURCE_DIR. Prints every violation; exit 1 if there is any."""
import pathlib
import re
import sys

MAX_HEADER_LINES = 300
MAX_FUNCTION_LINES = 80

# The layers of include/exasph/ in order (docs/architecture.md, "Layers"): a layer may include
# only the layers before it, and not these either:
LAYERS = ["util", "sfc", "config", "particles", "tree", "domain", "kernel", "sph", "gravity",
          "exact", "cases", "io", "render", "sim", "glass", "run"]
ALSO_FORBIDDEN = {
    "sph": ["domain"],           # kernels and launchers know nothing of the decomposition
    "gravity": ["sph"],          # the kernel table lives in kernel/
    "cases": ["domain", "tree"],  # cases make particles; the run distributes them
}
MPI_CALL = re.compile(r"\bMPI_[A-Z][a-z_]*\s*\(")
CONTROL = re.compile(r"^\s*(if|for|while|switch|else|do|catch|try|namespace|struct|class|union|"
                     r"enum|return|extern|case|default)\b")
FUNCTION_END = re.compile(r"\)\s*(const)?\s*(noexcept)?\s*(override)?\s*(mutable)?\s*"
                          r"(->\s*[\w:<>,\s*&]+)?\s*\{\s*$")


def strip_comments_and_strings(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    return re.sub(r'"(\\.|[^"\\\n])*"', '""', text)


def long_functions(path):
    """(first line, lines) of every function body longer than the limit: a '{' that closes a
    parameter list (after the statement's text, not a control statement) opens a function."""
    lines = strip_comments_and_strings(path.read_text()).split("\n")
    found, stack, statement, statement_start = [], [], "", 0
    for number, line in enumerate(lines, 1):
        if not statement.strip():
            statement_start = number
        statement += " " + line
        for pos, ch in enumerate(line):
            if ch == "{":
                head = statement[: len(statement) - len(line) + pos + 1]
                is_function = FUNCTION_END.search(head) and not CONTROL.match(head.strip())
                lam = re.search(r"\]\s*(\([^()]*\))?\s*(mutable)?\s*(->\s*[\w:<>]+)?\s*\{$", head)
                stack.append((statement_start if is_function else number,
                              bool(is_function or lam)))
                statement = ""
            elif ch == "}":
                if stack:
                    start, is_function = stack.pop()
                    if is_function and number - start + 1 > MAX_FUNCTION_LINES:
                        found.append((start, number - start + 1))
                statement = ""
            elif ch == ";":
                statement = ""
        if statement.strip() == "":
            statement = ""
    return found


def main(root):
    root = pathlib.Path(root)
    problems = []
    headers = sorted((root / "include").rglob("*.hpp"))
    sources = headers + sorted((root / "src").rglob("*.cpp")) + sorted((root / "apps").rglob("*.*pp"))
    for h in headers:
        n = len(h.read_text().split("\n")) - 1
        if n > MAX_HEADER_LINES:
            problems.append(f"{h.relative_to(root)}: {n} lines (at most {MAX_HEADER_LINES})")
    for s in sources:
        for start, n in long_functions(s):
            problems.append(f"{s.relative_to(root)}:{start}: function of {n} lines "
                            f"(at most {MAX_FUNCTION_LINES})")
    for layer in LAYERS:
        allowed = set(LAYERS[: LAYERS.index(layer) + 1]) - set(ALSO_FORBIDDEN.get(layer, []))
        for h in sorted((root / "include" / "exasph" / layer).glob("*.hpp")):
            text = h.read_text()
            for inc in re.findall(r'#include "exasph/(\w+)/', text):
                if inc not in allowed:
                    problems.append(f"{h.relative_to(root)}: {layer}/ includes {inc}/")
            if layer == "cases":
                code = strip_comments_and_strings(text)
                if MPI_CALL.search(code) or "util/mpi.hpp" in text:
                    problems.append(f"{h.relative_to(root)}: cases/ uses MPI")
    # MPI comes through util/mpi.hpp, so that a build without MPI gets the single-rank stand-in.
    for s in sources:
        if "#include <mpi.h>" in s.read_text() and s.name != "mpi.hpp":
            problems.append(f"{s.relative_to(root)}: includes <mpi.h> (use exasph/util/mpi.hpp)")
    for d in sorted((root / "include" / "exasph").iterdir()):
        if d.is_dir() and d.name not in LAYERS:
            problems.append(f"{d.relative_to(root)}: a folder that is not a layer of "
                            "docs/architecture.md")
    for p in problems:
        print(p)
    print(f"checked {len(headers)} headers and {len(sources)} sources: "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
