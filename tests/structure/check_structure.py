#!/usr/bin/env python3
"""The structural rules of docs/architecture.md, checked over the source tree (issues 15, 59):
  - no C++ file (include/, src/, apps/, tests/, bench/, fuzz/) over 300 lines;
  - no function (or lambda) over 80 lines there; the parser follows parentheses, so braced
    default arguments and initialisers do not hide a function, and it is checked against
    universal-ctags: every function ctags finds must be one the parser found (same last line);
  - the layer rules: a layer includes only the layers before it in LAYERS (so cases/ includes
    nothing from sim/, io/ nothing from sim/), gravity/ nothing from sph/, and cases/ calls no
    MPI function.
Usage: check_structure.py SOURCE_DIR. Prints every violation; exit 1 if there is any."""
import json
import pathlib
import re
import subprocess
import sys

MAX_FILE_LINES = 300
MAX_FUNCTION_LINES = 80

# The layers of include/exasph/ in order (docs/architecture.md, "Layers"): a layer may include
# only the layers before it, and not these either:
LAYERS = ["util", "sfc", "config", "particles", "tree", "domain", "kernel", "exact", "sph",
          "gravity", "cases", "io", "render", "sim", "glass", "run"]
ALSO_FORBIDDEN = {
    "sph": ["domain"],           # kernels and launchers know nothing of the decomposition
    "gravity": ["sph"],          # the kernel table lives in kernel/
    "cases": ["domain", "tree"],  # cases make particles; the run distributes them
}
MPI_CALL = re.compile(r"\bMPI_[A-Z][a-z_]*\s*\(")
CONTROL = re.compile(r"^\s*(if|for|while|switch|else|do|catch|try|namespace|struct|class|union|"
                     r"enum|return|case|default)\b")
FUNCTION_END = re.compile(r"[)}]\s*(const)?\s*(noexcept)?\s*(override)?\s*(mutable)?\s*"
                          r"(->\s*[\w:<>,\s*&]+)?\s*\{\s*$")


def strip_comments_and_strings(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    text = re.sub(r'"(\\.|[^"\\\n])*"', '""', text)
    return re.sub(r"'(\\.|[^'\\\n])'", "''", text)  # character literals such as '{'


def strip_to_statements(text):
    """The code without comments, strings, preprocessor lines and access labels, so that each
    statement starts with its own text (line numbers kept)."""
    text = strip_comments_and_strings(text)
    text = re.sub(r"^[ \t]*#(?:[^\n]*\\\n)*[^\n]*", lambda m: "\n" * m.group(0).count("\n"),
                  text, flags=re.M)  # with its continuation lines
    return re.sub(r"\b(public|private|protected)\s*:(?!:)", "", text)


# A '{' that opens a block rather than a braced initialiser (T x{1}, return {a, b}, = {}):
# after ')', after a control keyword, or after a declaration keyword's name.
DECLARATION = re.compile(r"^\s*(template\s*<.*>\s*)?(struct|class|union|enum|namespace|extern)\b",
                         re.S)
LAMBDA = re.compile(r"\]\s*(<[^<>]*>)?\s*(\([^()]*(\([^()]*\)[^()]*)*\))?\s*"
                    r"(mutable)?\s*(noexcept)?\s*"
                    r"([A-Z][A-Z0-9_]*\s*)*"  # attribute macros (EXASPH_INLINE_LAMBDA)
                    r"(->\s*[\w:<>,\s*&]+)?\s*\{$")


def opens_block(head):
    """Whether the '{' ending `head` (the statement's text so far) opens a block."""
    before = head[:-1].rstrip()
    if not before or before[-1] in ")}":
        return True
    if re.search(r"\b(else|do|try)$", before) or DECLARATION.match(head):
        return True
    return False


def functions(path):
    """(first line, last line) of every function and lambda body of the file: a block whose '{'
    closes a parameter list (or a constructor's initialisers) and does not follow a control
    statement, or a lambda's. Parentheses are followed so that a braced default argument
    (`const T& x = {}`) or initialiser does not end the statement."""
    text = strip_to_statements(path.read_text())
    found, stack, statement, start, line, depth = [], [], "", 1, 1, 0
    for ch in text:
        if ch == "\n":
            line += 1
        elif not statement.strip():
            start = line  # the statement's first line (templates and signatures included)
        statement += ch
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        elif ch == "{":
            is_function = depth == 0 and bool(FUNCTION_END.search(statement)) and \
                not CONTROL.match(statement.strip())
            is_lambda = bool(LAMBDA.search(statement))
            if not (is_function or is_lambda) and (depth > 0 or not opens_block(statement)):
                stack.append((line, None))  # an initialiser: the statement goes on
                continue
            stack.append((start if is_function else line, is_function or is_lambda))
            statement = ""
        elif ch == "}" and stack:
            first, kind = stack.pop()
            if kind is None:
                continue
            if kind:
                found.append((first, line))
            statement = ""
        elif ch == ";" and depth == 0:
            statement = ""
    return found


def long_functions(path):
    """(first line, lines) of every function or lambda longer than the limit."""
    return [(a, b - a + 1) for a, b in functions(path) if b - a + 1 > MAX_FUNCTION_LINES]


def ctags_functions(root, files):
    """{(path, last line): first line} of the functions universal-ctags finds, or None when
    it is not installed."""
    try:
        out = subprocess.run(["ctags", "--languages=C++", "--langmap=C++:+.cu", "--kinds-C++=f",
                              "--fields=+ne", "--output-format=json", "-f", "-"] +
                             [str(f) for f in files], capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    tags = {}
    for row in out.stdout.splitlines():
        tag = json.loads(row)
        if tag.get("kind") == "function" and "end" in tag:
            tags[(pathlib.Path(tag["path"]).resolve(), tag["end"])] = tag["line"]
    return tags


def compare_with_ctags(root, files):
    """Problems where the parser misses a function that universal-ctags finds (the same last
    line, a first line at or before ctags's name line) and the count of each."""
    tags = ctags_functions(root, files)
    if tags is None:
        print("universal-ctags is not installed: the comparison with it is skipped")
        return []
    ours = {(f.resolve(), last): first for f in files for first, last in functions(f)}
    problems = [f"{path.relative_to(root)}:{line}: a function ctags finds and the parser misses"
                for (path, last), line in sorted(tags.items())
                if not ((path, last) in ours and ours[(path, last)] <= line)]
    print(f"universal-ctags finds {len(tags)} functions, the parser {len(ours)} functions and "
          f"lambdas; {len(tags) - len(problems)} of ctags's are among the parser's")
    return problems


CODE_FOLDERS = ["include", "src", "apps", "tests", "bench", "fuzz"]
CODE_SUFFIXES = {".hpp", ".cpp", ".cu", ".cuh", ".h"}


def main(root):
    root = pathlib.Path(root).resolve()
    problems = []
    headers = sorted((root / "include").rglob("*.hpp"))
    sources = headers + sorted((root / "src").rglob("*.cpp")) + sorted((root / "apps").rglob("*.*pp"))
    code_files = sorted(f for d in CODE_FOLDERS for f in (root / d).rglob("*")
                  if f.suffix in CODE_SUFFIXES and f.is_file())
    for f in code_files:
        n = len(f.read_text().split("\n")) - 1
        if n > MAX_FILE_LINES:
            problems.append(f"{f.relative_to(root)}: {n} lines (at most {MAX_FILE_LINES})")
        for start, n in long_functions(f):
            problems.append(f"{f.relative_to(root)}:{start}: function of {n} lines "
                            f"(at most {MAX_FUNCTION_LINES})")
    problems += compare_with_ctags(root, code_files)
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
    print(f"checked {len(code_files)} code files ({len(headers)} headers in include/): "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
