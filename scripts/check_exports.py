#!/usr/bin/python3
"""The public surface of libgomboc.so: the symbols it exports (`nm -D --defined-only`) against the functions
its public headers mark GB_API (src/gb_export.h). Both lists must be equal: an exported symbol no public
header declares is an internal one leaking out; a marked declaration the library does not export is a
promise it does not keep. And every marked function is named by its module: gb_MODULE or gb_MODULE_...
in src/gb_MODULE.h (the house guide's rule, which REBOUND also checks with nm). With --callers, every exported
function must be named in one of the files that follow (the command, the harness, the fuzzers, the benchmarks,
the examples, the Python package): a function that only the library calls belongs inside it.

usage: check_exports.py LIBRARY HEADER [HEADER ...] [--callers FILE ...]
Prints one line of counts, or every difference and exits 1."""
import re
import subprocess
import sys


def exported(library):
    out = subprocess.run(["nm", "-D", "--defined-only", library], check=True, capture_output=True, text=True).stdout
    names = set()
    for line in out.splitlines():
        fields = line.split()
        # code and data the library defines; the linker's own markers (A) are not the library's API
        if len(fields) == 3 and fields[1] in "TDBRVWi":
            names.add(fields[2].split("@")[0])
    return names


def declared(headers):
    names = {}
    for path in headers:
        text = open(path, encoding="utf-8").read()
        text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)  # comments may name GB_API too
        text = re.sub(r"^\s*#.*$", " ", text, flags=re.M)  # and so does its own definition
        for match in re.finditer(r"\bGB_API\b([^;{]*?)\(", text):
            name = re.findall(r"[A-Za-z_]\w*", match.group(1))[-1]
            names[name] = path
    return names


def main(argv):
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    library, rest = argv[1], argv[2:]
    callers = []
    if "--callers" in rest:
        i = rest.index("--callers")
        rest, callers = rest[:i], rest[i + 1:]
    headers = rest
    have, promised = exported(library), declared(headers)
    uncalled = []
    if callers:
        text = "\n".join(open(path, encoding="utf-8", errors="replace").read() for path in callers)
        named = set(re.findall(r"\bgb_\w+", text))
        uncalled = sorted(name for name in have if name not in named)
        for name in uncalled:
            print(f"exports: {library} exports {name}, which none of the {len(callers)} files outside the library calls")
    leaking = sorted(have - set(promised))
    missing = sorted(set(promised) - have)
    misnamed = []
    for name, path in sorted(promised.items()):
        module = re.sub(r"\.h$", "", path.rsplit("/", 1)[-1])
        if module.startswith("gb_") and name != module and not name.startswith(module + "_"):
            misnamed.append(name)
            print(f"exports: {path} marks {name} GB_API, which is not named by its module ({module}_...)")
    for name in leaking:
        print(f"exports: {library} exports {name}, which no public header marks GB_API")
    for name in missing:
        print(f"exports: {promised[name]} marks {name} GB_API, which {library} does not export")
    if leaking or missing or misnamed or uncalled or not have:
        print(f"exports: FAILED ({len(leaking)} internal symbols exported, {len(missing)} public ones missing, "
              f"{len(misnamed)} not named by their module, {len(uncalled)} called by nothing outside the library)")
        return 1
    print(f"exports: {library} exports the {len(have)} functions the {len(headers)} public headers mark GB_API, "
          "and nothing else, each named by its module" + (f" and called outside the library ({len(callers)} files)"
                                                        if callers else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
