#!/usr/bin/env python3
"""Refuse a circle among the modules of one crate (docs/ARCHITECTURE.md: "no module imports one
that imports it").

Reads every module file of every crate under ROOT (`crates/*/src`, `xtask/src`), collects the
paths it names inside the crate (`use crate::a::B`, `super::x`, `self::y`, and inline
`crate::a::f()`), resolves each to the module that defines the item (following `pub use`
re-exports), and looks for cycles in that graph. A parent's `mod child;` is not an import.
Test modules (`#[cfg(test)] mod … { … }`) are left out: a test may look anywhere. The crate
root's `pub use` lines are its table of contents, not imports (a module may use an item the
root defines); every other `pub use` is an import of the module that holds it.

usage: module_circles.py [--known CRATE,CRATE] [ROOT]
  exit 1 and print each circle, or print "no module circle". A circle in a crate named by
  --known is printed as known (being removed) and does not fail the check.
"""

import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip(text):
    """The text with comments, strings and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif re.match(r'(b?r)(#*)"', text[i:i + 260]) and not re.match(r"[A-Za-z0-9_]", text[i - 1:i] or " "):
            m = re.match(r'(b?r)(#*)"', text[i:])
            end = '"' + m.group(2)
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:  # a char literal; otherwise a lifetime
                out.append(" " * m.end())
                i += m.end()
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching_brace(text, open_at):
    depth = 0
    for j in range(open_at, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(text) - 1


def drop_test_modules(code):
    """Blank each `#[cfg(test)] mod x { … }` (and `#[cfg(test)] mod x;` is left to file discovery)."""
    pattern = re.compile(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+" + IDENT + r"\s*\{")
    while True:
        m = pattern.search(code)
        if not m:
            return code
        end = matching_brace(code, m.end() - 1)
        code = code[:m.start()] + re.sub(r"[^\n]", " ", code[m.start():end + 1]) + code[end + 1:]


def test_only_children(code):
    """Names of `#[cfg(test)] mod x;` declarations (their files are test code)."""
    return set(re.findall(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+(" + IDENT + r")\s*;", code))


def expand_use_tree(tree):
    """`a::{b, c::{d, self}}` → [['a','b'], ['a','c','d'], ['a','c']]; `as` renames dropped."""
    tree = re.sub(r"\s+as\s+" + IDENT, "", tree)
    tree = re.sub(r"\s+", "", tree)
    results = []

    def walk(prefix, t):
        if not t:
            return
        brace = t.find("{")
        if brace < 0:
            parts = [p for p in t.split("::") if p]
            if parts and parts[-1] == "self":
                parts = parts[:-1]
            results.append(prefix + parts)
            return
        head = [p for p in t[:brace].split("::") if p]
        inner = t[brace + 1:t.rfind("}")]
        depth, start = 0, 0
        for k, ch in enumerate(inner + ","):
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            elif ch == "," and depth == 0:
                walk(prefix + head, inner[start:k])
                start = k + 1

    walk([], tree)
    return results


class Crate:
    def __init__(self, name, src):
        self.name, self.src = name, src
        self.files = {}  # module path (tuple) -> file
        root = "lib.rs" if os.path.exists(os.path.join(src, "lib.rs")) else "main.rs"
        self.discover((), os.path.join(src, root), src)

    def discover(self, module, path, dir_of_children):
        if not os.path.exists(path):
            return
        self.files[module] = path
        text = strip(open(path, encoding="utf-8").read())
        tests = test_only_children(text)
        code = drop_test_modules(text)
        for m in re.finditer(r"^\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+(" + IDENT + r")\s*;", code, re.M):
            child = m.group(1)
            if child in tests:
                continue
            for candidate, child_dir in (
                (os.path.join(dir_of_children, child + ".rs"), os.path.join(dir_of_children, child)),
                (os.path.join(dir_of_children, child, "mod.rs"), os.path.join(dir_of_children, child)),
            ):
                if os.path.exists(candidate):
                    self.discover(module + (child,), candidate, child_dir)
                    break

    def parse(self):
        """Per module: its uses [(path segments, absolute start module, line, is_pub_use)]."""
        self.uses = {}
        self.reexports = {m: {} for m in self.files}  # module -> name -> absolute path
        for module, path in self.files.items():
            code = drop_test_modules(strip(open(path, encoding="utf-8").read()))
            found = []
            # inline (non-test) modules: paths inside them are relative to the inline module
            inline = []
            for m in re.finditer(r"\bmod\s+(" + IDENT + r")\s*\{", code):
                inline.append((m.end() - 1, matching_brace(code, m.end() - 1), m.group(1)))

            def base_at(pos):
                b = module
                for s, e, name in inline:
                    if s <= pos <= e:
                        b = b + (name,)
                return b

            use_spans = []
            for m in re.finditer(r"\b(pub(?:\s*\([^)]*\))?\s+)?use\s+([^;]*);", code):
                use_spans.append((m.start(), m.end()))
                line = code.count("\n", 0, m.start()) + 1
                for segs in expand_use_tree(m.group(2)):
                    found.append((segs, base_at(m.start()), line, bool(m.group(1))))
            for m in re.finditer(r"(?<![A-Za-z0-9_:])((?:crate|super|self)(?:\s*::\s*" + IDENT + r")+)", code):
                if any(s <= m.start() < e for s, e in use_spans):
                    continue
                segs = re.sub(r"\s+", "", m.group(1)).split("::")
                line = code.count("\n", 0, m.start()) + 1
                found.append((segs, base_at(m.start()), line, False))
            self.uses[module] = []
            for segs, base, line, is_pub in found:
                absolute = self.absolute(segs, base)
                if absolute is None:
                    continue
                if is_pub and base == module and absolute:
                    self.reexports[module][absolute[-1]] = absolute
                    if module == ():
                        # the crate root's `pub use` is its table of contents, not an import
                        continue
                self.uses[module].append((absolute, line))

    def absolute(self, segs, base):
        """Absolute segments of a crate-relative path, or None for another crate's path."""
        if not segs:
            return None
        if segs[0] == "crate":
            return tuple(segs[1:])
        if segs[0] in ("self", "super"):
            cur = list(base)
            i = 0
            while i < len(segs) and segs[i] in ("self", "super"):
                if segs[i] == "super":
                    if not cur:
                        return None
                    cur.pop()
                i += 1
            return tuple(cur) + tuple(segs[i:])
        if base + (segs[0],) in self.files:  # `use child::X` (a uniform path to a submodule)
            return base + tuple(segs)
        return None  # a path through an external crate or a local name (not resolved)

    def defining_module(self, absolute, seen=None):
        """The module that defines the item at `absolute` (re-exports followed)."""
        seen = seen or set()
        k = len(absolute)
        while k > 0 and absolute[:k] not in self.files:
            k -= 1
        module = absolute[:k]
        rest = absolute[k:]
        if rest and rest[0] in self.reexports.get(module, {}) and (module, rest[0]) not in seen:
            seen.add((module, rest[0]))
            target = self.reexports[module][rest[0]] + rest[1:]
            return self.defining_module(target, seen)
        return module

    def graph(self):
        edges = {m: {} for m in self.files}
        for module, uses in self.uses.items():
            for absolute, line in uses:
                target = self.defining_module(absolute)
                # a module naming its own items is no import
                if target == module:
                    continue
                edges[module].setdefault(target, line)
        return edges


def name_of(module):
    return "::".join(module) if module else "(crate root)"


def cycles(edges):
    """Strongly connected components with more than one module (Tarjan), each as one cycle."""
    index, low, on, stack, comps, counter = {}, {}, set(), [], [], [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
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
                comps.append(comp)

    for v in sorted(edges):
        if v not in index:
            visit(v)
    result = []
    for comp in comps:
        members = set(comp)
        start = min(comp)
        # shortest path back to start inside the component (BFS)
        best = None
        for first in sorted(w for w in edges[start] if w in members):
            prev, frontier = {first: None}, [first]
            while frontier and start not in prev:
                nxt = []
                for v in frontier:
                    for w in sorted(edges[v]):
                        if w in members and w not in prev:
                            prev[w] = v
                            nxt.append(w)
                frontier = nxt
            if first == start:
                path = [start]
            elif start in prev:
                path, v = [], start
                while v is not None:
                    path.append(v)
                    v = prev[v]
                path = [start] + path[::-1]
            else:
                continue
            if best is None or len(path) < len(best):
                best = path
        result.append((sorted(comp), best))
    return result


def main():
    args = sys.argv[1:]
    known = set()
    if len(args) >= 2 and args[0] == "--known":
        known = {c for c in args[1].split(",") if c}
        args = args[2:]
    root = args[0] if args else "."
    crate_dirs = []
    crates = os.path.join(root, "crates")
    if os.path.isdir(crates):
        crate_dirs += [(d, os.path.join(crates, d, "src")) for d in sorted(os.listdir(crates))]
    crate_dirs.append(("xtask", os.path.join(root, "xtask", "src")))
    found = 0
    for name, src in crate_dirs:
        if not os.path.isdir(src):
            continue
        crate = Crate(name, src)
        crate.parse()
        edges = crate.graph()
        for members, path in cycles(edges):
            found += name not in known
            steps = []
            for a, b in zip(path, path[1:]):
                steps.append(f"{name_of(a)} ({os.path.relpath(crate.files[a], root)}:{edges[a][b]})")
            print(
                ("layering (known, being removed): " if name in known else "layering: ")
                + f"module circle in crate {name}: "
                + " -> ".join(steps + [name_of(path[-1])])
                + (f"; modules in the circle: {', '.join(name_of(m) for m in members)}" if len(members) > len(path) - 1 else "")
            )
    if found:
        return 1
    print("no module circle" + (f" outside the known ones ({', '.join(sorted(known))})" if known else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
