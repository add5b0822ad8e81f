#!/usr/bin/python3
"""House style: no function in src/ longer than 120 lines, from the line of its opening brace to
the line of its closing one (docs/architecture.md). A function is a brace block opened at
namespace or class level that is not itself a namespace, class, struct, enum or union; its
lambdas and local classes count as part of it. Comments, string and character literals are
blanked before braces are counted.

usage: check_function_length.py SOURCE_DIR [LIMIT]
"""
import os
import re
import sys

OPENS_TYPE = re.compile(r"\b(namespace|class|struct|enum|union)\b[^();]*$")


def blank(line, in_comment):
    """The line with comments and literals blanked, and whether a /* comment is still open."""
    out, i = [], 0
    while i < len(line):
        if in_comment:
            end = line.find("*/", i)
            if end < 0:
                return "".join(out), True
            i, in_comment = end + 2, False
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_comment, i = True, i + 2
        elif line[i] in "\"'":
            quote, j = line[i], i + 1
            while j < len(line) and line[j] != quote:
                j += 2 if line[j] == "\\" else 1
            out.append(quote + quote)
            i = j + 1
        else:
            out.append(line[i])
            i += 1
    return "".join(out), in_comment


def functions(path):
    """(length, first line) of every function body in the file."""
    stack, found, in_comment, pending = [], [], False, ""
    for number, raw in enumerate(open(path, encoding="utf-8"), 1):
        code, in_comment = blank(raw.rstrip("\n"), in_comment)
        for k, ch in enumerate(code):
            if ch == "{":
                head = (pending + " " + code[:k]).strip()
                kind = "type" if OPENS_TYPE.search(head.split(";")[-1].split("}")[-1]) else "fn"
                stack.append((kind, number))
                pending = ""
            elif ch == "}":
                if stack:
                    kind, first = stack.pop()
                    if kind == "fn" and all(kd == "type" for kd, _ in stack):
                        found.append((number - first + 1, first))
                pending = ""
            elif ch == ";":
                pending = ""
        tail = code[max(code.rfind("{"), code.rfind("}"), code.rfind(";")) + 1:]
        pending = (pending + " " + tail).strip()[-400:]
    return found


def main(root, limit):
    src = os.path.join(root, "src")
    too_long, count = [], 0
    for dirpath, _, names in os.walk(src):
        for name in sorted(names):
            if name.endswith((".hpp", ".cpp")):
                path = os.path.join(dirpath, name)
                for length, first in functions(path):
                    count += 1
                    if length > limit:
                        too_long.append(f"{os.path.relpath(path, root)}:{first}: a function of "
                                        f"{length} lines (at most {limit})")
    print("\n".join(too_long) if too_long else f"ok: {count} functions, none over {limit} lines")
    return 1 if too_long else 0


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) == 3 else 120))
