#!/usr/bin/python3
"""The contact loops hold no call to Eigen: every small vector operation of the point loop is
inlined (CMakeLists.txt says why contact/law_loops.cpp gets a larger inlining budget for that).

An out-of-line Eigen call in the loop spills every live vector register; such calls were the
cracked AN4 beam's lost step rate (bench/RESULTS.md, "Architecture (issue 29)"). This
reads the optimised binary's code, not its speed: deterministic for one compiler, so it runs
only on what CI builds (GCC, Release) and is skipped (77) otherwise.

usage: check_hot_loop_inlined.py BINARY CXX_COMPILER_ID BUILD_TYPE
"""
import re
import shutil
import subprocess
import sys

# The loops over contacts and their points, with their lambdas and OpenMP outlined bodies.
HOT = re.compile(r"\brcdem::(evaluate_contacts?|evaluate_contact_block|evaluate_contact_range|"
                 r"catch_up_condensed)[<(]")
FUNCTION = re.compile(r"^[0-9a-f]+ <(.*)>:$")
CALL = re.compile(r"\bcall\s+[0-9a-f]+ <(.*)>$")


def strip_templates(name):
    """The name with every <...> removed (balanced), as far as its parameter list."""
    out, depth = [], 0
    for i, ch in enumerate(name):
        if ch == "<":
            depth += 1
        elif ch == ">":
            depth -= 1
        elif ch == "(" and depth == 0 and not name[:i].endswith("operator"):
            break
        elif depth == 0:
            out.append(ch)
    return "".join(out)


def callee(target):
    """The called function's qualified name (its return type and arguments dropped)."""
    target = re.sub(r"\+0x[0-9a-f]+$", "", target)
    bare = strip_templates(target).strip()
    return bare.split(" ")[-1] if bare else target


def main(binary, compiler, build_type):
    if compiler != "GNU" or build_type != "Release":
        print(f"skipped: checked for GCC Release builds only (this is {compiler} {build_type})")
        return 77
    if not shutil.which("objdump"):
        print("skipped: objdump (binutils) not found")
        return 77
    dump = subprocess.run(["objdump", "-d", "-C", "--no-show-raw-insn", binary],
                          capture_output=True, text=True, check=True).stdout
    current, hot_functions, problems = None, 0, []
    for line in dump.splitlines():
        m = FUNCTION.match(line)
        if m:
            current = m.group(1) if HOT.search(m.group(1)) else None
            hot_functions += current is not None
            continue
        if current is None:
            continue
        c = CALL.search(line)
        if c and callee(c.group(1)).startswith("Eigen::"):
            problems.append(f"{current[:120]}...\n    calls {c.group(1)[:160]}...")
    if hot_functions == 0:
        print(f"{binary}: no contact loop found (renamed? update HOT in this script)")
        return 1
    for p in problems:
        print(p)
    print(f"{hot_functions} contact-loop functions, {len(problems)} calls to Eigen")
    if problems:
        print("the unit's inlining budget is spent: raise --param=inline-unit-growth for "
              "contact/law_loops.cpp in CMakeLists.txt, or split that unit")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__.strip().splitlines()[-1])
    sys.exit(main(*sys.argv[1:]))
