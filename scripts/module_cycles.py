#!/usr/bin/env python3
"""Report import cycles between modules of src/ (used by scripts/check_layering.sh).

Every `crate::…`, `super::…` and `self::…` path in a file (in `use` trees and inline) is
resolved to an absolute module path and becomes an edge from the file's module to the
target. Two graphs are checked:

- top level: edges between the top-level modules of src/ (`photon`, `shading`, `frame`, …);
- one level down: edges between the child modules of one top-level module (for example
  `shading::environment` and `shading::lights`).

A cycle is a strongly connected component with more than one module. Allowed cycles are
printed but do not fail the check: `--allow A,B` names one cycle by its modules (in any
order; it must match the cycle exactly), `--allow-within M` allows every cycle among the
children of top-level module M. Any other cycle exits with status 1. Comments and string
literals are ignored; test modules count like any other code.

Usage: module_cycles.py [--allow frame,schedule] [--allow-within scene] [SRC_DIR]
"""

import os
import re
import sys


def module_of(src, path):
    """Module path (list of names) of a file under src/; lib.rs/main.rs are the crate root."""
    rel = os.path.relpath(path, src)[: -len(".rs")].split(os.sep)
    if rel[-1] in ("mod", "lib", "main"):
        rel = rel[:-1]
    return rel


def strip_comments(text):
    """Remove // and /* */ comments and the contents of string literals."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    text = re.sub(r"'(?:\\.|[^'\\])'", "' '", text)
    return re.sub(r"//[^\n]*", "", text)


def expand_use_tree(tree):
    """Expand `a::{b, c::{d, e}}` into ['a::b', 'a::c::d', 'a::c::e']."""
    tree = re.sub(r"\s+as\s+\w+", "", tree)
    tree = re.sub(r"\s+", "", tree)
    out = []

    def walk(prefix, s):
        parts, depth, cur = [], 0, ""
        for ch in s:
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
                continue
            depth += ch == "{"
            depth -= ch == "}"
            cur += ch
        parts.append(cur)
        for part in parts:
            if not part:
                continue
            brace = part.find("{")
            if brace >= 0 and part.endswith("}"):
                walk(prefix + part[:brace], part[brace + 1 : -1])
            else:
                out.append(prefix + part)

    walk("", tree)
    return out


def resolve(module, path):
    """Absolute module path of a `crate::`/`super::`/`self::` path, else None."""
    segs = [s for s in path.split("::") if s]
    if not segs:
        return None
    if segs[0] == "crate":
        return segs[1:]
    if segs[0] in ("super", "self"):
        base = list(module)
        while segs and segs[0] in ("super", "self"):
            if segs.pop(0) == "super":
                if not base:
                    return None
                base.pop()
        return base + segs
    return None


USE_RE = re.compile(r"\buse\s+((?:crate|super|self)\b[^;]*);")
INLINE_RE = re.compile(r"\b((?:crate|super|self)(?:::\w+)+)")


def edges_of(src):
    """Yield (from_module, to_path) for every crate-relative path in src/."""
    for root, _, files in os.walk(src):
        for name in sorted(files):
            if not name.endswith(".rs"):
                continue
            path = os.path.join(root, name)
            module = module_of(src, path)
            with open(path, encoding="utf-8") as f:
                text = strip_comments(f.read())
            inline = inline_modules(text)
            for m in USE_RE.finditer(text):
                here = module + inline_path(inline, m.start())
                for p in expand_use_tree(m.group(1)):
                    target = resolve(here, p)
                    if target:
                        yield module, target, path
            for m in INLINE_RE.finditer(USE_RE.sub(lambda u: " " * len(u.group(0)), text)):
                target = resolve(module + inline_path(inline, m.start()), m.group(1))
                if target:
                    yield module, target, path


def inline_modules(text):
    """(start, end, name) of every inline `mod name { … }` block in a file."""
    out = []
    for m in re.finditer(r"\bmod\s+(\w+)\s*\{", text):
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        out.append((m.end(), i, m.group(1)))
    return out


def inline_path(inline, pos):
    """Names of the inline modules enclosing `pos`, outermost first."""
    return [name for start, end, name in sorted(inline) if start <= pos < end]


def sccs(graph):
    """Strongly connected components with more than one node (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(out)


def main(argv):
    allow, within, src = set(), set(), "src"
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--allow":
            allow.add(frozenset(args.pop(0).split(",")))
        elif a == "--allow-within":
            within.add(args.pop(0))
        else:
            src = a
    top_level = {
        os.path.splitext(n)[0]
        for n in os.listdir(src)
        if n.endswith(".rs") or os.path.isdir(os.path.join(src, n))
    } - {"lib", "main"}

    graph, witness = {}, {}

    def add(a, b, path):
        if a != b:
            graph.setdefault(a, set()).add(b)
            graph.setdefault(b, set())
            witness.setdefault((a, b), os.path.relpath(path))

    for module, target, path in edges_of(src):
        if not module or not target or target[0] not in top_level:
            continue
        if module[0] != target[0]:
            add(module[0], target[0], path)
        elif len(module) > 1 and len(target) > 1 and module[1] != target[1]:
            # Child modules of one top-level module; `target[1]` must be a module, not an
            # item re-exported by the parent (`use super::Foo`), so check that it exists.
            parent = os.path.join(src, module[0])
            if os.path.exists(os.path.join(parent, target[1] + ".rs")) or os.path.isdir(
                os.path.join(parent, target[1])
            ):
                add("::".join(module[:2]), "::".join(target[:2]), path)

    failed = False
    for comp in sccs(graph):
        parents = {m.split("::")[0] for m in comp}
        allowed = frozenset(comp) in allow or (
            all("::" in m for m in comp) and len(parents) == 1 and parents <= within
        )
        tag = "allowed (owned elsewhere)" if allowed else "error"
        print(f"{tag}: import cycle: {' <-> '.join(comp)}")
        for a in comp:
            for b in comp:
                if (a, b) in witness:
                    print(f"    {a} -> {b}  ({witness[(a, b)]})")
        failed |= not allowed
    if not failed:
        print("no import cycles outside the allow-list")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
