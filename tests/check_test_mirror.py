#!/usr/bin/python3
"""Tests mirror the code (docs/testing.md): the test of core/<path>/<unit>.cpp is
tests/core/<path>/<unit>_test.cpp (more files on the same unit: <unit>_<aspect>_test.cpp).

    check_test_mirror.py SOURCE_DIR              check the tree
    check_test_mirror.py --self-test SOURCE_DIR  the same, then prove that the check catches a new
        unit without a test, a test file that names no unit, a test folder no executable builds,
        and an entry of UNTESTED that is tested by now or names no unit

Fails on:
  - a unit core/<path>/<unit>.cpp without a test file found by its path, unless UNTESTED lists it;
  - an entry of UNTESTED that has a test now (take it off the list) or is no unit;
  - a file tests/core/<path>/<name>.cpp that is not <unit>_test.cpp or <unit>_<aspect>_test.cpp
    for a unit (a .cpp or a header) of core/<path>/ (a suite across units belongs in tests/cases/);
  - a folder of tests/ holding test sources (.cpp) that no footpoint_test(... DIRS ...) of
    tests/CMakeLists.txt names, so that no executable would build them (tests/registry/ and
    tests/tools/ have executables of their own), and a .cpp directly in tests/ (the flat layout).
"""
import os
import re
import shutil
import sys
import tempfile

# The units of core/ without a test of their own, each with what covers it meanwhile: none, every
# unit has its test. The list only shrinks: a new unit comes with its test.
UNTESTED = []

# Folders of tests/ built by executables other than footpoint_test's.
OWN_EXECUTABLES = {"registry", "tools"}
FOOTPOINT_TEST = re.compile(r"footpoint_test\(\s*\w+\s+DIRS\s+([^)]*?)\s+LIBS\b", re.S)


def rel(path, root):
    return os.path.relpath(path, root).replace(os.sep, "/")


def core_folders(root):
    """Every folder of core/ (relative to root) with the unit names (file stems) it holds."""
    folders = {}
    for base, _, names in os.walk(os.path.join(root, "core")):
        stems = {os.path.splitext(n)[0] for n in names if n.endswith((".cpp", ".hpp"))}
        folders[rel(base, root)] = stems
    return folders


def units(root):
    """core/<path>/<unit>.cpp, sorted."""
    found = []
    for base, _, names in os.walk(os.path.join(root, "core")):
        found += [rel(os.path.join(base, n), root) for n in names if n.endswith(".cpp")]
    return sorted(found)


def unit_of(test_name, stems):
    """The unit a test file <unit>[_<aspect>]_test.cpp names (the longest that fits), or None."""
    if not test_name.endswith("_test.cpp"):
        return None
    subject = test_name[: -len("_test.cpp")]
    fitting = [s for s in stems if subject == s or subject.startswith(s + "_")]
    return max(fitting, key=len) if fitting else None


def built_folders(root):
    with open(os.path.join(root, "tests", "CMakeLists.txt"), encoding="utf-8") as f:
        text = f.read()
    folders = set()
    for m in FOOTPOINT_TEST.finditer(text):
        folders.update(m.group(1).split())
    return folders


def check(root, untested):
    problems = []
    folders = core_folders(root)
    tested = set()
    tests_core = os.path.join(root, "tests", "core")
    for base, _, names in os.walk(tests_core):
        mirrored = "core/" + rel(base, tests_core) if base != tests_core else "core"
        for name in sorted(n for n in names if n.endswith(".cpp")):
            where = rel(os.path.join(base, name), root)
            if mirrored not in folders:
                problems.append(f"{where}: no folder {mirrored}/ in core/ to mirror")
                continue
            unit = unit_of(name, folders[mirrored])
            if unit is None:
                problems.append(f"{where}: names no unit of {mirrored}/ (<unit>_test.cpp or "
                                f"<unit>_<aspect>_test.cpp; a suite across units goes in "
                                f"tests/cases/)")
            else:
                tested.add(f"{mirrored}/{unit}")
    all_units = units(root)
    for unit in all_units:
        stem = unit[: -len(".cpp")]
        if stem not in tested and unit not in untested:
            problems.append(f"{unit}: no test tests/{stem}_test.cpp (write one; a unit is not left "
                            f"untested)")
    for unit in untested:
        if unit not in all_units:
            problems.append(f"UNTESTED lists {unit}, which is no unit of core/: take it off")
        elif unit[: -len(".cpp")] in tested:
            problems.append(f"UNTESTED lists {unit}, which has a test now: take it off")
    built = built_folders(root)
    tests_dir = os.path.join(root, "tests")
    for base, dirs, names in os.walk(tests_dir):
        folder = rel(base, tests_dir)
        if folder.split("/")[0] in OWN_EXECUTABLES or folder == "support":
            dirs[:] = []
            continue
        if folder == ".":
            # The flat layout's files (tests/<prefix>_<name>.cpp) belong in the folders now.
            problems += [f"tests/{n}: a test source outside the mirrored folders (docs/testing.md)"
                         for n in sorted(names) if n.endswith(".cpp")]
        elif any(n.endswith(".cpp") for n in names) and folder not in built:
            problems.append(f"tests/{folder}/: test sources that no footpoint_test(... DIRS ...) "
                            f"of tests/CMakeLists.txt builds")
    return problems, len(all_units), len(untested)


def self_test(root):
    """Each kind of fault planted in a copy of the tree must be caught."""
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        copy = os.path.join(tmp, "src")
        shutil.copytree(os.path.join(root, "core"), os.path.join(copy, "core"))
        shutil.copytree(os.path.join(root, "tests"), os.path.join(copy, "tests"),
                        ignore=shutil.ignore_patterns("data", "tools", "e2e"))

        def expect(what, planted, untested=UNTESTED, needle=None):
            problems, _, _ = check(copy, untested)
            if not any((needle or planted) in p for p in problems):
                failures.append(f"self-test: {what} ({planted}) not caught")

        def write(path, text="// planted by the self-test\n"):
            os.makedirs(os.path.dirname(os.path.join(copy, path)), exist_ok=True)
            with open(os.path.join(copy, path), "w", encoding="utf-8") as f:
                f.write(text)

        def remove(path):
            os.remove(os.path.join(copy, path))

        write("core/solvers/planted_unit.cpp")
        expect("a new unit without a test", "core/solvers/planted_unit.cpp")
        write("tests/core/solvers/planted_unit_test.cpp")
        problems, _, _ = check(copy, UNTESTED)
        if any("planted_unit" in p for p in problems):
            failures.append("self-test: a unit with its test still reported")
        remove("tests/core/solvers/planted_unit_test.cpp")
        write("tests/core/solvers/planted_unit_corners_test.cpp")
        problems, _, _ = check(copy, UNTESTED)
        if any("planted_unit" in p for p in problems):
            failures.append("self-test: a unit with an <aspect> test still reported")
        remove("tests/core/solvers/planted_unit_corners_test.cpp")
        remove("core/solvers/planted_unit.cpp")
        write("tests/core/solvers/across_units.cpp")
        expect("a test file that names no unit", "tests/core/solvers/across_units.cpp")
        remove("tests/core/solvers/across_units.cpp")
        write("tests/core/no_such_folder/thing_test.cpp")
        expect("a test folder mirroring nothing", "tests/core/no_such_folder/thing_test.cpp")
        expect("a test folder no executable builds", "tests/core/no_such_folder/")
        shutil.rmtree(os.path.join(copy, "tests/core/no_such_folder"))
        write("tests/surface_flat_layout.cpp")
        expect("a test file in the flat layout", "tests/surface_flat_layout.cpp")
        remove("tests/surface_flat_layout.cpp")
        tested = "core/solvers/piecewise_nearest.cpp"  # a unit with its test
        expect("an UNTESTED entry that is tested now", tested, untested=UNTESTED + [tested],
               needle=f"UNTESTED lists {tested}")
        expect("an UNTESTED entry that is no unit", "core/solvers/gone.cpp",
               untested=UNTESTED + ["core/solvers/gone.cpp"])
        problems, _, _ = check(copy, UNTESTED)
        if problems:
            failures.append("self-test: the unchanged copy fails: " + "; ".join(problems))
    return failures


def main(argv):
    args = [a for a in argv[1:] if a != "--self-test"]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    root = args[0]
    problems, total, untested = check(root, UNTESTED)
    for p in problems:
        print(p)
    if "--self-test" in argv:
        failures = self_test(root)
        for f in failures:
            print(f)
        problems += failures
    print(f"test mirror: {total - untested} of {total} core units tested by their path, "
          f"{untested} listed untested; {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
