"""Writes the type stubs of the built module, every line from the module itself (issue 22: nothing
is kept by hand). Run at build time by CMake:

    generate_stubs.py MODULE_DIR OUT_PYI

- A function or method: its pybind11 signature line(s) (one per overload), then its docstring.
- A function made from a procedure spec (python/wrap_specs.cc, it takes **keywords): its keywords
  from inertest.procedure_specs().
- A class: its properties (typed by their getters' signatures), its methods, and the lines of a
  "Members:" section of its docstring, written in stub syntax (`    name: Type  # comment`): the
  members of a result, which are its JSON keys (python/bindings.h).
- A module constant: typed from its value.
"""

import importlib
import json
import re
import sys

HEADER = '''from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union, overload

import os

import numpy
import numpy.typing

ArrayLike = numpy.typing.ArrayLike
FloatArray = numpy.typing.NDArray[numpy.float64]
IntArray = numpy.typing.NDArray[numpy.int64]
'''

PYTHON_TYPES = {"number": "float", "text": "str", "numbers": "Sequence[float]", "boolean": "bool", "texts": "Sequence[str]"}
ARRAY_TYPES = {"float64": "FloatArray", "int64": "IntArray"}
SPECIAL_METHODS = {"__init__", "__getattr__", "__getitem__", "__contains__", "__len__", "__float__", "__iter__"}


def readable_type(text, parameter):
    """A pybind11 type as the stubs write it: numpy arrays as ArrayLike (what a float64 parameter
    accepts, converted) or their NDArray alias, a path as str or os.PathLike (pybind11 names the
    second alone), no module prefix, unprintable defaults as '...'."""
    text = text.replace("inertest.", "").replace("os.PathLike", "Union[str, os.PathLike]")

    def array(match):
        dtype = match.group(1)
        return "ArrayLike" if parameter and dtype == "float64" else ARRAY_TYPES.get(dtype, f"numpy.typing.NDArray[numpy.{dtype}]")

    text = re.sub(r"numpy\.ndarray\[numpy\.(\w+)\]", array, text)
    # pybind11's std::array<T, N>, List[float[5]], is no type a checker reads: a list of N.
    text = re.sub(r"List\[(\w+)\[\d+\]\]", r"List[\1]", text)
    return re.sub(r"= <[^>]*>", "= ...", text)


def split_signature(signature):
    """'name(args) -> ret' as (args, ret), the parameters' and the result's types made readable."""
    head, _, result = signature.rpartition(" -> ")
    arguments = head[head.index("(") + 1 : -1]
    return readable_type(arguments, True), readable_type(result, False)


def docstring(text, indent):
    text = text.strip()
    if not text:
        return []
    body = text.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    lines = body.splitlines()
    return [f'{indent}"""{lines[0]}'] + [f"{indent}{line}" if line else "" for line in lines[1:]] + [f'{indent}"""']


def signatures_and_doc(name, doc):
    """The signature lines of a pybind11 docstring (several for an overloaded function) and the rest."""
    lines = (doc or "").splitlines()
    if len(lines) > 1 and lines[1].strip() == "Overloaded function.":
        overloads = [re.sub(r"^\d+\. ", "", line) for line in lines if re.match(rf"^\d+\. {name}\(", line)]
        return overloads, ""
    return lines[:1], "\n".join(lines[1:])


def function_lines(name, function, indent="", method=False):
    signatures, doc = signatures_and_doc(name, function.__doc__)
    lines = []
    for signature in signatures:
        arguments, result = split_signature(signature)
        if method:
            arguments = re.sub(r"^self: [\w.]+", "self", arguments)
        if len(signatures) > 1:
            lines.append(f"{indent}@overload")
        lines.append(f"{indent}def {name}({arguments}) -> {result}:")
        body = docstring(doc, indent + "    ") if len(signatures) == 1 else []
        lines += body or [f"{indent}    ..."]
    return lines


def members_section(doc):
    """The 'Members:' section of a class docstring (stub lines) and the docstring without it."""
    text = doc or ""
    head, found, tail = text.partition("Members:\n")
    if not found:
        return [], text
    return [line for line in tail.splitlines() if line.strip()], head


def class_lines(name, cls):
    bases = [base.__name__ for base in cls.__bases__ if base.__name__ not in ("pybind11_object", "object")]
    members, doc = members_section(cls.__doc__)
    lines = [f"class {name}({', '.join(bases)}):" if bases else f"class {name}:"]
    lines += docstring(doc, "    ")
    lines += [line if line.startswith("    ") else f"    {line.strip()}" for line in members]
    for member, value in vars(cls).items():
        if isinstance(value, property):
            _, result = split_signature(value.fget.__doc__.splitlines()[0])
            comment = (value.__doc__ or "").strip().splitlines()
            lines.append(f"    {member}: {result}" + (f"  # {comment[0]}" if comment and "->" not in comment[0] else ""))
        elif isinstance(value, staticmethod):
            lines += ["    @staticmethod"] + function_lines(member, value.__func__, "    ")
        elif type(value).__name__ == "instancemethod" and (not member.startswith("_") or member in SPECIAL_METHODS):
            lines += function_lines(member, value, "    ", method=True)
    return lines if len(lines) > 1 else lines + ["    ..."]


def python_literal(value):
    """A default as Python writes it: True, not JSON's true; strings in double quotes."""
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(python_literal(item) for item in value) + "]"
    return repr(value)


def parameter_line(parameter):
    annotation = "int" if parameter["whole"] else PYTHON_TYPES[parameter["type"]]
    if parameter["required"]:
        return f"    {parameter['name']}: {annotation},"
    default = parameter["default"]
    if default is None:
        return f"    {parameter['name']}: Optional[{annotation}] = None,"
    return f"    {parameter['name']}: {annotation} = {python_literal(default)},"


def input_line(spec_input):
    if spec_input["kind"] == "file":
        annotation = "str"
    elif spec_input["kind"] == "runs":
        annotation = "Sequence[str]" if not spec_input["number_key"] else "Sequence[tuple[float, str]]"
    else:
        annotation = "Union[float, ArrayLike]"
    if spec_input["alternative"]:
        return f"    {spec_input['name']}: Optional[{annotation}] = None,"
    return f"    {spec_input['name']}: {annotation},"


def spec_function_lines(spec, doc):
    """A function made from a procedure spec: keyword-only, in the order wrap_specs.cc documents."""
    lines = [f"def {spec['kind']}(", "    *,"]
    lines += [input_line(i) for i in spec["inputs"] if not i["alternative"]]
    lines += [parameter_line(p) for p in spec["parameters"] if p["required"]]
    lines += [input_line(i) for i in spec["inputs"] if i["alternative"]]
    lines += [parameter_line(p) for p in spec["parameters"] if not p["required"]]
    if spec["reads_records"]:
        lines += ['    column: str = "",', '    format: str = "",']
    if spec["reads_timed_records"]:
        lines += ["    sample_rate_hz: Optional[float] = None,", '    time_column: str = "",']
    lines.append(") -> ProcedureResult:")
    return lines + docstring(signatures_and_doc(spec["kind"], doc)[1], "    ")


def value_type(value):
    if isinstance(value, dict):
        keys = {type(k).__name__ for k in value} or {"str"}
        values = {type(v).__name__ for v in value.values()} or {"Any"}
        return f"dict[{keys.pop() if len(keys) == 1 else 'Any'}, {values.pop() if len(values) == 1 else 'Any'}]"
    if isinstance(value, tuple):
        items = {type(v).__name__ for v in value}
        return f"tuple[{items.pop()}, ...]" if len(items) == 1 else "tuple[Any, ...]"
    return type(value).__name__


def stubs(inertest):
    specs = {spec["kind"]: spec for spec in inertest.procedure_specs() if spec["generic_function"]}
    lines = docstring(inertest.__doc__, "") + [""] + HEADER.splitlines() + [""]
    for name, value in vars(inertest).items():
        if name.startswith("__") and name != "__version__":
            continue
        if isinstance(value, type):
            lines += [""] + class_lines(name, value)
        elif name in specs:
            lines += [""] + spec_function_lines(specs[name], value.__doc__)
        elif callable(value):
            lines += [""] + function_lines(name, value)
        else:
            lines.append(f"{name}: {value_type(value)}")
    return "\n".join(lines) + "\n"


def main(module_dir, out):
    sys.path.insert(0, module_dir)
    text = stubs(importlib.import_module("inertest"))
    with open(out, "w", encoding="utf-8") as target:
        target.write(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
