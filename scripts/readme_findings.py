#!/usr/bin/python3
"""The README's findings are the report's own words: copy OUT/findings.md (written by reports/make_report.py
from this run's verdicts) between the README's markers, or, with --check, say whether they are there already.

usage: readme_findings.py [--check] FINDINGS [README]   (README defaults to the repository's README.md)
Exit 0: copied, or (--check) the same; 1 (--check): different; 2: a file or marker is missing."""
import os
import sys

BEGIN = "<!-- findings: copied from reports/out/findings.md by scripts/readme_findings.py; do not edit by hand -->"
END = "<!-- end of findings -->"


def main():
    args = sys.argv[1:]
    check = "--check" in args
    args = [a for a in args if a != "--check"]
    if not args or len(args) > 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    readme = args[1] if len(args) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "README.md")
    try:
        block = open(args[0], encoding="utf-8").read().strip("\n")
        text = open(readme, encoding="utf-8").read()
    except OSError as e:
        print(f"readme_findings: {e}", file=sys.stderr)
        return 2
    start, end = text.find(BEGIN), text.find(END)
    if start < 0 or end < start:
        print(f"readme_findings: {readme} has no findings markers (allowed: a block between '{BEGIN}' and '{END}')",
              file=sys.stderr)
        return 2
    new = text[:start + len(BEGIN)] + "\n" + block + "\n" + text[end:]
    if check:
        return 0 if new == text else 1
    if new != text:
        temporary = readme + ".tmp"
        with open(temporary, "w", encoding="utf-8") as out:
            out.write(new)
        os.replace(temporary, readme)
    return 0


if __name__ == "__main__":
    sys.exit(main())
