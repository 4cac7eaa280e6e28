#!/usr/bin/env python3
"""Two layering checks of docs/ARCHITECTURE.md that `cargo tree` cannot make.

1. No unused dependency: every crate named in a member's `[dependencies]` is used by its
   library or binary sources (`src/`, `build.rs`), every `[dev-dependencies]` crate by its
   tests, benches, examples or `src/` (unit tests). "Used" means its Rust name (`-` as `_`)
   appears as a path (`name::`), in a `use`, or `extern crate`.
2. Sections stay in their rooms: a module under `crates/pipeline/src/sections/<a>/` imports
   no sibling section (`crate::sections::<b>`, `super::super::<b>`, `super::<b>` from a
   section's `mod.rs`); what sections share lives in the core modules. Nor does it name the
   whole configuration (`StudyConfig`), through which it would read its siblings' parts: it
   validates its own part with the study's resolved facts (`crate::resolved`); only the study
   and the core name `StudyConfig`, and only the phases section `PhaseConfig`.

Usage: deps_and_rooms.py [ROOT]   (exit 1 and one line per finding)
"""

import re
import sys
import tomllib
from pathlib import Path

# Dependencies used without their name in the source: they enable a feature, are linked for
# their side effect, or are a build tool.
ALLOWED = {
    # pulp: faer's SIMD dispatch feature `x86-v4` is turned on through this dependency
    ("harmonics", "pulp"): "used through `pulp::` in the SIMD kernel",
}


def rust_name(dep: str, spec) -> str:
    if isinstance(spec, dict) and "package" in spec:
        pass  # the key is the name used in Rust
    return dep.replace("-", "_")


def sources(crate: Path, dev: bool) -> str:
    dirs = ["src"] + (["tests", "benches", "examples"] if dev else [])
    text = []
    for d in dirs:
        for f in (crate / d).rglob("*.rs") if (crate / d).is_dir() else []:
            text.append(f.read_text(encoding="utf-8", errors="replace"))
    build = crate / "build.rs"
    if build.exists():
        text.append(build.read_text(encoding="utf-8"))
    return "\n".join(text)


def used(name: str, text: str) -> bool:
    pattern = rf"(\b{name}::|\buse\s+{name}\b|\bextern\s+crate\s+{name}\b|#\[{name}::|\b{name}!)"
    return re.search(pattern, text) is not None


def unused_dependencies(root: Path) -> list[str]:
    findings = []
    for manifest in sorted(list(root.glob("crates/*/Cargo.toml")) + list(root.glob("xtask/Cargo.toml"))):
        crate = manifest.parent
        data = tomllib.loads(manifest.read_text(encoding="utf-8"))
        package = data.get("package", {}).get("name", crate.name)
        for table, dev in (("dependencies", False), ("dev-dependencies", True)):
            deps = data.get(table, {})
            if not deps:
                continue
            text = sources(crate, dev)
            for dep, spec in deps.items():
                if (package, dep) in ALLOWED or (crate.name, dep) in ALLOWED:
                    continue
                name = rust_name(dep, spec)
                if not used(name, text):
                    findings.append(
                        f"unused dependency: {crate.relative_to(root)}/Cargo.toml [{table}] {dep}"
                        f" (no `{name}::` or `use {name}` in its sources)"
                    )
    return findings


SIBLING = re.compile(r"\b(?:crate::sections::|super::super::)(\w+)")
WHOLE_CONFIG = re.compile(r"\bStudyConfig\b")
PHASE_CONFIG = re.compile(r"\bPhaseConfig\b")


def sections_in_rooms(root: Path) -> list[str]:
    findings = []
    base = root / "crates/pipeline/src/sections"
    if not base.is_dir():
        return findings
    sections = {d.name for d in base.iterdir() if d.is_dir()} | {
        f.stem for f in base.glob("*.rs") if f.stem != "mod"
    }
    for section in sorted(sections):
        files = list((base / section).rglob("*.rs")) if (base / section).is_dir() else [base / f"{section}.rs"]
        for f in files:
            for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
                if line.lstrip().startswith("//"):
                    continue
                targets = [m.group(1) for m in SIBLING.finditer(line)]
                # `super::<b>` from a section's own mod.rs reaches the sections module
                if f.name == "mod.rs" and f.parent.name == section:
                    targets += re.findall(r"\bsuper::(\w+)", line)
                for other in targets:
                    if other in sections and other != section:
                        findings.append(
                            f"section {section} imports section {other}: "
                            f"{f.relative_to(root)}:{n} (what sections share belongs in the core)"
                        )
                if section != "phases" and PHASE_CONFIG.search(line):
                    findings.append(
                        f"section {section} reads the phases' configuration (PhaseConfig): "
                        f"{f.relative_to(root)}:{n} (what a phase was given as is a resolved "
                        f"fact, crate::resolved)"
                    )
                if WHOLE_CONFIG.search(line):
                    findings.append(
                        f"section {section} names the whole configuration (StudyConfig): "
                        f"{f.relative_to(root)}:{n} (a section validates its own part with the "
                        f"study's resolved facts, crate::resolved)"
                    )
    return findings


def main() -> int:
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
    findings = unused_dependencies(root) + sections_in_rooms(root)
    for f in findings:
        print(f"layering: {f}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
