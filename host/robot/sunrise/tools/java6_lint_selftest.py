#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Self-test of java6_lint.py: a file with one newer feature per line must fail, naming each
feature at its file:line; the same features inside comments and strings, and plain Java 6 code
(including switch defaults and generics), must pass."""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
LINT = os.path.join(HERE, "java6_lint.py")

# line number -> (source line, the feature the lint must name there)
BAD = [
    ("import java.nio.file.Paths;", "java.nio.file"),
    ("import java.util.function.Supplier;", "java.util.function"),
    ("import java.util.Objects;", "java.util.Objects"),
    ("interface I { default int f() { return 1; } }", "default method"),
    ("class A { java.util.List<String> l = new java.util.ArrayList<>();", "diamond operator <>"),
    ("  void a() throws Exception { try (java.io.InputStream in = null) { } }", "try-with-resources"),
    ("  void b() { try { } catch (IllegalStateException | IllegalArgumentException e) { } }", "multi-catch |"),
    ("  Runnable r = () -> { };", "lambda ->"),
    ("  Runnable q = A::b;", "method reference ::"),
    ("  int c(String s) { switch (s) { case \"x\": return 1; default: return 0; } }", "strings in switch"),
    ("  int mask = 0b1010;", "binary literal 0b"),
    ("  int million = 1_000_000;", "underscore in a numeric literal"),
    ("  @SafeVarargs final void d(java.util.List<String>... xs) { }", "@SafeVarargs"),
    ("}", None),
]

GOOD = """package x;
// Comments may name anything: () -> x, a::b, new ArrayList<>(), 0b1, 1_000, java.nio.file
/* try (x) { } catch (A | B e) default void f() */
import java.util.ArrayList;
import java.util.List;
class Good {
  List<String> names = new ArrayList<String>();
  String s = "-> :: <> 0b1 1_000 java.util.function case \\"x\\"";
  char arrow = '-';
  int mask = 0x00FF, big = 1000000, MAX_1_2 = 3;
  int f(int k) {
    switch (k) {
      case 1: return -1;
      default: return k > 0 ? k : -k;
    }
  }
  void g() {
    try {
      f(1);
    } catch (IllegalStateException e) {
      f(2);
    } finally {
      f(3);
    }
  }
}
"""


def run(path):
    p = subprocess.run([sys.executable, LINT, path], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def main():
    failures = []
    with tempfile.TemporaryDirectory() as d:
        bad = os.path.join(d, "Bad.java")
        with open(bad, "w") as f:
            f.write("\n".join(line for line, _ in BAD) + "\n")
        rc, out = run(bad)
        if rc != 1:
            failures.append("bad file: exit %d, expected 1\n%s" % (rc, out))
        for number, (line, feature) in enumerate(BAD, start=1):
            if feature is None:
                continue
            expected = "%s:%d: %s " % (bad, number, feature)
            if expected not in out:
                failures.append("bad file: no finding '%s' for line %d: %s" % (expected.strip(), number, line))
        findings = [l for l in out.splitlines() if l.startswith(bad + ":")]
        expected_count = sum(1 for _, feature in BAD if feature is not None)
        if len(findings) != expected_count:
            failures.append("bad file: %d findings, expected %d:\n%s" % (len(findings), expected_count, out))

        good = os.path.join(d, "Good.java")
        with open(good, "w") as f:
            f.write(GOOD)
        rc, out = run(good)
        if rc != 0:
            failures.append("good file: exit %d, expected 0\n%s" % (rc, out))

        rc, out = run(os.path.join(d, "Missing.java"))
        if rc != 2 or "cannot read" not in out:
            failures.append("missing file: exit %d, expected 2 with 'cannot read'\n%s" % (rc, out))
    for f in failures:
        print("FAIL: " + f)
    if not failures:
        print("java6_lint self-test: %d features found at their lines; comments, strings and Java 6 code pass"
              % sum(1 for _, feature in BAD if feature is not None))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
