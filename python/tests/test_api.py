"""The stubs describe the module as it is: every public name, class and
method of the extension is in `__init__.pyi` with the same parameters, and
has a docstring (from the Rust docs)."""

import ast
import inspect
import pathlib

import softshadow

STUB = pathlib.Path(softshadow.__file__).with_name("__init__.pyi")


def stub_tree():
    return ast.parse(STUB.read_text())


def test_stubs_name_every_public_item_and_its_parameters():
    tree = stub_tree()
    top = {n.name: n for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    public = set(softshadow.__all__) - {"__version__"}
    assert public <= set(top), public - set(top)
    for name in public:
        obj = getattr(softshadow, name)
        assert obj.__doc__ and obj.__doc__.strip(), name
        node = top[name]
        if isinstance(node, ast.FunctionDef):
            stub = [a.arg for a in node.args.args]
            assert stub == list(inspect.signature(obj).parameters), name
            continue
        members = {n.name: n for n in node.body if isinstance(n, ast.FunctionDef)}
        for attr, value in vars(obj).items():
            if attr.startswith("_"):
                continue
            assert attr in members, f"{name}.{attr} is not in the stubs"
            assert value.__doc__ and value.__doc__.strip(), f"{name}.{attr}"
            if callable(value) and not isinstance(value, property):
                stub = [a.arg for a in members[attr].args.args if a.arg not in ("self",)]
                got = [p for p in inspect.signature(value).parameters if p not in ("self", "$self")]
                assert stub == got, f"{name}.{attr}: {stub} != {got}"


def test_methods_lists_the_registry():
    ms = softshadow.methods()
    names = [m["name"] for m in ms]
    assert names[-2:] == ["mc", "exact"] and "pcss" in names and "oess" in names
    for m in ms:
        assert m["lights"] and set(m["lights"]) <= {"sphere", "disk", "rect", "segment", "point"}
        for setting in m["default_run"] + m["compare"]:
            assert setting.split(":")[0] == m["name"]
    oess = next(m for m in ms if m["name"] == "oess")
    assert oess["lights"] == ["segment"]
