# SPDX-License-Identifier: GPL-3.0-or-later
# The add-on's modules import one another without a cycle: the graph of every import in
# addon/hyvox_blender (at module level, inside functions and under TYPE_CHECKING alike), read
# from the source with ast (no module is run), has no cycle. A cycle makes the import order
# matter (a name half-defined when the other module reads it), and in Blender that is an
# add-on that fails to enable.
import ast
import pathlib

ADDON = pathlib.Path(__file__).resolve().parents[2] / "addon" / "hyvox_blender"
PACKAGE = ADDON.name


def module_name(path):
    parts = list(path.relative_to(ADDON.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path, modules):
    """The add-on modules `path` imports, by name."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")
            base = base[: len(base) - (node.level - 1)] if node.level else []
            source = ".".join(base + ([node.module] if node.module else []))
            found.add(source)
            # "from . import backend": the names may be modules of that package.
            found.update(f"{source}.{alias.name}" for alias in node.names)
    return {m for m in found if m in modules and m != name}


def import_graph():
    paths = sorted(ADDON.rglob("*.py"))
    modules = {module_name(p) for p in paths}
    return {module_name(p): imports_of(p, modules) for p in paths}


def cycles(graph):
    """Every cycle found by a depth-first search, each as the list of modules around it."""
    found, state = [], {}

    def visit(node, path):
        state[node] = "open"
        for target in sorted(graph[node]):
            if state.get(target) == "open":
                found.append(path[path.index(target) :] + [target])
            elif target not in state:
                visit(target, path + [target])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
    return found


def test_the_graph_sees_the_add_ons_imports():
    # The witness reads real edges (so an empty graph cannot pass the next test).
    graph = import_graph()
    assert f"{PACKAGE}.core.backend" in graph[f"{PACKAGE}.core.settings"]
    assert f"{PACKAGE}.core.settings" in graph[f"{PACKAGE}.core.pipeline"]
    assert f"{PACKAGE}.blender.ui.properties" in graph[f"{PACKAGE}.blender.gather"]
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]


def test_no_import_cycle_in_the_add_on():
    assert cycles(import_graph()) == []
