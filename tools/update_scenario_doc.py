#!/usr/bin/python3
"""Keeps the key reference in docs/scenario.md equal to `rcdem print-schema`.

usage: update_scenario_doc.py RCDEM_BINARY DOC [--check]
With --check, exits 1 if the doc's block differs (a test runs this); otherwise rewrites the block.
"""
import subprocess
import sys

rcdem, doc = sys.argv[1], sys.argv[2]
check = "--check" in sys.argv[3:]
begin, end = "<!-- schema:begin -->\n```toml\n", "```\n<!-- schema:end -->"
schema = subprocess.run([rcdem, "print-schema"], capture_output=True, text=True, check=True).stdout
text = open(doc).read()
i, j = text.find(begin), text.find(end)
if i < 0 or j < 0:
    sys.exit(f"{doc}: no schema block (markers '<!-- schema:begin -->' ... '<!-- schema:end -->')")
current = text[i + len(begin):j]
if check:
    if current != schema:
        sys.exit(f"{doc} is out of date with `rcdem print-schema`: run tools/update_scenario_doc.py")
    print(f"{doc}: schema block up to date")
else:
    open(doc, "w").write(text[:i + len(begin)] + schema + text[j:])
