#!/usr/bin/python3
"""Static checks of footpoint's deployment files, without a Docker engine or a cluster.

  deploy/Dockerfile      stages, build/runtime packages, install prefix, non-root USER, EXPOSE,
                         HEALTHCHECK, exec-form ENTRYPOINT
  deploy/compose.yaml    parses; footpoint replicas (built from the Dockerfile, at least two) behind
                         one load balancer (nginx, deploy/nginx.conf: upstream, port, body size,
                         timeouts), Redis (the registry: password from a secret file, maxmemory +
                         allkeys-lru, no published port); port, probe path, image, env, healthchecks
  deploy/k8s/*.yaml      parses; the fields Kubernetes requires per kind (Deployment, Service,
                         HorizontalPodAutoscaler, PodDisruptionBudget, Kustomization); selectors
                         match the pod templates; the HPA targets the footpoint Deployment; the
                         registry: a Redis Deployment and Service that FOOTPOINT_REGISTRY_URL
                         names, one Secret for both, mounted as the password file
and their consistency: one port, one probe path per purpose, one image name, one user id, only
environment variables the server reads (server/config.cpp), grace periods longer than the deadline.

  --binary PATH   also check that every shared library `ldd PATH` shows is installed by the
                  runtime stage's packages (their Debian dependency closure, read with dpkg-query)
  --self-test     break each file in memory in ways the checks must catch, and fail if one passes

Prints one line per problem and exits 1 if there is any.
"""
import argparse
import json
import os
import re
import shlex
import subprocess
import sys

import yaml

PORT = 8080
LIVENESS_PATH = "/healthz"
READINESS_PATH = "/readyz"
SERVER_BINARY = "footpoint-server"
RUNTIME_LIBRARIES = {"libmuparser2v5", "libcpp-httplib0.11", "libspdlog1.10", "libfmt9", "libhiredis0.14"}
DNS_LABEL = re.compile(r"^[a-z0-9]([-a-z0-9]*[a-z0-9])?$")


class Problems:
    def __init__(self):
        self.items = []

    def add(self, where, message):
        self.items.append(f"{where}: {message}")

    def expect(self, condition, where, message):
        if not condition:
            self.add(where, message)
        return bool(condition)


def get(node, *keys):
    """node[k0][k1]... or None when a level is missing or not a mapping/list."""
    for k in keys:
        if isinstance(node, dict) and k in node:
            node = node[k]
        elif isinstance(node, list) and isinstance(k, int) and -len(node) <= k < len(node):
            node = node[k]
        else:
            return None
    return node


# ---- Dockerfile ---------------------------------------------------------------------------------

def dockerfile_instructions(text):
    """[(keyword, arguments)] with line continuations joined and comment lines dropped."""
    out, pending = [], ""
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        line = pending + line
        pending = ""
        keyword, _, rest = line.partition(" ")
        out.append((keyword.upper(), rest.strip()))
    if pending:
        keyword, _, rest = pending.strip().partition(" ")
        out.append((keyword.upper(), rest.strip()))
    return out


def apt_packages(run):
    """Packages named by `apt-get install` in a RUN command."""
    packages = []
    for segment in re.split(r"&&|;|\|\|", run):
        words = shlex.split(segment)
        if "apt-get" in words and "install" in words:
            for w in words[words.index("install") + 1:]:
                if not w.startswith("-") and "=" not in w:
                    packages.append(w)
    return packages


def parse_stages(text):
    stages = []
    for keyword, args in dockerfile_instructions(text):
        if keyword == "FROM":
            words = args.split()
            words = [w for w in words if not w.startswith("--")]
            name = words[2] if len(words) >= 3 and words[1].upper() == "AS" else None
            stages.append({"image": words[0], "name": name, "instructions": []})
        elif stages:
            stages[-1]["instructions"].append((keyword, args))
    return stages


def instructions_of(stage, keyword):
    return [args for k, args in stage["instructions"] if k == keyword]


def service_packages(install_deps_text):
    """The packages of scripts/install-deps.sh's first list, `packages=( ... )`: what building
    and running the service needs (the test tools are a second list, installed with --test)."""
    m = re.search(r"^packages=\((.*?)^\)", install_deps_text, re.M | re.S)
    if not m:
        return set()
    words = " ".join(line.split("#")[0] for line in m.group(1).splitlines()).split()
    return {w for w in words if re.fullmatch(r"[a-z0-9.+-]+", w)}


def check_dockerfile(text, texts_extra, install_deps_text, p):
    """Returns facts the other files must agree with: port, uid, health command, prefix."""
    where = "deploy/Dockerfile"
    facts = {}
    stages = parse_stages(text)
    if not p.expect(len(stages) >= 2, where, "needs a build stage and a runtime stage (multi-stage)"):
        return facts
    build, runtime = stages[0], stages[-1]
    p.expect(build["image"].startswith("debian:bookworm") or build["image"].startswith("debian:12"),
             where, f"the build stage should be Debian 12, is {build['image']}")
    p.expect(runtime["image"] in ("debian:bookworm-slim", "debian:12-slim"), where,
             f"the runtime stage should be slim Debian 12, is {runtime['image']}")
    p.expect(build["name"], where, "the build stage needs a name (FROM ... AS build)")

    build_packages = [x for r in instructions_of(build, "RUN") for x in apt_packages(r)]
    needed = service_packages(install_deps_text)
    for pkg in sorted(needed - set(build_packages)):
        p.add(where, f"build stage does not install {pkg} (scripts/install-deps.sh needs it to build)")
    build_runs = " ".join(instructions_of(build, "RUN"))
    m = re.search(r"cmake --install \S+ --prefix (\S+)", build_runs)
    if p.expect(m, where, "the build stage must `cmake --install <build> --prefix <dir>`"):
        facts["prefix"] = m.group(1)
    p.expect("CMAKE_BUILD_TYPE=Release" in build_runs, where, "the build stage must build Release")

    runtime_packages = [x for r in instructions_of(runtime, "RUN") for x in apt_packages(r)]
    facts["runtime_packages"] = runtime_packages
    for pkg in sorted(RUNTIME_LIBRARIES - set(runtime_packages)):
        p.add(where, f"runtime stage does not install {pkg}")
    for pkg in runtime_packages:
        p.expect(not pkg.endswith("-dev") and pkg not in ("build-essential", "cmake", "g++", "gcc"),
                 where, f"runtime stage installs build-only package {pkg}")
    copies = instructions_of(runtime, "COPY")
    from_build = [c for c in copies if re.match(rf"--from={re.escape(build['name'] or '')}\s", c)]
    if p.expect(from_build, where, "the runtime stage must COPY --from the build stage"):
        if "prefix" in facts:
            p.expect(any(c.split()[1].rstrip("/") == facts["prefix"].rstrip("/") for c in from_build),
                     where, f"the runtime stage must copy the install prefix {facts['prefix']}")

    users = instructions_of(runtime, "USER")
    if p.expect(users, where, "the runtime stage needs a USER (non-root)"):
        user, _, group = users[-1].partition(":")
        p.expect(user not in ("root", "0"), where, "USER must not be root")
        if p.expect(user.isdigit(), where, "USER should be numeric so that runAsNonRoot can verify it"):
            facts["uid"] = int(user)
        if group:
            p.expect(group.isdigit() and group != "0", where, "USER's group must be numeric and not root")
            if group.isdigit():
                facts["gid"] = int(group)
    exposed = [w.split("/")[0] for e in instructions_of(runtime, "EXPOSE") for w in e.split()]
    p.expect(str(PORT) in exposed, where, f"the runtime stage must EXPOSE {PORT}")

    checks = instructions_of(runtime, "HEALTHCHECK")
    if p.expect(checks, where, "the runtime stage needs a HEALTHCHECK"):
        check = checks[-1]
        p.expect(LIVENESS_PATH in check, where, f"HEALTHCHECK must probe {LIVENESS_PATH}")
        tool = "wget" if re.search(r"\bwget\b", check) else "curl" if re.search(r"\bcurl\b", check) else None
        if p.expect(tool, where, "HEALTHCHECK should use curl or wget"):
            p.expect(tool in runtime_packages, where, f"HEALTHCHECK uses {tool} but the runtime stage does not install it")
            facts["health_tool"] = tool
        port = re.search(r"127\.0\.0\.1:(?:\$\{FOOTPOINT_PORT:-)?(\d+)", check)
        p.expect(port and int(port.group(1)) == PORT, where, f"HEALTHCHECK must use port {PORT}")

    entry = instructions_of(runtime, "ENTRYPOINT")
    if p.expect(entry, where, "the runtime stage needs an ENTRYPOINT"):
        try:
            argv = json.loads(entry[-1])
        except json.JSONDecodeError:
            argv = None
        if p.expect(isinstance(argv, list) and argv and all(isinstance(a, str) for a in argv), where,
                    "ENTRYPOINT must be exec form (a JSON array) so that the server is PID 1 and gets SIGTERM"):
            p.expect(argv[0] not in ("sh", "/bin/sh", "bash", "/bin/bash"), where,
                     "ENTRYPOINT must run the server, not a shell")
            if "prefix" in facts:
                p.expect(argv[0] == f"{facts['prefix'].rstrip('/')}/bin/{SERVER_BINARY}", where,
                         f"ENTRYPOINT must run {facts['prefix']}/bin/{SERVER_BINARY}, runs {argv[0]}")
    ignore = texts_extra.get("Dockerfile.dockerignore")
    if p.expect(ignore is not None, where, "needs deploy/Dockerfile.dockerignore (keeps host build trees out of the context)"):
        allowed = {line[1:].strip().rstrip("/") for line in ignore.splitlines() if line.startswith("!")}
        p.expect("*" in [line.strip() for line in ignore.splitlines()], "deploy/Dockerfile.dockerignore",
                 "should ignore everything (*) but the sources the build copies")
        for c in instructions_of(build, "COPY"):
            for src in c.split()[:-1]:
                if not src.startswith("--"):
                    p.expect(src.rstrip("/") in allowed, "deploy/Dockerfile.dockerignore",
                             f"the build stage copies {src} but the context excludes it")
    stop = instructions_of(runtime, "STOPSIGNAL")
    p.expect(not stop or stop[-1] in ("SIGTERM", "15"), where, "STOPSIGNAL must be SIGTERM")
    p.expect(not instructions_of(runtime, "CMD") or entry, where, "CMD without ENTRYPOINT")
    return facts


# ---- environment and durations ------------------------------------------------------------------

def env_names_of_server(config_cpp_text):
    return set(re.findall(r'"(FOOTPOINT_[A-Z0-9_]+)"', config_cpp_text))


def check_env(env, known, where, p):
    """env: {name: value}. Names must be read by the server; FOOTPOINT_PORT must be the port."""
    for name, value in env.items():
        if known:
            p.expect(name in known, where, f"environment variable {name} is not read by the server (server/config.cpp)")
        p.expect(isinstance(value, str), where, f"{name}: value must be a string, is {value!r}")
    if "FOOTPOINT_PORT" in env:
        p.expect(str(env["FOOTPOINT_PORT"]) == str(PORT), where, f"FOOTPOINT_PORT must be {PORT}")
    if "FOOTPOINT_HOST" in env:
        p.expect(env["FOOTPOINT_HOST"] in ("0.0.0.0", "::"), where, "FOOTPOINT_HOST must listen on all addresses")


def deadline_seconds(env):
    return int(env.get("FOOTPOINT_DEADLINE_MS", "30000")) / 1000.0


def compose_duration(text):
    total = 0.0
    for number, unit in re.findall(r"(\d+(?:\.\d+)?)(ms|s|m|h)", str(text)):
        total += float(number) * {"ms": 0.001, "s": 1, "m": 60, "h": 3600}[unit]
    return total


# ---- compose ------------------------------------------------------------------------------------

def compose_role(svc):
    """footpoint (built from the Dockerfile), redis (the registry) or lb (the load balancer)."""
    if isinstance(get(svc, "build"), dict):
        return "footpoint"
    image = str(get(svc, "image") or "")
    if image.startswith("redis:"):
        return "redis"
    if image.startswith("nginx:"):
        return "lb"
    return None


def registry_url_parts(url):
    """(host, port) of redis://[user@]host[:port][/db], or None."""
    m = re.match(r"^redis://(?:[^:@/]+@)?([^:/@]+)(?::(\d+))?(?:/\d*)?$", str(url or ""))
    return (m.group(1), int(m.group(2) or 6379)) if m else None


def nginx_directives(text):
    """[(name, [args])] of an nginx.conf, comments dropped (enough for the checks here)."""
    text = re.sub(r"#[^\n]*", "", text)
    return [(words[0], words[1:]) for words in (d.split() for d in re.split(r"[;{}]", text)) if words]


def nginx_size(text):
    m = re.match(r"^(\d+)([kKmMgG]?)$", text)
    return int(m.group(1)) * {"": 1, "k": 1 << 10, "m": 1 << 20, "g": 1 << 30}[m.group(2).lower()] if m else None


def nginx_seconds(text):
    m = re.match(r"^(\d+)(ms|s|m)?$", text)
    return int(m.group(1)) * {"ms": 0.001, "s": 1, "m": 60, None: 1}[m.group(2)] if m else None


def check_common_service(svc, w, p):
    test = get(svc, "healthcheck", "test")
    p.expect(test, w, "needs a healthcheck")
    signal = get(svc, "stop_signal")
    p.expect(signal in (None, "SIGTERM"), w, "stop_signal must be SIGTERM")
    user = get(svc, "user")
    p.expect(user is None or str(user).split(":")[0] not in ("0", "root"), w, "must not run as root")
    return " ".join(test) if isinstance(test, list) else str(test or "")


def published_targets(svc):
    targets = []
    for port in get(svc, "ports") or []:
        if isinstance(port, dict):
            targets.append(int(port.get("target", -1)))
        else:
            targets.append(int(str(port).split(":")[-1].split("/")[0]))
    return targets


def service_env(svc):
    env = get(svc, "environment") or {}
    if isinstance(env, list):
        env = dict(e.split("=", 1) for e in env)
    return env


def check_compose(doc, deploy_dir, known_env, facts, p, texts):
    where = "deploy/compose.yaml"
    services = get(doc, "services")
    if not p.expect(isinstance(services, dict) and services, where, "needs a services mapping"):
        return
    roles = {}
    for name, svc in services.items():
        role = compose_role(svc)
        if p.expect(role, f"{where}: services.{name}",
                    "unexpected service (neither built from deploy/Dockerfile, nor redis:, nor nginx:)"):
            roles.setdefault(role, []).append(name)
    for role in ("footpoint", "redis", "lb"):
        p.expect(len(roles.get(role, [])) == 1, where, f"needs exactly one {role} service")
    secrets = get(doc, "secrets") or {}
    for name, svc in services.items():
        w = f"{where}: services.{name}"
        role = compose_role(svc)
        health = check_common_service(svc, w, p)
        image = get(svc, "image")
        if role == "footpoint":
            build = get(svc, "build")
            context = os.path.normpath(os.path.join(deploy_dir, str(build.get("context", "."))))
            dockerfile = os.path.join(context, str(build.get("dockerfile", "Dockerfile")))
            p.expect(os.path.samefile(dockerfile, os.path.join(deploy_dir, "Dockerfile"))
                     if os.path.exists(dockerfile) else False, w, "build must use deploy/Dockerfile")
            p.expect(os.path.exists(os.path.join(context, "CMakeLists.txt")), w,
                     "build.context must be the repository root")
            if p.expect(isinstance(image, str), w, "needs an image name"):
                facts.setdefault("images", []).append((w, image))
            replicas = get(svc, "deploy", "replicas")
            p.expect(isinstance(replicas, int) and replicas >= 2, w, "needs deploy.replicas >= 2 (scale-out)")
            p.expect(not get(svc, "ports"), w,
                     "must not publish host ports (replicas would clash): the load balancer publishes")
            env = service_env(svc)
            check_env(env, known_env, w, p)
            p.expect(LIVENESS_PATH in health and f":{PORT}/" in health, w, f"healthcheck must probe :{PORT}{LIVENESS_PATH}")
            if "health_tool" in facts:
                p.expect(facts["health_tool"] in health, w, f"healthcheck must use {facts['health_tool']} (installed in the image)")
            grace = get(svc, "stop_grace_period")
            p.expect(grace is not None and compose_duration(grace) > deadline_seconds(env), w,
                     "stop_grace_period must exceed the request deadline (FOOTPOINT_DEADLINE_MS)")
            p.expect("FOOTPOINT_REGISTRY_PASSWORD" not in env, w,
                     "no password in the environment: FOOTPOINT_REGISTRY_PASSWORD_FILE from a secret")
            url = registry_url_parts(env.get("FOOTPOINT_REGISTRY_URL"))
            if p.expect(url, w, "FOOTPOINT_REGISTRY_URL must be redis://<the redis service>:6379/<db>"):
                p.expect(url[0] in roles.get("redis", []) and url[1] == 6379, w,
                         f"FOOTPOINT_REGISTRY_URL names {url[0]}:{url[1]}, not the redis service on 6379")
            password_file = str(env.get("FOOTPOINT_REGISTRY_PASSWORD_FILE", ""))
            secret = password_file[len("/run/secrets/"):] if password_file.startswith("/run/secrets/") else None
            if p.expect(secret, w, "FOOTPOINT_REGISTRY_PASSWORD_FILE must be /run/secrets/<secret>"):
                p.expect(secret in (get(svc, "secrets") or []) and secret in secrets, w,
                         f"the secret {secret} must be declared and given to the service")
                facts["compose_secret"] = secret
            facts["compose_footpoint"] = name
            facts["compose_env"] = env
        elif role == "redis":
            command = " ".join(get(svc, "command") or []) if isinstance(get(svc, "command"), list) else str(get(svc, "command") or "")
            p.expect("--maxmemory " in command and "allkeys-lru" in command, w,
                     "Redis must be bounded: --maxmemory with --maxmemory-policy allkeys-lru")
            p.expect("requirepass" in command, w, "Redis needs a password (requirepass)")
            p.expect(not get(svc, "ports"), w, "must not publish Redis on the host")
            p.expect("redis-cli" in health and "ping" in health.lower(), w, "healthcheck must be redis-cli ping")
            facts["compose_redis_secrets"] = get(svc, "secrets") or []
            facts["compose_redis_command"] = command
        elif role == "lb":
            p.expect(PORT in published_targets(svc) and any(str(x).startswith(f"{PORT}:") for x in get(svc, "ports") or []),
                     w, f"the load balancer must publish {PORT}:{PORT}, the one address")
            p.expect(LIVENESS_PATH in health, w, f"healthcheck must probe {LIVENESS_PATH} through the balancer")
            mounts = [str(v).split(":") for v in get(svc, "volumes") or []]
            conf = [m[0] for m in mounts if len(m) >= 2 and m[1] == "/etc/nginx/nginx.conf"]
            if p.expect(conf, w, "must mount deploy/nginx.conf at /etc/nginx/nginx.conf"):
                facts["nginx_conf"] = os.path.normpath(conf[0])
            p.expect(roles.get("footpoint", [None])[0] in (get(svc, "depends_on") or {}), w,
                     "must depend on the footpoint service")
    secret = facts.get("compose_secret")
    if secret and "compose_redis_secrets" in facts:
        p.expect(secret in facts["compose_redis_secrets"] and f"/run/secrets/{secret}" in facts["compose_redis_command"],
                 where, f"Redis must take its password from the same secret ({secret}) as the replicas")
    if "nginx_conf" in facts:
        check_nginx(texts.get(facts["nginx_conf"]), facts, p)


def check_nginx(text, facts, p):
    where = f"deploy/{facts['nginx_conf']}"
    if not p.expect(text is not None, where, "does not exist (mounted by the lb service)"):
        return
    d = nginx_directives(text)
    servers = [a[0] for n, a in d if n == "server" and a]
    target = f"{facts.get('compose_footpoint')}:{PORT}"
    p.expect(target in servers, where, f"the upstream must be {target} (the replicas' service)")
    p.expect(["8080"] in [a for n, a in d if n == "listen"], where, f"must listen on {PORT}")
    env = facts.get("compose_env", {})
    sizes = [nginx_size(a[0]) for n, a in d if n == "client_max_body_size"]
    limit = int(env.get("FOOTPOINT_MAX_BODY_BYTES", 16 << 20))
    p.expect(sizes and sizes[0] and sizes[0] >= limit, where,
             f"client_max_body_size must admit FOOTPOINT_MAX_BODY_BYTES ({limit})")
    reads = [nginx_seconds(a[0]) for n, a in d if n == "proxy_read_timeout"]
    p.expect(reads and reads[0] and reads[0] > deadline_seconds(env), where,
             "proxy_read_timeout must exceed the request deadline (FOOTPOINT_DEADLINE_MS)")
    p.expect(any(n == "proxy_pass" for n, _ in d), where, "needs a proxy_pass to the upstream")


# ---- Kubernetes ---------------------------------------------------------------------------------

def check_metadata(doc, where, p):
    name = get(doc, "metadata", "name")
    p.expect(isinstance(name, str) and DNS_LABEL.match(name) and len(name) <= 63, where,
             f"metadata.name must be a DNS-1123 label, is {name!r}")
    labels = get(doc, "metadata", "labels") or {}
    for k, v in labels.items():
        p.expect(isinstance(v, str), where, f"label {k} must be a string")


def selector_matches(selector, labels):
    return isinstance(selector, dict) and selector and isinstance(labels, dict) and all(
        labels.get(k) == v for k, v in selector.items())


def check_probe(container, probe, path, ports, where, p):
    spec = get(container, probe)
    if not p.expect(isinstance(spec, dict), where, f"needs a {probe}"):
        return
    http = get(spec, "httpGet")
    if p.expect(isinstance(http, dict), where, f"{probe} must be an httpGet"):
        p.expect(http.get("path") == path, where, f"{probe} must probe {path}, probes {http.get('path')}")
        port = http.get("port")
        p.expect(port in ports or port == PORT, where, f"{probe} port {port!r} is not the container's port")


def check_deployment(doc, where, known_env, facts, p):
    spec = get(doc, "spec")
    if not p.expect(isinstance(spec, dict), where, "needs spec"):
        return
    selector = get(spec, "selector", "matchLabels")
    labels = get(spec, "template", "metadata", "labels")
    p.expect(selector_matches(selector, labels), where,
             "spec.selector.matchLabels must be non-empty and match spec.template.metadata.labels")
    facts["pod_labels"] = labels or {}
    pod = get(spec, "template", "spec")
    containers = get(pod, "containers")
    if not p.expect(isinstance(containers, list) and containers, where, "needs spec.template.spec.containers"):
        return
    grace = get(pod, "terminationGracePeriodSeconds")
    uid = get(pod, "securityContext", "runAsUser")
    p.expect(get(pod, "securityContext", "runAsNonRoot") is True, where, "pod securityContext.runAsNonRoot must be true")
    if "uid" in facts:
        p.expect(uid == facts["uid"], where, f"runAsUser {uid} is not the image's USER {facts['uid']}")
    if "gid" in facts:
        gid = get(pod, "securityContext", "runAsGroup")
        p.expect(gid in (None, facts["gid"]), where, f"runAsGroup {gid} is not the image's group {facts['gid']}")
    for c in containers:
        w = f"{where}: container {get(c, 'name')}"
        p.expect(isinstance(get(c, "name"), str) and DNS_LABEL.match(get(c, "name")), w, "needs a DNS-1123 name")
        image = get(c, "image")
        if p.expect(isinstance(image, str) and image, w, "needs an image"):
            facts.setdefault("images", []).append((w, image))
        ports = {}
        for port in get(c, "ports") or []:
            if p.expect(isinstance(get(port, "containerPort"), int), w, "ports[].containerPort must be an integer"):
                if "name" in port:
                    ports[port["name"]] = port["containerPort"]
                ports.setdefault(None, port["containerPort"])
        p.expect(PORT in ports.values(), w, f"must declare containerPort {PORT}")
        facts["container_ports"] = ports
        check_probe(c, "livenessProbe", LIVENESS_PATH, ports, w, p)
        check_probe(c, "readinessProbe", READINESS_PATH, ports, w, p)
        for kind in ("requests", "limits"):
            for res in ("cpu", "memory"):
                p.expect(get(c, "resources", kind, res) is not None, w, f"needs resources.{kind}.{res}")
        env = {}
        for e in get(c, "env") or []:
            if p.expect(isinstance(get(e, "name"), str), w, "env[].name is required"):
                env[e["name"]] = e.get("value")
        check_env(env, known_env, w, p)
        check_memory_budget(env, get(c, "resources", "limits", "memory"), w, p)
        p.expect(isinstance(grace, int) and grace > deadline_seconds(env), where,
                 "terminationGracePeriodSeconds must exceed the request deadline (FOOTPOINT_DEADLINE_MS)")
        p.expect(get(c, "securityContext", "allowPrivilegeEscalation") is False, w,
                 "securityContext.allowPrivilegeEscalation must be false")
        p.expect("FOOTPOINT_REGISTRY_PASSWORD" not in env, w,
                 "no password in the environment: FOOTPOINT_REGISTRY_PASSWORD_FILE from a Secret volume")
        facts["registry_url"] = (w, env.get("FOOTPOINT_REGISTRY_URL"))
        facts["registry_password"] = (w, env.get("FOOTPOINT_REGISTRY_PASSWORD_FILE"),
                                      secret_mounts(pod, c))
    facts["deployment"] = get(doc, "metadata", "name")


# What a replica holds besides the requests in flight (docs/operations.md, Memory): the process at
# rest, the geometry cache and one geometry's compile.
BASELINE_BYTES = 128 << 20


def check_memory_budget(env, limit_text, where, p):
    """The memory limit holds the process at rest, the cache, one compile and the in-flight budget."""
    limit = redis_memory_bytes(limit_text)
    budget = int(env.get("FOOTPOINT_MAX_INFLIGHT_BYTES") or 0)
    if limit is None or budget == 0:
        return  # 0: the server derives the budget from the limit itself
    cache = int(env.get("FOOTPOINT_CACHE_BYTES") or 256 << 20)
    geometry = int(env.get("FOOTPOINT_MAX_GEOMETRY_BYTES") or 0) or cache // 4
    needed = BASELINE_BYTES + cache + geometry + budget
    p.expect(needed <= limit, where,
             f"resources.limits.memory ({limit_text}) is below what the replica may hold: 128 MiB + "
             f"FOOTPOINT_CACHE_BYTES + one geometry + FOOTPOINT_MAX_INFLIGHT_BYTES = {needed} bytes")


def secret_mounts(pod, container):
    """{mountPath: secretName} of the container's volume mounts that come from a Secret."""
    secrets = {v.get("name"): get(v, "secret", "secretName") for v in get(pod, "volumes") or []
               if get(v, "secret", "secretName")}
    return {m.get("mountPath"): secrets[m.get("name")] for m in get(container, "volumeMounts") or []
            if m.get("name") in secrets}


def redis_memory_bytes(text):
    """Bytes of a Redis size (200mb, 1gb) or a Kubernetes quantity (256Mi, 1Gi)."""
    m = re.match(r"^(\d+)(b|kb|mb|gb|Ki|Mi|Gi|k|M|G)?$", str(text))
    if not m:
        return None
    unit = {"b": 1, "kb": 1 << 10, "mb": 1 << 20, "gb": 1 << 30, "Ki": 1 << 10, "Mi": 1 << 20, "Gi": 1 << 30,
            "k": 1000, "M": 10 ** 6, "G": 10 ** 9, None: 1}[m.group(2)]
    return int(m.group(1)) * unit


def check_redis_deployment(doc, where, facts, p):
    spec = get(doc, "spec") or {}
    labels = get(spec, "template", "metadata", "labels")
    p.expect(selector_matches(get(spec, "selector", "matchLabels"), labels), where,
             "spec.selector.matchLabels must be non-empty and match spec.template.metadata.labels")
    facts["redis_labels"] = labels or {}
    pod = get(spec, "template", "spec") or {}
    p.expect(get(spec, "replicas") in (None, 1), where, "one Redis: every footpoint pod must see the same registry")
    p.expect(get(pod, "securityContext", "runAsNonRoot") is True, where, "pod securityContext.runAsNonRoot must be true")
    for c in get(pod, "containers") or []:
        w = f"{where}: container {get(c, 'name')}"
        ports = {port.get("name"): port.get("containerPort") for port in get(c, "ports") or []}
        p.expect(6379 in ports.values(), w, "must declare containerPort 6379")
        facts["redis_ports"] = ports
        for probe in ("livenessProbe", "readinessProbe"):
            p.expect(isinstance(get(c, probe), dict), w, f"needs a {probe}")
        for kind in ("requests", "limits"):
            for res in ("cpu", "memory"):
                p.expect(get(c, "resources", kind, res) is not None, w, f"needs resources.{kind}.{res}")
        for e in get(c, "env") or []:
            p.expect(isinstance(e.get("value"), str) or get(e, "valueFrom", "secretKeyRef"), w,
                     f"env {e.get('name')}: a string or a secretKeyRef")
        command = " ".join(str(x) for x in (get(c, "command") or []) + (get(c, "args") or []))
        maxmemory = re.search(r"--maxmemory (\S+)", command)
        if p.expect(maxmemory and "--maxmemory-policy allkeys-lru" in command, w,
                    "Redis must be bounded: --maxmemory with --maxmemory-policy allkeys-lru"):
            limit = redis_memory_bytes(get(c, "resources", "limits", "memory"))
            p.expect(limit and redis_memory_bytes(maxmemory.group(1)) < limit, w,
                     "--maxmemory must stay below the container's memory limit")
        mounts = secret_mounts(pod, c)
        from_secret = [path for path in mounts if f"{path.rstrip('/')}/" in command]
        p.expect("requirepass" in command and from_secret, w,
                 "Redis needs a password (requirepass) read from a mounted Secret, not written in the manifest")
        facts["redis_secrets"] = {mounts[path] for path in from_secret}
        p.expect(get(c, "securityContext", "allowPrivilegeEscalation") is False, w,
                 "securityContext.allowPrivilegeEscalation must be false")


def check_service(doc, where, facts, p):
    selector = get(doc, "spec", "selector")
    p.expect(isinstance(selector, dict) and selector, where, "needs spec.selector")
    facts.setdefault("pending", []).append(("service", where, doc))
    ports = get(doc, "spec", "ports")
    if p.expect(isinstance(ports, list) and ports, where, "needs spec.ports"):
        for port in ports:
            p.expect(isinstance(get(port, "port"), int), where, "ports[].port must be an integer")


def check_hpa(doc, where, facts, p):
    spec = get(doc, "spec") or {}
    ref = get(spec, "scaleTargetRef") or {}
    p.expect(ref.get("apiVersion") == "apps/v1" and ref.get("kind") == "Deployment", where,
             "scaleTargetRef must be an apps/v1 Deployment")
    facts.setdefault("pending", []).append(("hpa", where, doc))
    lo, hi = spec.get("minReplicas", 1), spec.get("maxReplicas")
    p.expect(isinstance(hi, int) and isinstance(lo, int) and 1 <= lo <= hi, where,
             "needs 1 <= minReplicas <= maxReplicas")
    facts["min_replicas"] = lo
    cpu = [m for m in spec.get("metrics") or []
           if m.get("type") == "Resource" and get(m, "resource", "name") == "cpu"]
    if p.expect(cpu, where, "needs a Resource metric on cpu"):
        target = get(cpu[0], "resource", "target") or {}
        p.expect(target.get("type") == "Utilization" and isinstance(target.get("averageUtilization"), int),
                 where, "the cpu target must be a Utilization with an integer averageUtilization")


def check_pdb(doc, where, facts, p):
    spec = get(doc, "spec") or {}
    p.expect(("minAvailable" in spec) != ("maxUnavailable" in spec), where,
             "needs exactly one of minAvailable and maxUnavailable")
    p.expect(isinstance(get(spec, "selector", "matchLabels"), dict), where, "needs spec.selector.matchLabels")
    facts.setdefault("pending", []).append(("pdb", where, doc))


def check_kustomization(doc, where, k8s_files, p):
    resources = get(doc, "resources") or []
    others = sorted(f for f in k8s_files if f != os.path.basename(where))
    p.expect(sorted(resources) == others, where, f"resources {sorted(resources)} must list {others}")


KINDS = {
    "Deployment": "apps/v1",
    "Service": "v1",
    "HorizontalPodAutoscaler": "autoscaling/v2",
    "PodDisruptionBudget": "policy/v1",
    "Kustomization": "kustomize.config.k8s.io/v1beta1",
}


def check_k8s(docs_by_file, known_env, facts, p):
    seen = {}
    for name, docs in sorted(docs_by_file.items()):
        for i, doc in enumerate(docs):
            where = f"deploy/k8s/{name}" + (f"[{i}]" if len(docs) > 1 else "")
            if not p.expect(isinstance(doc, dict), where, "must be a mapping"):
                continue
            kind = doc.get("kind")
            if not p.expect(kind in KINDS, where, f"unexpected kind {kind!r}"):
                continue
            p.expect(doc.get("apiVersion") == KINDS[kind], where, f"{kind} must be apiVersion {KINDS[kind]}")
            seen.setdefault(kind, []).append(where)
            if kind == "Kustomization":
                check_kustomization(doc, where, list(docs_by_file), p)
                continue
            check_metadata(doc, where, p)
            if kind == "Deployment":
                images = [str(get(c, "image") or "") for c in get(doc, "spec", "template", "spec", "containers") or []]
                if any(i.startswith("redis:") for i in images):
                    seen.setdefault("redis Deployment", []).append(where)
                    check_redis_deployment(doc, where, facts, p)
                else:
                    seen.setdefault("footpoint Deployment", []).append(where)
                    check_deployment(doc, where, known_env, facts, p)
            elif kind == "Service":
                check_service(doc, where, facts, p)
            elif kind == "HorizontalPodAutoscaler":
                check_hpa(doc, where, facts, p)
            elif kind == "PodDisruptionBudget":
                check_pdb(doc, where, facts, p)
    for kind, n in (("footpoint Deployment", 1), ("redis Deployment", 1), ("Service", 2),
                    ("HorizontalPodAutoscaler", 1), ("PodDisruptionBudget", 1)):
        p.expect(len(seen.get(kind, [])) == n, "deploy/k8s", f"needs exactly {n} {kind}")
    # Cross-references, now that the Deployment is known.
    labels = facts.get("pod_labels", {})
    ports = facts.get("container_ports", {})
    redis_labels, redis_ports = facts.get("redis_labels", {}), facts.get("redis_ports", {})
    redis_services = {}
    for what, where, doc in facts.get("pending", []):
        if what == "service" and selector_matches(get(doc, "spec", "selector"), redis_labels):
            for port in get(doc, "spec", "ports") or []:
                target = port.get("targetPort", port.get("port"))
                p.expect(target in redis_ports or target == 6379, where, f"targetPort {target!r} is not Redis's port")
                redis_services[get(doc, "metadata", "name")] = port.get("port")
        elif what == "service":
            p.expect(selector_matches(get(doc, "spec", "selector"), labels), where,
                     "spec.selector must select the Deployment's pods")
            for port in get(doc, "spec", "ports") or []:
                target = port.get("targetPort", port.get("port"))
                p.expect(target in ports or target == PORT, where, f"targetPort {target!r} is not the container's port")
                p.expect(port.get("port") == PORT, where, f"the Service port should be {PORT} like everywhere else")
        elif what == "hpa":
            p.expect(get(doc, "spec", "scaleTargetRef", "name") == facts.get("deployment"), where,
                     "scaleTargetRef.name must name the Deployment")
        elif what == "pdb":
            p.expect(selector_matches(get(doc, "spec", "selector", "matchLabels"), labels), where,
                     "spec.selector must select the Deployment's pods")
            lo = get(doc, "spec", "minAvailable")
            if isinstance(lo, int):
                p.expect(lo < facts.get("min_replicas", 1), where,
                         "minAvailable must be below the HPA's minReplicas, or no node can ever be drained")
    if "registry_url" in facts:
        w, url = facts["registry_url"]
        parts = registry_url_parts(url)
        if p.expect(parts, w, "FOOTPOINT_REGISTRY_URL must be redis://<the Redis Service>:<port>/<db>"):
            p.expect(redis_services.get(parts[0]) == parts[1], w,
                     f"FOOTPOINT_REGISTRY_URL names {parts[0]}:{parts[1]}, not the Redis Service "
                     f"({', '.join(f'{k}:{v}' for k, v in redis_services.items()) or 'none'})")
    if "registry_password" in facts:
        w, path, mounts = facts["registry_password"]
        secret = next((name for mount, name in mounts.items() if path and path.startswith(f"{mount.rstrip('/')}/")), None)
        if p.expect(secret, w, "FOOTPOINT_REGISTRY_PASSWORD_FILE must be a file of a mounted Secret volume"):
            p.expect(secret in facts.get("redis_secrets", set()), w,
                     f"the password Secret {secret} is not the one Redis reads")


# ---- all files ----------------------------------------------------------------------------------

def check_texts(texts, deploy_dir, install_deps_text, config_cpp_text):
    """texts: {relative path under deploy/: content}. Returns the list of problems and the facts."""
    p = Problems()
    facts = check_dockerfile(texts.get("Dockerfile", ""), texts, install_deps_text, p)
    known_env = env_names_of_server(config_cpp_text) if config_cpp_text else set()
    k8s_docs = {}
    for rel, text in sorted(texts.items()):
        if not rel.endswith((".yaml", ".yml")):
            continue
        try:
            docs = [d for d in yaml.safe_load_all(text) if d is not None]
        except yaml.YAMLError as e:
            p.add(f"deploy/{rel}", f"does not parse: {e}")
            continue
        if rel.startswith("k8s/"):
            k8s_docs[rel[len("k8s/"):]] = docs
        elif rel in ("compose.yaml", "compose.yml"):
            p.expect(len(docs) == 1, f"deploy/{rel}", "must hold one document")
            if docs:
                check_compose(docs[0], deploy_dir, known_env, facts, p, texts)
        else:
            p.add(f"deploy/{rel}", "unexpected YAML file (not compose, not k8s)")
    p.expect("compose.yaml" in texts, "deploy", "needs compose.yaml")
    check_k8s(k8s_docs, known_env, facts, p)
    images = facts.get("images", [])
    for where, image in images:
        p.expect(image.split("@")[0].split("/")[-1] == images[0][1].split("@")[0].split("/")[-1], where,
                 f"image {image} differs from {images[0][1]} ({images[0][0]})")
    return p.items, facts


def read_texts(deploy_dir):
    texts = {}
    for root, _, files in os.walk(deploy_dir):
        for f in files:
            if f.endswith((".yaml", ".yml", ".conf")) or f in ("Dockerfile", "Dockerfile.dockerignore"):
                path = os.path.join(root, f)
                with open(path, encoding="utf-8") as fh:
                    texts[os.path.relpath(path, deploy_dir)] = fh.read()
    return texts


# ---- the runtime libraries of a built binary ------------------------------------------------------

def package_of(path):
    candidates = [path, os.path.realpath(path)]
    for c in list(candidates):
        candidates.append(c[4:] if c.startswith("/usr/") else "/usr" + c)
    for c in candidates:
        r = subprocess.run(["dpkg-query", "-S", c], capture_output=True, text=True)
        if r.returncode == 0:
            return r.stdout.split(":")[0].strip()
    return None


def dependency_closure(packages):
    done, todo = set(), list(packages)
    while todo:
        pkg = todo.pop()
        if pkg in done:
            continue
        done.add(pkg)
        r = subprocess.run(["dpkg-query", "-W", "-f=${Depends},${Pre-Depends}", pkg], capture_output=True, text=True)
        for alternative in re.split(r"[,|]", r.stdout):
            name = alternative.strip().split(" ")[0].split(":")[0]
            if name:
                todo.append(name)
    return done


def check_binary(binary, runtime_packages):
    problems = []
    if not os.path.exists("/usr/bin/dpkg-query"):
        return [f"{binary}: dpkg-query not found: cannot map libraries to packages"]
    out = subprocess.run(["ldd", binary], capture_output=True, text=True, check=True).stdout
    closure = dependency_closure(runtime_packages)
    for line in out.splitlines():
        m = re.match(r"\s*(\S+)\s+=>\s+(\S+)", line) or re.match(r"\s*(/\S+)\s+\(", line)
        if not m:
            continue
        path = m.group(2) if m.lastindex == 2 else m.group(1)
        if path == "not":
            problems.append(f"{binary}: {m.group(1)} not found")
            continue
        pkg = package_of(path)
        if pkg is None:
            problems.append(f"{binary}: {path} belongs to no Debian package")
        elif pkg not in closure:
            problems.append(f"deploy/Dockerfile: runtime stage lacks {pkg} (for {path}, linked by {binary})")
    return problems


# ---- self-test: the checks must catch broken files ----------------------------------------------

MUTATIONS = [
    ("Dockerfile", "USER 10001:10001", "USER root", "USER must not be root"),
    ("Dockerfile", "USER 10001:10001\n", "", "needs a USER"),
    ("Dockerfile", "EXPOSE 8080", "EXPOSE 9090", "EXPOSE 8080"),
    ("Dockerfile", "HEALTHCHECK --interval", "#HEALTHCHECK --interval", "needs a HEALTHCHECK"),
    ("Dockerfile", 'ENTRYPOINT ["/opt/footpoint/bin/footpoint-server"]',
     "ENTRYPOINT /opt/footpoint/bin/footpoint-server", "exec form"),
    ("Dockerfile", "FROM debian:bookworm-slim AS runtime", "FROM debian:bookworm AS runtime", "slim"),
    ("Dockerfile", " libfmt9", " libfmt-dev", "build-only package"),
    ("Dockerfile", " libnanoflann-dev", "", "libnanoflann-dev"),
    ("Dockerfile.dockerignore", "!server/\n", "", "copies server/"),
    ("compose.yaml", '"8080:8080"', '"8080:9090"', "must publish 8080:8080"),
    ("compose.yaml", "      replicas: 2", "      replicas: 1", "deploy.replicas >= 2"),
    ("compose.yaml", '    expose:\n      - "8080"', '    ports:\n      - "8080:8080"', "must not publish host ports"),
    ("compose.yaml", "redis://redis:6379/0", "redis://cache:6379/0", "not the redis service"),
    ("compose.yaml", "FOOTPOINT_REGISTRY_PASSWORD_FILE: /run/secrets/registry_password",
     'FOOTPOINT_REGISTRY_PASSWORD: "hunter2"', "no password in the environment"),
    ("compose.yaml", "--maxmemory-policy allkeys-lru", "--maxmemory-policy noeviction", "allkeys-lru"),
    ("compose.yaml", "    secrets:\n      - registry_password\n    healthcheck:\n      test: [\"CMD-SHELL\", \"REDIS",
     "    healthcheck:\n      test: [\"CMD-SHELL\", \"REDIS", "same secret"),
    ("compose.yaml", "redis-cli ping", "true", "redis-cli ping"),
    ("compose.yaml", "      - ./nginx.conf:/etc/nginx/nginx.conf:ro", "      - ./nginx.conf:/etc/nginx/other.conf:ro",
     "must mount deploy/nginx.conf"),
    ("compose.yaml", "    image: nginx:stable-bookworm", "    image: traefik:v3", "unexpected service"),
    ("nginx.conf", "server footpoint:8080;", "server footpoint:9090;", "upstream must be footpoint:8080"),
    ("nginx.conf", "client_max_body_size 16m;", "client_max_body_size 1m;", "client_max_body_size"),
    ("nginx.conf", "proxy_read_timeout 40s;", "proxy_read_timeout 10s;", "proxy_read_timeout"),
    ("k8s/redis.yaml", "--maxmemory 200mb", "--maxmemory 300mb", "below the container's memory limit"),
    ("k8s/redis.yaml", "--maxmemory-policy allkeys-lru", "--maxmemory-policy noeviction", "allkeys-lru"),
    ("k8s/redis.yaml", '"$(cat /var/run/secrets/footpoint-registry/password)"', "hunter2", "read from a mounted Secret"),
    ("k8s/redis.yaml", "  replicas: 1\n", "  replicas: 3\n", "one Redis"),
    ("k8s/redis.yaml", "    app.kubernetes.io/component: registry\n  ports:", "    app.kubernetes.io/component: cache\n  ports:",
     "select the Deployment's pods"),
    ("k8s/deployment.yaml", "redis://footpoint-redis:6379/0", "redis://redis:6379/0", "not the Redis Service"),
    ("k8s/deployment.yaml", "              value: /var/run/secrets/footpoint-registry/password",
     "              value: /etc/footpoint/password", "mounted Secret volume"),
    ("k8s/deployment.yaml", "            secretName: footpoint-registry", "            secretName: other-secret",
     "not the one Redis reads"),
    ("k8s/kustomization.yaml", "  - redis.yaml\n", "", "must list"),
    ("compose.yaml", "stop_grace_period: 40s", "stop_grace_period: 10s", "stop_grace_period"),
    ("compose.yaml", "FOOTPOINT_MAX_POINTS", "FOOTPOINT_MAXPOINTS", "not read by the server"),
    ("compose.yaml", "image: footpoint:", "image: other:", "differs from"),
    ("k8s/deployment.yaml", "path: /readyz", "path: /ready", "readinessProbe must probe /readyz"),
    ("k8s/deployment.yaml", "path: /healthz", "path: /health", "livenessProbe must probe /healthz"),
    ("k8s/deployment.yaml", "containerPort: 8080", "containerPort: 8081", "containerPort 8080"),
    ("k8s/deployment.yaml", "runAsUser: 10001", "runAsUser: 1000", "is not the image's USER"),
    ("k8s/deployment.yaml", "runAsGroup: 10001", "runAsGroup: 0", "is not the image's group"),
    ("k8s/deployment.yaml", "terminationGracePeriodSeconds: 45", "terminationGracePeriodSeconds: 20",
     "terminationGracePeriodSeconds"),
    ("k8s/deployment.yaml", "  selector:\n    matchLabels:\n      app.kubernetes.io/name: footpoint",
     "  selector:\n    matchLabels:\n      app.kubernetes.io/name: footprint", "match spec.template"),
    ("k8s/deployment.yaml", "              memory: 2Gi", "", "resources.limits.memory"),
    ("k8s/deployment.yaml", "              memory: 2Gi", "              memory: 1Gi", "below what the replica may hold"),
    ("k8s/deployment.yaml", '"1677721600"', '"1677721601"', "below what the replica may hold"),
    ("k8s/deployment.yaml", "name: footpoint\n  labels", "name: Foot_point\n  labels", "DNS-1123"),
    ("k8s/service.yaml", "targetPort: http", "targetPort: web", "targetPort"),
    ("k8s/service.yaml", "component: server\n  ports", "component: client\n  ports", "select the Deployment"),
    ("k8s/hpa.yaml", "    name: footpoint\n  minReplicas", "    name: footpoint-x\n  minReplicas",
     "scaleTargetRef.name"),
    ("k8s/hpa.yaml", "autoscaling/v2", "autoscaling/v1", "apiVersion autoscaling/v2"),
    ("k8s/hpa.yaml", "name: cpu", "name: memory", "Resource metric on cpu"),
    ("k8s/pdb.yaml", "maxUnavailable: 1", "minAvailable: 2", "below the HPA's minReplicas"),
    ("k8s/pdb.yaml", "      app.kubernetes.io/component: server", "      app.kubernetes.io/component: db",
     "select the Deployment"),
    ("k8s/pdb.yaml", "kind: PodDisruptionBudget", "kind: PodDisruptionBudget\n  bad: [", "does not parse"),
    ("k8s/kustomization.yaml", "  - pdb.yaml\n", "", "must list"),
]


def self_test(texts, deploy_dir, install_deps_text, config_cpp_text):
    failures = []
    for rel, old, new, expected in MUTATIONS:
        if rel not in texts or old not in texts[rel]:
            failures.append(f"self-test: {rel} no longer contains {old!r}: update MUTATIONS")
            continue
        broken = dict(texts)
        broken[rel] = texts[rel].replace(old, new, 1)
        problems, _ = check_texts(broken, deploy_dir, install_deps_text, config_cpp_text)
        if not any(expected in q for q in problems):
            failures.append(f"self-test: {rel}: {old!r} -> {new!r} was not reported (expected '{expected}'); "
                            f"got {problems}")
    return failures


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--deploy-dir", default=here)
    ap.add_argument("--binary", help="a built footpoint-server whose ldd libraries the runtime stage must provide")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    root = os.path.dirname(os.path.abspath(args.deploy_dir))

    def read(path):
        try:
            with open(os.path.join(root, path), encoding="utf-8") as f:
                return f.read()
        except FileNotFoundError:
            return ""

    install_deps_text, config_cpp_text = read("scripts/install-deps.sh"), read("server/config.cpp")
    texts = read_texts(args.deploy_dir)
    problems, facts = check_texts(texts, args.deploy_dir, install_deps_text, config_cpp_text)
    if not config_cpp_text:
        print("note: server/config.cpp not found: environment variable names not checked")
    if args.binary:
        problems += check_binary(args.binary, facts.get("runtime_packages", []))
    if args.self_test:
        problems += self_test(texts, args.deploy_dir, install_deps_text, config_cpp_text)
    for q in problems:
        print(q)
    files = sorted(texts)
    checked = f"{len(files)} files ({', '.join(files)})" + (f", {len(MUTATIONS)} mutations" if args.self_test else "")
    if problems:
        print(f"FAILED: {len(problems)} problem(s) in {checked}")
        return 1
    print(f"OK: {checked}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
