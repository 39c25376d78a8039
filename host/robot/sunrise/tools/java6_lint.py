#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Rejects Java language features and library packages newer than Java 6 in the bridge core.

KUKA Sunrise runs an old Java; the core is compiled with `javac --release 7`, which alone would
let Java 7 syntax through. Usage: java6_lint.py FILE_OR_DIR... ; prints one line per finding,
`file:line: <feature> (Java N) is not allowed in the bridge core (Java 6)`, and exits 1 when
there is any (2 on a usage or file error). Comments and the insides of string and character
literals are not looked at.
"""
import os
import re
import sys

# (feature name, Java version, pattern over code with comments and literal contents blanked)
RULES = [
    ("diamond operator <>", 7, re.compile(r"<\s*>")),
    ("try-with-resources", 7, re.compile(r"\btry\s*\(")),
    ("multi-catch |", 7, re.compile(r"\bcatch\s*\([^)]*\|")),
    ("strings in switch", 7, re.compile(r"\bcase\s+\"")),
    ("binary literal 0b", 7, re.compile(r"\b0[bB][01_]")),
    ("underscore in a numeric literal", 7, re.compile(r"\b(0[xX][0-9a-fA-F_]*_[0-9a-fA-F]|\d[\d_]*_+\d)")),
    ("@SafeVarargs", 7, re.compile(r"@\s*SafeVarargs\b")),
    ("java.nio.file", 7, re.compile(r"\bjava\s*\.\s*nio\s*\.\s*file\b")),
    ("java.util.Objects", 7, re.compile(r"\bjava\s*\.\s*util\s*\.\s*Objects\b")),
    ("lambda ->", 8, re.compile(r"->")),
    ("method reference ::", 8, re.compile(r"::")),
    ("java.util.function", 8, re.compile(r"\bjava\s*\.\s*util\s*\.\s*function\b")),
    ("default method", 8, re.compile(r"\bdefault\s+(?!:)(?:(?:public|static|synchronized|strictfp)\s+)*[\w<>\[\],.?\s]+?\s+\w+\s*\(")),
    ("@FunctionalInterface", 8, re.compile(r"@\s*FunctionalInterface\b")),
    ("var declaration", 10, re.compile(r"\bvar\s+\w+\s*[=:]")),
    ("text block \"\"\"", 15, re.compile(r"\"\"\"")),
]


def blank(text):
    """The text with comments removed and string/char literal contents blanked, lines kept."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('"""', i):  # a text block: keep the quotes so the rule sees it
            out.append('"""')
            j = text.find('"""', i + 3)
            j = n if j < 0 else j
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i + 3:j]))
            out.append('"""' if j < n else "")
            i = j + 3
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join("\n" if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            out.append(c)
            i += 1
            while i < n and text[i] != c and text[i] != "\n":
                i += 2 if text[i] == "\\" else 1
            out.append(c)
            i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def lint_file(path):
    findings = []
    with open(path, encoding="utf-8") as f:
        code = blank(f.read())
    for number, line in enumerate(code.split("\n"), start=1):
        for name, version, pattern in RULES:
            if pattern.search(line):
                findings.append("%s:%d: %s (Java %d) is not allowed in the bridge core (Java 6)"
                                % (path, number, name, version))
    return findings


def java_files(paths):
    for p in paths:
        if os.path.isdir(p):
            for root, _, files in os.walk(p):
                for name in sorted(files):
                    if name.endswith(".java"):
                        yield os.path.join(root, name)
        else:
            yield p


def main(argv):
    if len(argv) < 2:
        sys.stderr.write("usage: java6_lint.py FILE_OR_DIR...\n")
        return 2
    findings, checked = [], 0
    for path in java_files(argv[1:]):
        try:
            findings += lint_file(path)
        except OSError as e:
            sys.stderr.write("java6_lint: cannot read %s: %s\n" % (path, e.strerror))
            return 2
        checked += 1
    for f in findings:
        print(f)
    if findings:
        return 1
    print("java6_lint: %d files use Java 6 language features only" % checked)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
