#!/usr/bin/python3
"""Runs the copy-paste curl examples of the documentation against a running server.

  check_examples.py [--server PATH] BASE_URL FILE...

Reads the sections the FILEs mark with <!-- NAME:begin --> and <!-- NAME:end --> (each NAME from the
first FILE that has it): results and formulas (docs/api.md, docs/formulas.md), examples (the API by
example of docs/api.md) and operations (docs/operations.md). Their ```sh blocks run in that order. The
Results section must name every member, status, location and certificate reason of a result as the
server's /openapi.yaml has them, and the Formulas section every function and operator of its
Formula schema (x-functions, x-operators). Every command of every block runs, in order, in one bash (so that `ID=$(...)`
carries over), with localhost:8080 replaced by BASE_URL. A command starting with `curl` must answer
2xx, unless a comment `# → CODE (STATUS ...)` just above it names the error code and status it
expects; its body must then be that JSON error. JSON answers must parse; /metrics, /openapi.yaml and a
mesh's OBJ must look like what they are. A `VAR=$(...)` command must set VAR. With --server, the operations
section's configuration table must list exactly the flags, variables and defaults of `PATH --help`.
"""
import json
import re
import shlex
import subprocess
import sys

import yaml

SECTIONS = ("results", "formulas", "examples", "operations")  # the order their blocks run in


def named_section(text, name):
    """The text between <!-- NAME:begin --> and <!-- NAME:end -->, or None."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    if begin not in text:
        return None
    return text.split(begin, 1)[1].split(end, 1)[0]


def check_reference_sections(results, formulas, spec):
    """What the Results and Formulas sections must name, from the served openapi.yaml."""
    problems = []
    if results is None or formulas is None:
        return ["the Results or the Formulas section is missing (<!-- results:begin --> / <!-- formulas:begin -->)"]
    schemas = spec["components"]["schemas"]
    names = {
        "result member": list(schemas["ProjectionResult"]["properties"]),
        "diagnostics member": list(schemas["Diagnostics"]["properties"]),
        "status": schemas["Status"]["enum"],
        "location": schemas["Location"]["enum"],
        "certificate member": list(schemas["Certificate"]["properties"]),
        "certificate reason": schemas["Certificate"]["properties"]["reason"]["enum"],
        "stats member": list(schemas["ProjectStats"]["properties"]),
    }
    for kind, values in names.items():
        for v in values:
            if f"`{v}`" not in results:
                problems.append(f"the Results section does not name the {kind} `{v}`")
    operators_text = formulas.replace("\\|", "|")
    for f in schemas["Formula"]["x-functions"]:
        if f"`{f}(" not in formulas:
            problems.append(f"the Formulas section does not list the function {f}")
    for o in schemas["Formula"]["x-operators"]:
        if o not in operators_text:
            problems.append(f"the Formulas section does not list the operator {o}")
    return problems


def commands(block):
    """[(expected (code, status) or None, command text)]: lines joined until their quotes close."""
    out, pending, expected = [], "", None
    for line in block.splitlines():
        if not pending:
            m = re.match(r"#\s*→\s*(\w+)\s*\((\d{3})", line.strip())
            if m:
                expected = (m.group(1), int(m.group(2)))
                continue
            if not line.strip() or line.strip().startswith("#"):
                continue
        pending += line + "\n"
        try:
            shlex.split(pending)
        except ValueError:
            continue  # an open quote: the command goes on
        if pending.rstrip().endswith("\\"):
            continue
        out.append((expected, pending.rstrip("\n")))
        pending, expected = "", None
    if pending:
        raise SystemExit(f"unterminated command in a block: {pending!r}")
    return out


def check_configuration_table(text, server):
    """The configuration table (| `--flag` | `ENV` | `default` | ...) against `server --help`."""
    help_text = subprocess.run([server, "--help"], capture_output=True, text=True, check=True).stdout
    actual = {m.group(1): (m.group(2), m.group(3))
              for m in re.finditer(r"^\s+--(\S+)\s+(FOOTPOINT_\w+)\s.*\(default ([^)]*)\)$", help_text, re.M)}
    documented = {m.group(1): (m.group(2), m.group(3))
                  for m in re.finditer(r"^\| `--([\w-]+)` \| `(\w+)` \| `([^`]*)` \|", text, re.M)}
    problems = []
    for flag in sorted(set(actual) | set(documented)):
        if flag not in documented:
            problems.append(f"configuration table lacks --{flag} {actual[flag]}")
        elif flag not in actual:
            problems.append(f"configuration table documents --{flag}, which the server does not take")
        elif actual[flag] != documented[flag]:
            problems.append(f"configuration table: --{flag} is {documented[flag]}, the server says {actual[flag]}")
    return problems, len(actual)


def main():
    args = sys.argv[1:]
    server = None
    if args[:1] == ["--server"]:
        server, args = args[1], args[2:]
    base = args[0].rstrip("/")
    host = re.sub(r"^https?://", "", base)
    found, sources = {}, []
    for path in args[1:]:
        with open(path, encoding="utf-8") as f:
            whole = f.read()
        for name in SECTIONS:
            text = named_section(whole, name)
            if text is not None and name not in found:
                found[name] = text
                if path not in sources:
                    sources.append(path)
    results, formulas = found.get("results"), found.get("formulas")
    blocks = [b for name in SECTIONS if name in found for b in re.findall(r"```sh\n(.*?)```", found[name], re.S)]
    source = ", ".join(sources)
    if not blocks:
        print("FAIL: no ```sh blocks in the sections of " + ", ".join(args[1:]))
        return 1
    if server and "operations" not in found:
        print("FAIL: no operations section (<!-- operations:begin -->) in " + ", ".join(args[1:]))
        return 1
    cmds = [c for b in blocks for c in commands(b)]
    script = ["set -uo pipefail"]
    for i, (expected, cmd) in enumerate(cmds):
        cmd = cmd.replace("localhost:8080", host)
        script.append(f"echo '@@command {i}'")
        if cmd.startswith("curl "):
            script.append("curl -w '\\n@@status %{http_code}\\n' " + cmd[len("curl "):])
        else:
            script.append(cmd)
            m = re.match(r"(\w+)=\$\(", cmd)
            if m:
                script.append(f'echo "@@var {m.group(1)}=${m.group(1)}"')
    run = subprocess.run(["bash", "-c", "\n".join(script)], capture_output=True, text=True, timeout=120)
    outputs = re.split(r"^@@command \d+\n", run.stdout, flags=re.M)[1:]
    problems = []
    if run.stderr.strip():
        problems.append(f"stderr: {run.stderr.strip()}")
    if len(outputs) != len(cmds):
        problems.append(f"ran {len(outputs)} of {len(cmds)} commands")
    for (expected, cmd), out in zip(cmds, outputs):
        first = cmd.splitlines()[0]
        var = re.search(r"^@@var (\w+)=(.*)$", out, re.M)
        if var:
            if not re.fullmatch(r"[0-9a-f]{16,64}", var.group(2)):
                problems.append(f"{first}: {var.group(1)} is {var.group(2)!r}, not a geometry id")
            continue
        m = re.search(r"\n?@@status (\d{3})\n$", out)
        if not m:
            problems.append(f"{first}: no HTTP status (curl failed?): {out[-300:]!r}")
            continue
        status, body = int(m.group(1)), out[: m.start()]
        if expected:
            code, want = expected
            try:
                got = json.loads(body).get("error", {}).get("code")
            except (json.JSONDecodeError, AttributeError):
                got = None
            if status != want or got != code:
                problems.append(f"{first}: expected {want} {code}, got {status} {body[:300]}")
            continue
        if not 200 <= status < 300:
            problems.append(f"{first}: HTTP {status}: {body[:300]}")
        elif "/metrics" in first:
            if not body.startswith("# HELP footpoint_"):
                problems.append(f"{first}: not Prometheus text")
        elif "/openapi.yaml" in first:
            try:
                doc = yaml.safe_load(body)
            except yaml.YAMLError as e:
                mark = getattr(e, "problem_mark", None)
                problems.append(f"{first}: not valid YAML: {getattr(e, 'problem', e)}"
                                + (f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""))
                continue
            if not isinstance(doc, dict) or not str(doc.get("openapi", "")).startswith("3.1"):
                problems.append(f"{first}: not an OpenAPI 3.1 document")
        elif "format=obj" in first:
            if not body.startswith("# footpoint mesh of geometry "):
                problems.append(f"{first}: not a footpoint OBJ mesh: {body[:120]!r}")
        elif status == 204:
            if body:
                problems.append(f"{first}: 204 with a body")
        else:
            try:
                doc = json.loads(body)
            except json.JSONDecodeError as e:
                problems.append(f"{first}: not JSON ({e}): {body[:200]}")
                continue
            if "error" in doc:
                problems.append(f"{first}: unexpected error {doc['error']}")
            for r in [doc.get("result")] + list(doc.get("results") or []):
                # projections' results (an evaluation's have no diagnostics)
                if r is not None and "diagnostics" in r and \
                        r["diagnostics"].get("status") not in ("converged", "beyond_max_distance"):
                    problems.append(f"{first}: a result did not converge: {r}")
    try:
        served = subprocess.run(["curl", "-sf", base + "/openapi.yaml"], capture_output=True, text=True, check=True).stdout
        problems += check_reference_sections(results, formulas, yaml.safe_load(served))
    except (subprocess.CalledProcessError, yaml.YAMLError) as e:
        problems.append(f"cannot read the served /openapi.yaml: {e}")
    settings = 0
    if server:
        table_problems, settings = check_configuration_table(found["operations"], server)
        problems += table_problems
    for q in problems:
        print("FAIL:", q)
    if problems:
        return 1
    print(f"ok: {len(cmds)} curl examples of {source} ({len(blocks)} blocks) answered as documented; "
          "the Results and Formulas sections name what /openapi.yaml does"
          + (f"; its configuration table matches --help ({settings} settings)" if server else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
