#!/usr/bin/env python3
"""Every package a test needs is one that `tools/run.sh test` installs.

usage: check_packages_named.py SOURCE_DIR BUILD_DIR

tools/packages.txt is the one list of Debian packages per job. A test that
finds a program (command -v, find_program) or reads a path that the test
job does not install passes on a developer's machine, where someone once
installed it by hand, and skips or fails on a fresh one (that is how
abi_selfcheck_cross came to fail on a new machine while CI stayed green).
This check fails when:
  - a ctest entry's label needs:P names a package P that the list does not
    give the test job;
  - a script a ctest entry runs (and the scripts of the tree that one
    calls) looks for a program or path that no line of the list provides,
    or that a package provides which is neither build's nor named by the
    needs: labels of an entry that runs the script;
  - a CMake file finds a program, or tests/CMakeLists.txt names an
    absolute path, that no package of the list provides (for the tests:
    none of the test job's).
It prints each test's needs, then each problem; exit 0 when there is none.
"""
import fnmatch
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile


def read_packages(path):
    """package -> (jobs, lookups)"""
    packages = {}
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            if len(words) < 2:
                sys.exit(f"{path}: '{line.strip()}' names no job")
            packages[words[0]] = (set(words[1].split(",")), words[2:])
    return packages


def provider(packages, lookup):
    """The package whose lookups match LOOKUP (a program name or a path)."""
    for name, (_, lookups) in packages.items():
        for pattern in lookups:
            if fnmatch.fnmatchcase(lookup, pattern) or fnmatch.fnmatchcase(pattern, lookup):
                return name
    return None


COMMAND_V = re.compile(r"command -v\s+([^\s|;&)]+)")
FOR_WORDS = re.compile(r"for (\w+) in ([^;]+);")
ABS_PATH = re.compile(r"(?<![\w$.])(/(?:usr|opt)/[\w.*/+-]+)")
M32_PROBE = re.compile(r"\bg(cc|\+\+) -m32\b")
TREE_SCRIPT = re.compile(r"((?:tools|tests|cmake)/[\w./-]+\.(?:sh|py))")


def script_lookups(text):
    """The programs and paths a shell script looks for."""
    found = set()
    for line in text.splitlines():
        code = line.split("#", 1)[0] if not line.lstrip().startswith("#!") else ""
        for m in COMMAND_V.finditer(code):
            word = m.group(1)
            if word.startswith("$"):
                # `for t in nasm readelf; do command -v $t`: the loop's words.
                var = word.lstrip("${").rstrip("}")
                loop = next((f for f in FOR_WORDS.finditer(code) if f.group(1) == var), None)
                if loop is None:
                    found.add(f"<unresolved {word}>")
                else:
                    found.update(loop.group(2).split())
            else:
                found.add(word)
        for m in ABS_PATH.finditer(code):
            found.add(m.group(1).rstrip("/"))
        for m in M32_PROBE.finditer(code):
            found.add(f"g{m.group(1)}-m32")
    return found


def scripts_of(command, source_dir):
    """The tree's scripts COMMAND runs, and those they name, transitively."""
    todo = [a for a in command
            if os.path.isfile(a) and os.path.realpath(a).startswith(source_dir + os.sep)]
    seen = []
    while todo:
        path = os.path.realpath(todo.pop())
        if path in seen or not path.endswith((".sh", ".py")):
            continue
        seen.append(path)
        with open(path, errors="replace") as f:
            text = f.read()
        # The scripts it runs: named on a line of shell code, not in a
        # comment or in a message it prints.
        for line in (text.splitlines() if path.endswith(".sh") else []):
            code = line.split("#", 1)[0]
            if re.search(r"\b(echo|err|printf|fail|skip)\b", code):
                continue
            for m in TREE_SCRIPT.finditer(code):
                candidate = os.path.join(source_dir, m.group(1))
                if os.path.isfile(candidate):
                    todo.append(candidate)
    return seen


FIND_PROGRAM = re.compile(r"find_program\s*\(\s*(\w+)\s+([^)]*)\)", re.S)
FIND_PROGRAM_KEYWORDS = {"NAMES", "REQUIRED", "NO_DEFAULT_PATH", "NO_CACHE", "PATHS", "HINTS", "DOC"}


def cmake_lookups(text):
    found = set()
    for m in FIND_PROGRAM.finditer(text):
        words = m.group(2).split()
        names = []
        for w in words:
            if w in ("PATHS", "HINTS", "DOC"):
                break
            if w not in FIND_PROGRAM_KEYWORDS:
                names.append(w)
        found.update(names)
    return found


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source_dir = os.path.realpath(sys.argv[1])
    build_dir = sys.argv[2]
    packages = read_packages(os.path.join(source_dir, "tools", "packages.txt"))
    test_job = {p for p, (jobs, _) in packages.items() if jobs & {"build", "test"}}
    base = {p for p, (jobs, _) in packages.items() if "build" in jobs}
    # The test programs of the cross builds (tools/run.sh cross) are
    # configured from tests/CMakeLists.txt too.
    cross_job = {p for p, (jobs, _) in packages.items() if jobs & {"build", "cross"}}
    problems = []

    # ctest lists the entries from a copy of the build's CTestTestfile.cmake
    # files: run in the build folder itself, it would truncate the
    # Testing/Temporary/LastTest.log of the ctest run this check is part of.
    with tempfile.TemporaryDirectory() as mirror:
        for dirpath, _, filenames in os.walk(build_dir):
            if "CTestTestfile.cmake" in filenames:
                dest = os.path.join(mirror, os.path.relpath(dirpath, build_dir))
                os.makedirs(dest, exist_ok=True)
                shutil.copy(os.path.join(dirpath, "CTestTestfile.cmake"), dest)
        listing = subprocess.run(["ctest", "--show-only=json-v1"], cwd=mirror, check=True,
                                 capture_output=True, text=True).stdout
    tests = json.loads(listing)["tests"]
    if not tests:
        problems.append(f"ctest in {build_dir} lists no test")
    # A script that several entries run (one mode each, as
    # check_abi_selfcheck_cross.sh) may look for what any of them needs.
    needs_of_script = {}
    scripts_of_test = {}
    for t in tests:
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        labels = props.get("LABELS", [])
        needs = {l.split(":", 1)[1] for l in labels if l.startswith("needs:")}
        print(f"{t['name']}: needs {' '.join(sorted(needs)) or '(the build packages only)'}")
        for p in sorted(needs - set(packages)):
            problems.append(f"{t['name']}: needs:{p} names a package tools/packages.txt does not list")
        for p in sorted((needs & set(packages)) - test_job):
            problems.append(f"{t['name']}: needs:{p}, which tools/packages.txt does not give the test job")
        scripts_of_test[t["name"]] = scripts_of(t.get("command", []), source_dir)
        for script in scripts_of_test[t["name"]]:
            needs_of_script.setdefault(script, set()).update(needs)
    for name, scripts in scripts_of_test.items():
        for script in scripts:
            with open(script, errors="replace") as f:
                lookups = script_lookups(f.read())
            rel = os.path.relpath(script, source_dir)
            for lookup in sorted(lookups):
                p = provider(packages, lookup)
                if p is None:
                    problems.append(f"{name}: {rel} looks for {lookup}, which no line of "
                                    "tools/packages.txt provides")
                elif p not in base and p not in needs_of_script[script]:
                    problems.append(f"{name}: {rel} looks for {lookup} (package {p}), "
                                    f"but no entry that runs it is labelled needs:{p}")

    for dirpath, dirnames, filenames in os.walk(source_dir):
        dirnames[:] = [d for d in dirnames if not d.startswith((".", "build"))]
        for fn in filenames:
            if fn != "CMakeLists.txt" and not fn.endswith(".cmake"):
                continue
            path = os.path.join(dirpath, fn)
            rel = os.path.relpath(path, source_dir)
            with open(path, errors="replace") as f:
                text = f.read()
            in_tests = rel.startswith("tests" + os.sep)
            lookups = cmake_lookups(text)
            if in_tests:
                lookups |= {m.group(1).rstrip("/") for m in ABS_PATH.finditer(text)}
            for lookup in sorted(lookups):
                p = provider(packages, lookup)
                if p is None:
                    problems.append(f"{rel} looks for {lookup}, which no line of tools/packages.txt provides")
                elif in_tests and p not in test_job | cross_job:
                    problems.append(f"{rel} looks for {lookup} (package {p}), which neither the "
                                    "test job nor the cross job installs")

    for p in problems:
        print(f"FAIL: {p}")
    print(f"{len(tests)} entries, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
