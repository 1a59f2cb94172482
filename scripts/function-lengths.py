#!/usr/bin/python3
"""Lengths of the C++ functions and files of the library, for the code-style limits
(functions ≤ ~80 lines, files ≤ ~600 lines; docs in the developers' guide).

    /usr/bin/python3 scripts/function-lengths.py [paths ...] [--limit 80] [--file-limit 600]
                                                  [--all] [--check]

Paths default to the library: include/ and src/ without src/cli/. Each .cpp/.hpp/.h file is
scanned once, comments, string and character literals and preprocessor lines removed, for its
braces. A brace opens a *function body* when it stands at namespace or class scope (inside no
other function) and the text before it, since the last `;`, `{` or `}`, holds a parenthesis and
is not a class, struct, union or enum head (a template parameter list stripped first); the
braces of a constructor's member initializers (`x_{…}`) and of `= {…}` initializers are skipped.
A function's length is its lines from the first line of that text (its signature, the
`template <…>` line included) to its closing brace, blank and comment lines included. Lambdas
and local classes count towards the function that holds them. A file's length is its line count.

Prints the functions and files over the limits (every function with --all), longest first;
with --check the status is 1 if any is over.
"""

import argparse
import os
import re
import sys

SOURCE_ENDINGS = (".cpp", ".hpp", ".h", ".cc")


def strip(text):
    """The text with comments, literals and preprocessor lines blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            # A preprocessor line, with its continuations.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if c == "\n":
            at_line_start = True
            out.append(c)
            i += 1
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i:end]))
            i = end
            continue
        raw = re.match(r'R"([^(\s]*)\(', text[i:i + 20])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = text.find(")" + raw.group(1) + '"', i)
            end = n if end < 0 else end + len(raw.group(1)) + 2
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i:end]))
            i = end
            continue
        if c == '"' or (c == "'" and not (i > 0 and (text[i - 1].isalnum()))):  # 1'000 is a digit separator
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j, n - 1) + 1 - i))
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def strip_template_heads(header):
    """The header without `template <…>` parameter lists (balanced angle brackets)."""
    result = header
    while True:
        m = re.search(r"\btemplate\s*<", result)
        if not m:
            return result
        depth, j = 1, m.end()
        while j < len(result) and depth:
            depth += {"<": 1, ">": -1}.get(result[j], 0)
            j += 1
        result = result[:m.start()] + result[j:]


CLASS_HEAD = re.compile(r"^\s*(?:\[\[[^\]]*\]\]\s*)*(class|struct|union|enum)\b")


def classify(header):
    """'namespace', 'class', 'function', 'init' (a brace initializer) or 'block' for the text before a `{`."""
    h = " ".join(header.split())
    if re.match(r"^(inline\s+)?namespace\b", h) or re.match(r'^extern\s*$', h):
        return "namespace"
    bare = strip_template_heads(h)
    if CLASS_HEAD.match(bare) and "(" not in bare.split("{")[0].split(":")[0]:
        return "class"
    if re.search(r"=\s*$", h) or not h:
        return "init"
    if "(" in h:
        # A member initializer's brace, `X() : a_(x), b_{`: after the signature's `)` and a single
        # colon, an identifier right before the brace (a body follows a `)` or a `}`).
        if re.search(r"\)[\s\w]*(?<!:):(?!:)", h) and re.search(r"[\w>]\s*$", h):
            return "member_init"
        return "function"
    return "init"


def scan(path):
    """(name, first line, lines) of every function body in the file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = strip(f.read())
    functions = []
    stack = []  # kinds of the open braces
    header_start = 0  # index where the text before the next brace begins
    i = 0
    line_of = []
    line = 1
    for ch in text:
        line_of.append(line)
        if ch == "\n":
            line += 1
    function_open = None  # (name, start line, depth) of the function being scanned
    keep_header = False
    while i < len(text):
        c = text[i]
        if c == "{":
            if function_open is None and all(k in ("namespace", "class") for k in stack):
                header = text[header_start:i]
                kind = classify(header)
                if kind == "function":
                    start = header_start + (len(header) - len(header.lstrip()))
                    name = " ".join(header.split())
                    name = re.sub(r"\s*\(.*", "", name.split("(")[0] + "(")
                    name = name.split()[-1] if name.split() else "?"
                    function_open = (name, line_of[start], len(stack))
                elif kind in ("member_init", "init"):
                    keep_header = kind == "member_init"
                stack.append(kind)
            else:
                stack.append("block")
            if stack[-1] != "member_init":
                header_start = i + 1
            i += 1
            continue
        if c == "}":
            kind = stack.pop() if stack else "block"
            if function_open is not None and len(stack) == function_open[2]:
                name, start, _ = function_open
                functions.append((name, start, line_of[i] - start + 1))
                function_open = None
            if kind != "member_init":
                header_start = i + 1
            i += 1
            continue
        if c == ";" and (function_open is None):
            header_start = i + 1
        i += 1
    return functions


def library_paths(root):
    paths = []
    for top in ("include", "src"):
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(d for d in dirs if os.path.join(folder, d) != os.path.join(root, "src", "cli"))
            paths.extend(os.path.join(folder, f) for f in sorted(files) if f.endswith(SOURCE_ENDINGS))
    return paths


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("paths", nargs="*", help="files or folders (default: the library)")
    parser.add_argument("--limit", type=int, default=80, help="function lines")
    parser.add_argument("--file-limit", type=int, default=600, help="file lines")
    parser.add_argument("--all", action="store_true", help="every function, not only those over the limit")
    parser.add_argument("--check", action="store_true", help="exit 1 if anything is over a limit")
    args = parser.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    paths = []
    for p in args.paths or library_paths(root):
        if os.path.isdir(p):
            for folder, dirs, files in os.walk(p):
                dirs.sort()
                paths.extend(os.path.join(folder, f) for f in sorted(files) if f.endswith(SOURCE_ENDINGS))
        else:
            paths.append(p)
    functions, files = [], []
    for path in paths:
        shown = os.path.relpath(path, root) if os.path.abspath(path).startswith(root) else path
        with open(path, encoding="utf-8", errors="replace") as f:
            files.append((sum(1 for _ in f), shown))
        functions.extend((length, f"{shown}:{start}", name) for name, start, length in scan(path))
    functions.sort(key=lambda f: (-f[0], f[1]))
    files.sort(key=lambda f: (-f[0], f[1]))
    long_functions = [f for f in functions if f[0] > args.limit]
    long_files = [f for f in files if f[0] > args.file_limit]
    for length, where, name in functions if args.all else long_functions:
        print(f"{length:5d}  {name}  {where}")
    for length, shown in long_files:
        print(f"{length:5d}  file  {shown}")
    print(f"{len(functions)} functions in {len(files)} files; over {args.limit} lines: {len(long_functions)} "
          f"functions, over {args.file_limit} lines: {len(long_files)} files", file=sys.stderr)
    return 1 if args.check and (long_functions or long_files) else 0


if __name__ == "__main__":
    sys.exit(main())
