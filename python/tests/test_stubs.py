# SPDX-License-Identifier: Apache-2.0
"""The hand-written stubs (palp/_palp.pyi, palp/analyze.pyi) name exactly what the module has, so
they cannot drift silently from the bindings."""

import ast
import inspect
import os

import palp
import palp._palp
import palp.analyze

PACKAGE = os.path.dirname(palp.__file__)


def stub_names(path):
    """Top-level names of a stub, and each class's member names."""
    tree = ast.parse(open(path).read())
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            top.add(node.name)
            members[node.name] = {n.name if isinstance(n, (ast.FunctionDef, ast.ClassDef)) else n.target.id
                                  for n in node.body if isinstance(n, (ast.FunctionDef, ast.AnnAssign, ast.ClassDef))}
        elif isinstance(node, (ast.FunctionDef,)):
            top.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
        elif isinstance(node, ast.Assign):
            top.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return top, members


def public(names):
    """The names a user calls: no underscore, and the protocol methods the bindings define."""
    return {n for n in names if not n.startswith("_") or n in ("__enter__", "__exit__", "__len__")}


def test_the_extension_stub_names_every_public_attribute_and_nothing_else():
    top, members = stub_names(os.path.join(PACKAGE, "_palp.pyi"))
    analyses = {n for n in dir(palp._palp) if n.startswith("_analyze_")}  # palp.analyze's engines
    assert analyses == {"_analyze_indentation", "_analyze_pressure", "_analyze_sweep"}
    runtime = public(n for n in dir(palp._palp) if not n.startswith("__")) | analyses
    aliases = {n for n in top if n.startswith("_") and n not in analyses}  # the stub's own
    assert top - aliases == runtime
    for name, cls in inspect.getmembers(palp._palp, inspect.isclass):
        if issubclass(cls, BaseException):
            continue  # the exceptions: fields set per instance, listed in the stub as annotations
        assert public(members[name]) == public(vars(cls)), name


def test_the_analyze_stub_names_every_public_function():
    top, _ = stub_names(os.path.join(PACKAGE, "analyze.pyi"))
    runtime = {n for n, v in vars(palp.analyze).items()
               if not n.startswith("_") and inspect.isfunction(v) and v.__module__ == "palp.analyze"}
    assert runtime | {"RecordingLike"} == top


def test_the_package_re_exports_every_public_name_of_the_extension():
    runtime = {n for n in dir(palp._palp) if not n.startswith("_")}
    assert runtime <= set(palp.__all__), runtime - set(palp.__all__)
