#!/usr/bin/env python3
"""The library stays readable in pieces (issue 33): no file of src/exactpixels over
MAX_FILE_LINES lines, and no function of the scene layer over MAX_FUNCTION_LINES lines,
counted from the line of its opening brace to the line of its closing brace.

Usage: code_size_check.py LIBRARY_DIR   (the folder src/exactpixels)
Prints every file and function over its limit and exits 1 if there is one.

Functions are found by braces, after comments, string and character literals are
blanked: a brace at namespace scope, or directly inside a class, struct or union, whose
text before it (back to the previous `;`, `{` or `}`) ends in `)` plus qualifiers is a
function body; lambdas and blocks inside a body count towards that body.
"""
import re
import sys
from pathlib import Path

MAX_FILE_LINES = 800
MAX_FUNCTION_LINES = 80
FUNCTION_LAYERS = ["scene"]
SOURCE_SUFFIXES = {".hpp", ".cpp", ".inl"}

LITERAL = re.compile(r'//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                     re.S)
FUNCTION_HEAD = re.compile(
    r"\)\s*(?:const|noexcept(?:\([^()]*\))?|override|final|mutable|&|&&|\s)*"
    r"(?:->\s*[\w:<>,\s&*]+)?\s*$")
SCOPE_HEAD = re.compile(r"\b(?:namespace|class|struct|union|enum)\b[^()]*$|extern\s*$")


def blank(match):
    """A literal or comment replaced by spaces, its newlines kept."""
    return re.sub(r"[^\n]", " ", match.group(0))


def long_functions(text):
    """(first line, lines) of every function body in `text` over MAX_FUNCTION_LINES."""
    code = LITERAL.sub(blank, text)
    found = []
    stack = []  # per open brace: "scope" (namespace/class) or ("body", line) or "inner"
    last_stop = 0
    for at, char in enumerate(code):
        if char == "{":
            head = code[last_stop:at]
            in_scope = all(kind == "scope" for kind in stack)
            line = code.count("\n", 0, at) + 1
            if in_scope and SCOPE_HEAD.search(head) and not FUNCTION_HEAD.search(head):
                stack.append("scope")
            elif in_scope and FUNCTION_HEAD.search(head):
                stack.append(("body", line))
            else:
                stack.append("inner")
            last_stop = at + 1
        elif char == "}":
            if stack:
                kind = stack.pop()
                if isinstance(kind, tuple):
                    lines = code.count("\n", 0, at) + 1 - kind[1] + 1
                    if lines > MAX_FUNCTION_LINES:
                        found.append((kind[1], lines))
            last_stop = at + 1
        elif char == ";":
            last_stop = at + 1
    return found


def main():
    library = Path(sys.argv[1])
    problems = []
    for path in sorted(library.rglob("*")):
        if path.suffix not in SOURCE_SUFFIXES:
            continue
        text = path.read_text(encoding="utf-8")
        lines = text.count("\n")
        if lines > MAX_FILE_LINES:
            problems.append(f"{path}: {lines} lines (at most {MAX_FILE_LINES})")
        if path.relative_to(library).parts[0] in FUNCTION_LAYERS:
            for first, length in long_functions(text):
                problems.append(f"{path}:{first}: a function of {length} lines "
                                f"(at most {MAX_FUNCTION_LINES})")
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
