#!/usr/bin/python3
"""Include direction of the sources (docs/architecture.md, "Include direction").

    check_include_direction.py [--root DIR] [RULE ...]

Rules (all when none is named):
  LibgranNeverIncludesPlugins              libgran/ includes nothing from drivers/, observables/
                                           or species/: the plugins include libgran, not the
                                           reverse.
  SceneAndPluginInterfacesIncludeNoEngine  libgran/scene/ and libgran/plugins/ include no engine
                                           header (libgran/engines/...).

Every `#include "..."` line (and `#include <...>` naming a project directory) of the C++ files
below the checked directories is resolved as the compiler does: next to the including file first,
then from the project root (the include directory of the build). Exit status 0 when no rule is
broken; 1 otherwise, listing each offending file:line; 2 on a usage error.
"""
import argparse
import os
import pathlib
import re
import sys

SOURCE_SUFFIXES = {".hpp", ".cpp", ".h", ".cc", ".hh", ".ipp", ".tpp"}
PROJECT_DIRS = ("libgran", "drivers", "observables", "species", "apps", "bench", "tests")
INCLUDE = re.compile(r'^\s*#\s*include\s*(?:"([^"]+)"|<([^>]+)>)')

# name -> (directories whose files are checked, forbidden directories, why)
RULES = {
    "LibgranNeverIncludesPlugins": (
        ("libgran",),
        ("drivers", "observables", "species"),
        "libgran/ must not include the plugin directories (plugins include libgran)",
    ),
    "SceneAndPluginInterfacesIncludeNoEngine": (
        ("libgran/scene", "libgran/plugins"),
        ("libgran/engines",),
        "libgran/scene/ and libgran/plugins/ must not include an engine header",
    ),
}


def inside(path, directory):
    """Whether the root-relative POSIX path lies below directory."""
    return path == directory or path.startswith(directory + "/")


def resolve(root, source, name, quoted):
    """Root-relative POSIX path of an included file, or None when it is outside the project."""
    candidates = [source.parent / name] if quoted else []
    candidates.append(root / name)
    for c in candidates:
        if c.is_file():
            return relative(root, c.resolve())
    # A missing file: judge the spelling (a missing project header is still an include of it).
    for c in candidates:
        rel = relative(root, pathlib.Path(os.path.normpath(c)))
        if rel is not None and rel.split("/")[0] in PROJECT_DIRS:
            return rel
    return None


def relative(root, path):
    try:
        return path.relative_to(root).as_posix()
    except ValueError:
        return None


def includes(root, source):
    """(line number, spelled name with its delimiters, root-relative target) of each project
    include of source."""
    out = []
    text = source.read_text(encoding="utf-8", errors="replace")
    for number, line in enumerate(text.splitlines(), start=1):
        m = INCLUDE.match(line)
        if not m:
            continue
        quoted = m.group(1) is not None
        name = m.group(1) if quoted else m.group(2)
        if not quoted and pathlib.PurePosixPath(name).parts[0] not in PROJECT_DIRS:
            continue  # a system or library header
        target = resolve(root, source, name, quoted)
        if target is not None:
            out.append((number, f'"{name}"' if quoted else f"<{name}>", target))
    return out


def check(root, rule):
    """Violations of one rule as 'file:line: ...' strings, and the number of files checked."""
    checked_dirs, forbidden, _ = RULES[rule]
    problems, files = [], 0
    for d in checked_dirs:
        for source in sorted((root / d).rglob("*")):
            if source.suffix not in SOURCE_SUFFIXES or not source.is_file():
                continue
            files += 1
            rel = source.relative_to(root).as_posix()
            for number, name, target in includes(root, source):
                if any(inside(target, f) for f in forbidden):
                    problems.append(f"{rel}:{number}: #include {name} ({target})")
    return problems, files


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parents[2]),
                        help="project root (default: two levels above this script)")
    parser.add_argument("rules", nargs="*", metavar="RULE", help=", ".join(RULES))
    args = parser.parse_args()
    root = pathlib.Path(args.root).resolve()
    unknown = [r for r in args.rules if r not in RULES]
    if unknown:
        parser.error(f"unknown rule(s) {', '.join(unknown)}; known: {', '.join(RULES)}")
    failed = False
    for rule in args.rules or list(RULES):
        problems, files = check(root, rule)
        if files == 0:
            print(f"{rule}: no source file found under {root} (wrong --root?)")
            failed = True
        elif problems:
            print(f"{rule}: FAILED, {RULES[rule][2]}; {len(problems)} offending include(s):")
            for p in problems:
                print(f"  {p}")
            failed = True
        else:
            print(f"{rule}: ok ({files} files)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
