#!/usr/bin/env python3
"""Lists the functions of src/ and apps/ over 80 lines (from the signature's first line to the
closing brace) and the files over 600, longest first; exits 1 when there is one. Run by ctest as
long_functions. Usage: scripts/long_functions.py [--max N] [--max-file N] [PATH ...]

A function is a brace block whose header (the text since the previous ';', '{' or '}' at its
level) ends in a parameter list: `name(...) [const] [noexcept] [override] [-> T] [: inits]`.
Control statements, classes, namespaces and lambdas assigned at namespace level are not
functions; a lambda or a local class counts in the function that holds it."""
import argparse
import pathlib
import re
import sys

NOT_FUNCTIONS = re.compile(r"^\s*(?:if|for|while|switch|catch|do|else|try|namespace|class|struct|"
                           r"enum|union|extern)\b|\bnamespace\b|=\s*\[")
CALL = re.compile(r"[\w:~<>,\s\*&\[\]]*?(?:operator\s*\S+|[~\w:]+)\s*\(")


def strip(text):
    """The source with comments, strings and characters blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (j + 1 - i)); i = j + 1
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(path):
    """(name, first line, length in lines) of each outermost function body in the file."""
    text = strip(path.read_text(errors="replace"))
    found, stack, header_start = [], [], 0
    for i, c in enumerate(text):
        if c == "{":
            header = text[header_start:i]
            in_function = any(kind == "function" for kind, _, _ in stack)
            kind = "block"
            if not in_function and not NOT_FUNCTIONS.search(header):
                flat = " ".join(header.split())
                if re.search(r"\)\s*(?:const|noexcept|override|final|mutable|\s)*"
                             r"(?:->\s*[^{]+)?(?::[^{]*)?$", flat) and CALL.match(flat):
                    kind = "function"
            first = header_start + len(header) - len(header.lstrip())
            stack.append((kind, first, header))
            header_start = i + 1
        elif c == "}":
            if stack:
                kind, first, header = stack.pop()
                if kind == "function":
                    name = re.search(r"(operator\s*\S+?|[~\w:]+)\s*\(", " ".join(header.split()))
                    first_line = text.count("\n", 0, first) + 1
                    last_line = text.count("\n", 0, i) + 1
                    found.append((name.group(1) if name else "?", first_line, last_line - first_line + 1))
            header_start = i + 1
        elif c == ";":
            header_start = i + 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max", type=int, default=80, help="lines a function may have")
    parser.add_argument("--max-file", type=int, default=600, help="lines a file may have")
    parser.add_argument("paths", nargs="*", default=["src", "apps"])
    args = parser.parse_args()
    root = pathlib.Path(__file__).resolve().parent.parent
    over = {}  # (file, function or None) -> lines
    for base in args.paths:
        base_path = root / base
        files = [base_path] if base_path.is_file() else sorted(
            p for p in base_path.rglob("*") if p.suffix in (".cpp", ".hpp", ".h", ".cc"))
        for f in files:
            name = f.relative_to(root).as_posix()
            lines = f.read_text(errors="replace").count("\n")
            if lines > args.max_file:
                over[(name, None)] = lines
            for function, _, length in functions(f):
                if length > args.max:
                    over[(name, function)] = max(length, over.get((name, function), 0))
    for (name, function), lines in sorted(over.items(), key=lambda kv: -kv[1]):
        print(f"{name} {function}: {lines} lines, over {args.max}" if function
              else f"{name}: {lines} lines, over {args.max_file}")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
