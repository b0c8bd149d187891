"""The package's structure: the import graph between its stages has no cycle, methods
refuse options that are not theirs, and the old public names keep working.

``python tests/test_architecture.py`` prints the import graph, stage by stage (each
package or top-level module of rigidblocks, its lines and what it imports), with
function-level imports counted like the others.
"""

from __future__ import annotations

import ast
import warnings
from pathlib import Path

import pytest

import rigidblocks as rb
from rigidblocks.errors import InputError

PACKAGE = Path(rb.__file__).resolve().parent
#: deprecated aliases: they import their new homes, and nothing imports them
ALIASES = {"rigidblocks.examples", "rigidblocks.problems.analysis"}


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def module_imports() -> dict[str, set[str]]:
    """Module -> the rigidblocks modules it imports (anywhere in its body)."""
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        pkg = name if path.name == "__init__.py" else name.rpartition(".")[0]
        out: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = pkg.split(".")
                    base = base[:len(base) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                cands = [f"{target}.{a.name}" for a in node.names] + [target]
            elif isinstance(node, ast.Import):
                cands = [a.name for a in node.names]
            else:
                continue
            for c in cands:
                if c in modules and c != name:
                    out.add(c)
                    break
        graph[name] = out
    return graph


def stage(module: str) -> str:
    """A module's stage: its package under rigidblocks (or the module itself)."""
    parts = module.split(".")
    return ".".join(parts[:2])


def stage_graph() -> dict[str, set[str]]:
    g: dict[str, set[str]] = {}
    for m, deps in module_imports().items():
        if m in ALIASES or m == "rigidblocks":
            continue
        s = stage(m)
        g.setdefault(s, set()).update(stage(d) for d in deps if stage(d) != s
                                      and d not in ALIASES and d != "rigidblocks")
    return g


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
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

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_import_cycle_between_modules():
    """Function-level imports count: a cycle hidden inside a function is still one."""
    g = {m: d - ALIASES for m, d in module_imports().items() if m not in ALIASES}
    assert cycles(g) == []


def test_no_import_cycle_between_stages():
    """The stages (scene, contacts, equilibrium, problems, solvers, methods, analyses,
    results, io, plotting, studies, cli) form a layered graph."""
    assert cycles(stage_graph()) == []


def test_lower_stages_do_not_reach_up():
    """Geometry never imports a solver, solvers never read files or know the analyses,
    the analyses never draw."""
    g = stage_graph()
    assert not g["rigidblocks.scene"] & {"rigidblocks.solvers", "rigidblocks.methods",
                                         "rigidblocks.analyses", "rigidblocks.io"}
    assert not g["rigidblocks.solvers"] & {"rigidblocks.io", "rigidblocks.methods",
                                           "rigidblocks.analyses", "rigidblocks.problems",
                                           "rigidblocks.scene"}
    assert not g["rigidblocks.methods"] & {"rigidblocks.analyses", "rigidblocks.io",
                                           "rigidblocks.cli"}
    assert not g["rigidblocks.analyses"] & {"rigidblocks.plotting", "rigidblocks.io",
                                            "rigidblocks.cli"}


#: the largest function the numerical core may hold (lines, docstring included)
FUNCTION_LINES = 80
#: the largest the convex method's module may grow (lines)
CONVEX_LINES = 700


def _functions(path: Path) -> list[ast.FunctionDef | ast.AsyncFunctionDef]:
    return [n for n in ast.walk(ast.parse(path.read_text()))
            if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef)]


def test_no_function_of_the_numerical_core_is_over_80_lines():
    """methods/, analyses/ and solvers/: one screen per function (a search's rules are
    small named functions, not one loop with its cases inline)."""
    long = [f"{p.relative_to(PACKAGE)}:{f.lineno} {f.name} ({f.end_lineno - f.lineno + 1})"
            for sub in ("methods", "analyses", "solvers")
            for p in sorted((PACKAGE / sub).rglob("*.py")) for f in _functions(p)
            if f.end_lineno - f.lineno + 1 > FUNCTION_LINES]
    assert long == []
    assert len((PACKAGE / "methods" / "convex.py").read_text().splitlines()) <= CONVEX_LINES


def private_calls_outside_methods() -> list[str]:
    """Where a module outside rigidblocks/methods reads a private member (``x._name``,
    ``x`` not ``self`` or ``cls``) of the name of one defined in a class of
    rigidblocks/methods."""
    private = set()
    for p in (PACKAGE / "methods").rglob("*.py"):
        for cls in (n for n in ast.walk(ast.parse(p.read_text()))
                    if isinstance(n, ast.ClassDef)):
            for n in ast.walk(cls):
                name = n.name if isinstance(n, ast.FunctionDef) else \
                    n.attr if isinstance(n, ast.Attribute) else ""
                if name.startswith("_") and not name.startswith("__"):
                    private.add(name)
    out = []
    for p in sorted(PACKAGE.rglob("*.py")):
        if (PACKAGE / "methods") in p.parents:
            continue
        for n in ast.walk(ast.parse(p.read_text())):
            if isinstance(n, ast.Attribute) and n.attr in private and not (
                    isinstance(n.value, ast.Name) and n.value.id in ("self", "cls")):
                out.append(f"{p.relative_to(PACKAGE)}:{n.lineno} .{n.attr}")
    return out


def test_no_module_outside_methods_reads_a_private_member_of_a_method():
    """The analyses, the CLI and the studies use the methods' public interface: a
    private member may change with the method's inside."""
    assert private_calls_outside_methods() == []


def test_options_that_do_not_apply_to_a_method_are_errors():
    scene = rb.read_scene(Path(__file__).parents[1] / "examples" / "reference.json")
    for kw, word in (({"solver": "highs"}, "solver"), ({"pyramid": 8}, "pyramid"),
                     ({"contact_tol": 1e-6}, "contact_tol"),
                     ({"settings": {"tol_feas": 1e-9}}, "tol_feas")):
        with pytest.raises(InputError, match=word):
            rb.check(scene, method="distortion", **kw)
    with pytest.raises(InputError, match="unknown method"):
        rb.check(scene, method="simplex")
    with pytest.raises(InputError, match="another"):
        rb.check(scene, method="highs", solver="clarabel")
    with pytest.raises(InputError, match="unknown Clarabel setting"):
        rb.check(scene, settings={"tol_feasibility": 1e-9})
    # a back end's name as the method is the convex path with that back end
    assert rb.min_friction(scene, method="highs").solver == "highs"



def test_numbers_given_by_the_user_are_checked_by_one_helper():
    """finite_number serves the analyses, the generators and the CLI: each keeps its
    wording and its rule on bools (float() takes them, running_bond_wall does not)."""
    import argparse

    import numpy as np

    from rigidblocks.cli.options import finite_float
    from rigidblocks.errors import finite_number
    from rigidblocks.generators.arches import arch
    from rigidblocks.generators.walls import running_bond_wall

    scene = rb.read_scene(Path(__file__).parents[1] / "examples" / "reference.json")
    for value, words in (("x", "load factor must be an int or float, got 'x'"),
                         (float("inf"), "load factor must be a finite number, got inf")):
        with pytest.raises(InputError, match=words):
            rb.check(scene, load_factor=value)
    with pytest.raises(InputError, match="arch: radius must be a finite number, got nan"):
        arch(radius=float("nan"))
    assert arch(radius=True).name == arch(radius=1.0).name
    with pytest.raises(InputError, match="running_bond_wall: friction must be an int or "
                                         "float, got True"):
        running_bond_wall(2, 2, friction=True)
    with pytest.raises(InputError, match="running_bond_wall: depth must be > 0, got 0"):
        running_bond_wall(2, 2, depth=0)
    assert running_bond_wall(2, 2, depth=np.float64(0.5)).depth == 0.5
    with pytest.raises(argparse.ArgumentTypeError, match="not a finite number: '1e999'"):
        finite_float("1e999")
    with pytest.raises(InputError, match="must be a finite number"):
        finite_number(10**400)
    assert finite_number(True) == 1.0 and finite_number("2.5") == 2.5

def test_old_names_still_work_and_warn():
    with pytest.warns(DeprecationWarning):
        from rigidblocks.problems import check
    assert check is rb.check
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from rigidblocks.problems.analysis import max_load_multiplier
    assert max_load_multiplier is rb.max_load_multiplier


def test_stage_timings_are_on_the_results():
    """Benchmarks read where the time goes from the result, without patching modules."""
    scene = rb.read_scene(Path(__file__).parents[1] / "examples" / "wall.json")
    r = rb.max_load_multiplier(scene)
    assert {"contacts", "assembly", "build", "solve", "state"} <= set(r.cpu_timings)
    assert all(v >= 0 for v in r.timings.values())
    assert r.timings["solve"] > 0


def main() -> None:
    lines = {}
    for p in PACKAGE.rglob("*.py"):
        s = stage(_module_name(p))
        lines[s] = lines.get(s, 0) + len(p.read_text().splitlines())
    g = stage_graph()
    order: list[str] = []
    while len(order) < len(g):
        ready = sorted(s for s in g if s not in order and g[s] <= set(order) | {s})
        if not ready:  # a cycle: print the rest as it is
            ready = sorted(s for s in g if s not in order)
        order += ready
    for s in order:
        deps = ", ".join(d.removeprefix("rigidblocks.") for d in sorted(g[s])) or "-"
        print(f"{s.removeprefix('rigidblocks.'):<14} {lines.get(s, 0):>6} lines  <- {deps}")
    found = cycles({m: d - ALIASES for m, d in module_imports().items()
                    if m not in ALIASES})
    print("cycles:", found or "none")


if __name__ == "__main__":
    main()
