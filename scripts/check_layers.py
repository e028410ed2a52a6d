#!/usr/bin/env python3
"""Checks the module layers of noncirc-core and that noncirc-search stands alone.

Each module of crates/noncirc-core/src may use its own layer and those below:
util ← model ← scene ← evaluate ← study. A module's `crate::` references (in code and in
doc links; plain `//` comments are skipped) must not reach a higher layer, and the modules
must not form a cycle, within a layer either. A name re-exported at the crate root
(`crate::Scene`) counts as a reference to the module it comes from; a re-exported item
of another crate (`crate::Fitness`, from noncirc-search) is no module's.

crates/noncirc-search must not refer to noncirc-core: no `noncirc_core`/`noncirc-core` in
its code or its Cargo.toml, and no `noncirc_core::` path in its doc comments (their prose
may name the core, as the crate's doc does).

Run from anywhere: `python3 scripts/check_layers.py`. Prints "layers ok", or each problem
as file:line and exits 1.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORE = ROOT / "crates/noncirc-core/src"
SEARCH = ROOT / "crates/noncirc-search"

LAYERS = [  # lowest first; a module may use its own layer and those below
    "error vec2 angle lanes quadrature resolution golden segment_tree",                    # util
    "curve gear planetary teeth moving_box gearbox blank",                             # model
    "scene check reference messages params agronomy objective_kind measure goal constraint tolerance target dynamics_spec cad_spec whole_number",  # scene
    "evaluation evaluator events interference anatomy dynamics flywheel objectives measure_value accuracy fit inverse strength",           # evaluate
    "robustness sensitivity problem checkpoint serial",                          # study
]
NAMES = ["util", "model", "scene", "evaluate", "study"]
LAYER = {m: i for i, ms in enumerate(LAYERS) for m in ms.split()}


def rel(path):
    return path.relative_to(ROOT)


def without_comments(line, keep_docs):
    """The line without its `//` comment; doc comments (`///`, `//!`) kept if asked."""
    pattern = r"(?<!/)//(?![/!]).*" if keep_docs else r"//.*"
    return re.sub(pattern, "", line)


def crate_references(text):
    """(offset, name) of each module or root item that a `crate::` path names, including
    every member of a `crate::{a::X, b}` group (nested braces, several lines)."""
    for m in re.finditer(r"\bcrate::", text):
        at = m.end()
        if text.startswith("{", at):
            depth, start = 0, at + 1
            for end in range(at, len(text)):
                depth += {"{": 1, "}": -1}.get(text[end], 0)
                if depth == 0:
                    break
            # The group's members at its top level: the first name of each.
            depth, member = 0, start
            for i in range(start, end + 1):
                c = text[i]
                if depth == 0 and c in ",}":
                    name = re.match(r"\s*(\w+)", text[member:i])
                    if name:
                        yield member + name.start(1), name.group(1)
                    member = i + 1
                depth += {"{": 1, "}": -1}.get(c, 0)
        else:
            name = re.match(r"\w+", text[at:])
            if name:
                yield at, name.group(0)


def check_core():
    lib = (CORE / "lib.rs").read_text()
    mods = set(re.findall(r"^\s*(?:pub(?:\(crate\))?\s+)?mod\s+(\w+)\s*;", lib, re.M))
    errors = [f"{rel(CORE / 'lib.rs')}: module '{m}' has no layer" for m in sorted(mods - set(LAYER))]
    errors += [f"{rel(pathlib.Path(__file__).resolve())}: the layer table names '{m}', "
               "which is no module of lib.rs" for m in sorted(set(LAYER) - mods)]
    root = {}  # item re-exported at the crate root -> its module (or crate)
    for m, body in re.findall(r"pub use (\w+)(?:::\w+)*::\{([^}]*)\}", lib):
        for item in body.split(","):
            if item.strip():
                root[item.split(" as ")[-1].strip()] = m
    for m, item, alias in re.findall(r"pub use (\w+)(?:::\w+)*::(\w+)(?: as (\w+))?;", lib):
        root[alias or item] = m
    edges = {}
    for f in sorted(CORE.rglob("*.rs")):
        if f == CORE / "lib.rs":
            continue
        me = f.relative_to(CORE).parts[0].removesuffix(".rs")
        if me not in LAYER:
            continue  # reported above, from lib.rs
        text = "\n".join(without_comments(line, keep_docs=True)
                         for line in f.read_text().splitlines())
        for at, name in crate_references(text):
            n = text.count("\n", 0, at) + 1
            target = name if name in mods else root.get(name)
            if target is None:
                errors.append(f"{rel(f)}:{n}: cannot resolve crate::{name}")
            elif target != me and target in mods:  # not a re-exported external crate
                edges.setdefault(me, set()).add(target)
                if LAYER[target] > LAYER[me]:
                    errors.append(
                        f"{rel(f)}:{n}: {me} ({NAMES[LAYER[me]]}) uses {target} "
                        f"({NAMES[LAYER[target]]}, a higher layer): crate::{name}")

    def reach(m):  # every module m depends on, directly or not
        seen, todo = set(), [m]
        while todo:
            for t in edges.get(todo.pop(), ()):
                if t not in seen:
                    seen.add(t)
                    todo.append(t)
        return seen

    r = {m: reach(m) for m in edges}
    cycles = {frozenset(n for n in r[m] if m in r.get(n, ())) for m in r if m in r[m]}
    errors += ["cycle among: " + ", ".join(sorted(c)) for c in sorted(cycles, key=sorted)]
    return errors


def check_search():
    errors = []
    toml = SEARCH / "Cargo.toml"
    for n, line in enumerate(toml.read_text().splitlines(), 1):
        if re.search(r"noncirc[-_]core", line.split("#")[0]):
            errors.append(f"{rel(toml)}:{n}: noncirc-search depends on noncirc-core")
    for f in sorted((SEARCH / "src").rglob("*.rs")):
        for n, line in enumerate(f.read_text().splitlines(), 1):
            code = without_comments(line, keep_docs=False)
            if re.search(r"noncirc[-_]core", code) or "noncirc_core::" in line:
                errors.append(f"{rel(f)}:{n}: noncirc-search refers to noncirc-core")
    return errors


if __name__ == "__main__":
    problems = check_core() + check_search()
    print("\n".join(problems) or "layers ok")
    sys.exit(1 if problems else 0)
