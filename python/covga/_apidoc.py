"""The book's page of the Python API, written from the package's own signatures and docstrings:
``python -m covga._apidoc > docs/src/guide/python-api.md`` makes it, and
``python/tests/test_apidoc.py`` requires the committed page to equal what this writes, so a
docstring or a signature changed without the page re-made fails a test.

Signatures are shown without their annotations (names and defaults), which read the same on
every Python version the package supports; the annotations are in the package's types
(``py.typed``)."""

from __future__ import annotations

import inspect
from types import ModuleType
from typing import Any

import covga
from covga import plot, stats, thesis

MODULES: list[ModuleType] = [covga, thesis, stats, plot]


def _signature(obj: Any) -> str:
    """``(name, key=default, ...)`` of a callable, annotations left out."""
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return "(...)"
    params = [p.replace(annotation=inspect.Parameter.empty) for p in sig.parameters.values()]
    return str(sig.replace(parameters=params, return_annotation=inspect.Signature.empty))


def _public(module: ModuleType) -> list[tuple[str, Any]]:
    """The module's public functions and classes: its ``__all__`` where it has one, else what it
    defines; submodules are left to their own section."""
    listed = getattr(module, "__all__", None)
    names = listed or [n for n in dir(module) if not n.startswith("_")]
    out = []
    for name in sorted(names):
        obj = getattr(module, name)
        if inspect.ismodule(obj):
            continue
        # Without `__all__`, what the module defines itself (not what it imports).
        if listed is None and getattr(obj, "__module__", None) != module.__name__:
            continue
        if inspect.isfunction(obj) or inspect.isclass(obj):
            out.append((name, obj))
    return out


def _members(cls: type) -> list[tuple[str, Any]]:
    """A class's public methods and properties with docstrings of their own."""
    out = []
    for name, member in sorted(vars(cls).items()):
        if name.startswith("_"):
            continue
        if isinstance(member, property) or inspect.isfunction(member) or inspect.isroutine(member):
            if inspect.getdoc(member):
                out.append((name, member))
    return out


def markdown() -> str:
    """The page as Markdown."""
    lines = [
        "# The Python API",
        "",
        "Every public function and class of the package `covga`, with its docstring. This page is",
        "written by `python -m covga._apidoc` from the package itself; `python/tests/test_apidoc.py`",
        "requires it to equal what the package writes. [From Python](python.md) shows them at work.",
    ]
    for module in MODULES:
        lines += ["", f"## `{module.__name__}`", ""]
        doc = inspect.getdoc(module) or ""
        lines += [doc.split("\n\n")[0], ""]
        for name, obj in _public(module):
            kind = "class" if inspect.isclass(obj) else "def"
            lines += [f"### `{module.__name__}.{name}`", "", "```python", f"{kind} {name}{_signature(obj)}", "```", ""]
            lines += [inspect.getdoc(obj) or "(no docstring)", ""]
            if inspect.isclass(obj):
                for member_name, member in _members(obj):
                    shown = member_name if isinstance(member, property) else f"{member_name}{_signature(member)}"
                    lines += [f"- `{shown}`: {' '.join((inspect.getdoc(member) or '').split())}"]
                lines.append("")
    return "\n".join(lines).rstrip() + "\n"


if __name__ == "__main__":
    print(markdown(), end="")
