#!/usr/bin/env python3
"""Functions over 200 lines in the workspace's non-test Rust code (crates/*/src, xtask/src).

A long function is read as one block; split it into named steps a reader can follow (issue
31). Counts the lines from `fn` to its closing brace; comments, strings and characters are
blanked first so that their braces do not count. Test code is left out: `#[cfg(test)]`
modules, inline or in their own files. Prints each function found and exits 1;
`python3 .ci/long_functions.py ROOT [--limit N]`. Run by `.ci/layering`.
"""
import os, re, sys

def clean(text):
    """The text with comments, strings and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i)); i = j; continue
        if text.startswith('/*', i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith('/*', j): depth += 1; j += 2
                elif text.startswith('*/', j): depth -= 1; j += 2
                else: j += 1
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j; continue
        m = re.match(r'b?r(#*)"', text[i:i+300]) if c in 'br' and (i == 0 or not (text[i-1].isalnum() or text[i-1] == '_')) else None
        if m:
            hashes = m.group(1)
            end = text.find('"' + hashes, i + m.end())
            end = n if end < 0 else end + 1 + len(hashes)
            out.append(re.sub(r'[^\n]', ' ', text[i:end])); i = end; continue
        if c == '"' or (c == 'b' and text.startswith('b"', i) and (i == 0 or not (text[i-1].isalnum() or text[i-1] == '_'))):
            j = i + (2 if c == 'b' else 1)
            while j < n and text[j] != '"':
                j += 2 if text[j] == '\\' else 1
            j += 1
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j; continue
        if c == "'":
            m = re.match(r"'(\\(x[0-9a-fA-F]{2}|u\{[0-9a-fA-F]+\}|.)|[^\\'])'", text[i:i+12])
            if m:
                out.append(' ' * m.end()); i += m.end(); continue
        out.append(c); i += 1
    return ''.join(out)

def test_files(root):
    """Module files declared behind #[cfg(test)] (and their sub-modules' directories)."""
    skip = set()
    for path in rust_files(root, with_tests=True):
        text = clean(open(path, encoding='utf-8').read())
        for m in re.finditer(r'#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;', text):
            name = m.group(1)
            base = os.path.dirname(path)
            stem = os.path.splitext(os.path.basename(path))[0]
            if stem not in ('mod', 'lib', 'main'):
                base = os.path.join(base, stem)
            for cand in (os.path.join(base, name + '.rs'), os.path.join(base, name, 'mod.rs'), os.path.join(base, name)):
                skip.add(os.path.normpath(cand))
    return skip

def rust_files(root, with_tests=False):
    """The Rust files of crates/*/src and xtask/src."""
    crates = os.path.join(root, 'crates')
    tops = [os.path.join(crates, c, 'src') for c in sorted(os.listdir(crates))] if os.path.isdir(crates) else []
    for src in tops + [os.path.join(root, 'xtask', 'src')]:
        for dirpath, dirs, files in os.walk(src):
            dirs.sort()
            for f in sorted(files):
                if f.endswith('.rs'):
                    yield os.path.normpath(os.path.join(dirpath, f))

def functions(path, text):
    c = clean(text)
    # Test modules inside the file: #[cfg(test)] mod x { ... }
    blocked = []
    for m in re.finditer(r'#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([^)]*\))?\s+)?mod\s+\w+\s*\{', c):
        end = match_brace(c, m.end() - 1)
        blocked.append((m.start(), end))
    for m in re.finditer(r'\bfn\s+(\w+)', c):
        if any(a <= m.start() < b for a, b in blocked):
            continue
        j, depth = m.end(), 0
        while j < len(c):
            ch = c[j]
            if ch in '(<[': depth += 1
            elif ch in ')>]':
                if not (ch == '>' and c[j-1] == '-'): depth -= 1
            elif ch == ';' and depth <= 0: j = -1; break
            elif ch == '{' and depth <= 0: break
            j += 1
        if j < 0 or j >= len(c):
            continue
        end = match_brace(c, j)
        # start at the line of `fn`
        start_line = c.count('\n', 0, m.start()) + 1
        end_line = c.count('\n', 0, end) + 1
        yield m.group(1), start_line, end_line - start_line + 1

def match_brace(c, j):
    depth = 0
    for k in range(j, len(c)):
        if c[k] == '{': depth += 1
        elif c[k] == '}':
            depth -= 1
            if depth == 0: return k
    return len(c) - 1

def main():
    args = sys.argv[1:]
    limit = 200
    root = '.'
    while args:
        a = args.pop(0)
        if a == '--limit': limit = int(args.pop(0))
        else: root = a
    skip = test_files(root)
    rows = []
    for path in rust_files(root):
        if path in skip or any(path.startswith(s + os.sep) for s in skip):
            continue
        text = open(path, encoding='utf-8').read()
        for name, line, length in functions(path, text):
            if length > limit:
                rows.append((length, os.path.relpath(path, root), line, name))
    for length, path, line, name in sorted(rows, reverse=True):
        print(f'long function: {path}:{line} {name} has {length} lines (at most {limit}): '
              'split it into named steps')
    return 1 if rows else 0

sys.exit(main())
