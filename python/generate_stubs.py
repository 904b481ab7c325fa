"""Writes the type stubs of the built module: the hand-kept part (python/inertest.pyi) and one
function per declared procedure that has no function of its own, made from inertest.procedure_specs()
as the module makes the function itself (python/wrap_specs.cc). Run at build time by CMake:

    generate_stubs.py HAND_KEPT_PYI MODULE_DIR OUT_PYI
"""

import importlib
import json
import sys

PYTHON_TYPES = {"number": "float", "text": "str", "numbers": "Sequence[float]", "boolean": "bool"}


def parameter_line(parameter):
    annotation = "int" if parameter["whole"] else PYTHON_TYPES[parameter["type"]]
    if parameter["required"]:
        return f"    {parameter['name']}: {annotation},"
    default = parameter["default"]
    if default is None:
        return f"    {parameter['name']}: Optional[{annotation}] = None,"
    return f"    {parameter['name']}: {annotation} = {json.dumps(default)},"


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


def function_stub(spec):
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
    lines.append(f'    """{spec["title"]} ({spec["clause"]}). Members: {", ".join(spec["fields"])}."""')
    return "\n".join(lines)


def main(hand_kept, module_dir, out):
    sys.path.insert(0, module_dir)
    inertest = importlib.import_module("inertest")
    stubs = [function_stub(spec) for spec in inertest.procedure_specs() if spec["generic_function"]]
    with open(hand_kept, encoding="utf-8") as source:
        text = source.read()
    text += "\n# generated from the procedure specs (python/generate_stubs.py)\n\n" + "\n\n".join(stubs) + "\n"
    with open(out, "w", encoding="utf-8") as target:
        target.write(text)


if __name__ == "__main__":
    main(*sys.argv[1:])
