#!/usr/bin/python3
"""The layers of core/ and server/ read top to bottom (core/CMakeLists.txt draws the picture):

    formula -> geometry -> seeding -> solvers -> compiled -> batch, cache, mesh -> server

Every `#include "..."` of a file in a layer must name a header of the same layer or of a layer
below it, and the libraries the build makes of third-party code stay where they belong (muparser
only in formula/, nanoflann only in seeding/, OpenSSL only in compiled/ and server/, JSON, HTTP and
logging only in server/). With the
layers' static libraries, bottom to top, every symbol a layer's library leaves undefined must not
be defined only by a library above it (a wrong-way call, which a link may or may not catch,
depending on what else pulled that object in).

    check_layer_order.py SOURCE_DIR [LIBRARY ...]              check the tree (and the libraries)
    check_layer_order.py --self-test SOURCE_DIR [LIBRARY ...]  the same, then prove that the checks
        catch a wrong-way include, a misplaced third-party header and (with libraries) wrong-way
        symbols: planted in a copy of the tree, and the libraries handed over in the wrong order
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Bottom to top: a layer and the folders (relative to the source directory) it is made of.
LAYERS = [
    ("formula", ["core/formula"]),
    ("geometry", ["core/projection", "core/geometry", "core/parametric/geometry", "core/implicit/geometry"]),
    ("seeding", ["core/seeding", "core/parametric/seeding", "core/implicit/seeding"]),
    ("solvers", ["core/solvers", "core/parametric/solvers", "core/implicit/solvers"]),
    ("compiled", ["core/compiled"]),
    ("batch/cache/mesh", ["core/batch", "core/cache", "core/mesh"]),
    ("server", ["server"]),
]
# The directories quoted includes are looked up in, after the including file's own directory.
INCLUDE_DIRS = ["core", "server"]
# Third-party headers (angle includes by prefix) and the layers allowed to include them.
THIRD_PARTY = [
    ("muParser", {"formula"}),
    ("nanoflann", {"seeding"}),
    ("nlohmann/", {"server"}),
    ("httplib", {"server"}),
    ("spdlog/", {"server"}),
    ("fmt/", {"server"}),
    ("openssl/", {"compiled", "server"}),
]
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def layer_of(path, root):
    rel = os.path.relpath(path, root).replace(os.sep, "/")
    for index, (name, folders) in enumerate(LAYERS):
        if any(rel == f or rel.startswith(f + "/") for f in folders):
            return index
    return None


def source_files(root):
    for _, folders in LAYERS:
        for folder in folders:
            for base, _, names in os.walk(os.path.join(root, folder)):
                for n in sorted(names):
                    if n.endswith((".hpp", ".cpp", ".h")):
                        yield os.path.join(base, n)


def check_includes(root):
    """Every include against the layer order, as 'file:line: message' lines."""
    problems = []
    for path in source_files(root):
        own = layer_of(path, root)
        with open(path, encoding="utf-8") as f:
            lines = f.readlines()
        for number, line in enumerate(lines, 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            where = f"{os.path.relpath(path, root)}:{number}"
            kind, name = m.groups()
            if kind == "<":
                for prefix, allowed in THIRD_PARTY:
                    if name.startswith(prefix) and LAYERS[own][0] not in allowed:
                        problems.append(f"{where}: <{name}> belongs to {', '.join(sorted(allowed))} only, "
                                        f"not to {LAYERS[own][0]}")
                continue
            candidates = [os.path.join(os.path.dirname(path), name)]
            candidates += [os.path.join(root, d, name) for d in INCLUDE_DIRS]
            target = next((c for c in candidates if os.path.isfile(c)), None)
            if target is None:
                problems.append(f'{where}: "{name}" is no header of the tree')
                continue
            theirs = layer_of(target, root)
            if theirs is None:
                problems.append(f'{where}: "{name}" lies outside the layers')
            elif theirs > own:
                problems.append(f'{where}: {LAYERS[own][0]} includes "{name}" of {LAYERS[theirs][0]}, '
                                f"a layer above it")
    return problems


def symbols(library, defined):
    flag = "--defined-only" if defined else "--undefined-only"
    out = subprocess.run(["nm", "--format=posix", flag, library], check=True, capture_output=True,
                         text=True).stdout
    names = set()
    for line in out.splitlines():
        parts = line.split()
        # "name type [value size]"; archive member headers end with ':'
        if len(parts) >= 2 and not parts[0].endswith(":") and (not defined or parts[1] in "TDBRVWtdbr"):
            if defined and parts[1] in "tdbr":
                continue  # local symbols
            names.add(parts[0])
    return names


def check_symbols(libraries):
    """libraries bottom to top: a symbol that one of them uses and only libraries above define."""
    defined = [symbols(lib, True) for lib in libraries]
    problems = []
    for i, lib in enumerate(libraries):
        below = set().union(*defined[: i + 1])
        above = set().union(*defined[i + 1:]) if i + 1 < len(libraries) else set()
        wrong = sorted((symbols(lib, False) - below) & above)
        for name in wrong[:10]:
            owner = next(os.path.basename(libraries[j]) for j in range(i + 1, len(libraries))
                         if name in defined[j])
            problems.append(f"{os.path.basename(lib)} uses {name}, defined above it in {owner}")
        if len(wrong) > 10:
            problems.append(f"{os.path.basename(lib)}: {len(wrong) - 10} more")
    return problems


def report(title, problems):
    if problems:
        print(f"FAIL {title}:")
        for p in problems:
            print("  " + p)
    else:
        print(f"ok: {title}")
    return not problems


def self_test(root, libraries):
    ok = True
    with tempfile.TemporaryDirectory(prefix="footpoint-layers.") as tmp:
        for _, folders in LAYERS:
            for folder in folders:
                shutil.copytree(os.path.join(root, folder), os.path.join(tmp, folder))
        ok &= report("self-test: the copied tree is clean", check_includes(tmp))
        plants = [
            # (file, line to add, what the finding must say)
            ("core/implicit/seeding/curve_cells.hpp", '#include "implicit/solvers/implicit_curve_auto.hpp"\n',
             "seeding includes"),
            ("core/geometry/vec.hpp", '#include "compiled/compiled_geometry.hpp"\n', "geometry includes"),
            ("core/batch/batch.cpp", '#include "api.hpp"\n', "batch/cache/mesh includes"),
            ("core/parametric/solvers/gsa.cpp", "#include <nlohmann/json.hpp>\n", "belongs to server only"),
        ]
        for file, line, expected in plants:
            path = os.path.join(tmp, file)
            with open(path, encoding="utf-8") as f:
                original = f.read()
            with open(path, "w", encoding="utf-8") as f:
                f.write(line + original)
            found = check_includes(tmp)
            caught = len(found) == 1 and found[0].startswith(file + ":1:") and expected in found[0]
            ok &= report(f"self-test: {line.strip()} in {file} is caught", [] if caught else
                         [f"expected one finding '{expected}' at {file}:1, got {found}"])
            with open(path, "w", encoding="utf-8") as f:
                f.write(original)
    if libraries:
        # The libraries handed over top to bottom: every layer's use of the one below is wrong-way.
        found = check_symbols(list(reversed(libraries)))
        ok &= report("self-test: the libraries in the reverse order give wrong-way symbols",
                     [] if found else ["no finding"])
    return ok


def main(argv):
    test = argv[:1] == ["--self-test"]
    args = argv[1:] if test else argv
    if not args:
        print(__doc__)
        return 2
    root, libraries = os.path.abspath(args[0]), args[1:]
    missing = [lib for lib in libraries if not os.path.isfile(lib)]
    if missing:
        print("FAIL: libraries not built: " + " ".join(missing))
        return 1
    ok = report("includes follow the layer order", check_includes(root))
    if libraries:
        ok &= report("symbols follow the layer order", check_symbols(libraries))
    if test:
        ok &= self_test(root, libraries)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
