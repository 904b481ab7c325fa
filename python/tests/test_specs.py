"""The registry seen from Python (issue 22): every plan kind has a function, and the functions made
from the procedure specs give what the CLI gives."""

import json

import numpy
import numpy as np
import pytest

import inertest
from conftest import cli_json

# Plan kinds whose function has another name: contracts of the Python module since issue 10.
PYTHON_NAMES = {
    "bandwidth": "bandwidth_and_delay",
    "bias_temperature": "bias_temperature_sensitivity",
    "centrifuge": "calibrate_drift_coefficients",
    "threshold": "threshold_rate_table",
}



def test_every_plan_kind_has_a_function():
    kinds = inertest.plan_kinds()
    assert "polarity" in kinds and "scale_factor" in kinds and "hand_checks" in kinds
    for kind in kinds:
        name = PYTHON_NAMES.get(kind, kind)
        assert callable(getattr(inertest, name, None)), f"plan kind {kind} has no inertest.{name}"


def test_hand_checks_is_the_cli_json():
    expected = cli_json("hand-checks", "--check", "name=Insulation resistance,value=120,unit=Mohm,min=20",
                        "--check", "name=Appearance,value=pass")
    result = inertest.hand_checks([{"name": "Insulation resistance", "value": 120, "unit": "Mohm", "min": 20},
                                   {"name": "Appearance", "value": "pass"}])
    assert result.to_dict() == expected
    assert result.all_pass and result.insulation_resistance.unit == "Mohm"
    failed = inertest.hand_checks([{"name": "Insulation resistance", "value": 12.5, "unit": "Mohm", "min": 20}])
    assert not failed.all_pass and not failed.check_pass.insulation_resistance
    with pytest.raises(inertest.Error, match="unknown key 'limit'"):
        inertest.hand_checks([{"name": "Insulation resistance", "value": 120, "limit": 20}])
    with pytest.raises(inertest.Error, match="a number, \"pass\" or \"fail\""):
        inertest.hand_checks([{"name": "Appearance", "value": "good"}])
    # None, a bool or an array where a number goes was a pybind11 RuntimeError naming nothing (or 1.0).
    for key, value in [("min", None), ("value", None), ("value", True), ("max", np.array([1.0, 2.0]))]:
        check = {"name": "Insulation resistance", "value": 120, "unit": "Mohm", key: value}
        with pytest.raises(inertest.Error, match=f"hand check: '{key}' must be a number"):
            inertest.hand_checks([check])


def test_every_declared_procedure_has_a_function_and_stubs():
    for spec in inertest.procedure_specs():
        function = getattr(inertest, spec["kind"])
        assert callable(function)
        if spec["generic_function"]:
            assert spec["title"] in function.__doc__ and spec["clause"] in function.__doc__


def test_polarity_from_numbers_and_arrays_is_the_cli_json():
    expected = cli_json("polarity", "--positive-output", "-3", "--negative-output", "3")
    result = inertest.polarity(positive=-3, negative=3.0)
    assert result.to_dict() == expected
    assert result.polarity == "negative"
    # An array of samples counts by its mean, with its standard error (s / sqrt(n) = 1), as a record
    # file does; one sample has none.
    samples = inertest.polarity(positive=numpy.array([-2.0, -4.0]), negative=numpy.array([3.0])).to_dict()
    assert samples["output_positive_rate"].pop("uncertainty") == pytest.approx(1.0, rel=1e-15)
    assert samples == expected
    with pytest.raises(inertest.Error, match="within 3 standard errors"):
        inertest.polarity(positive=numpy.array([0.0, 2.2]), negative=numpy.array([1.0, 1.0]))
    assert "Polarity" in result.report()


def test_resolution_from_a_file_is_the_cli_json(tmp_path):
    # The hand case of src/procedures/resolution_test.cc (resolution 4 deg/h), K = 3600 per deg/s.
    steps = tmp_path / "steps.csv"
    b, f0 = 10.0, 36007.0
    rows = [(b, f0, b + 10 / 3600, f0 + 10), (b, f0, b + 5 / 3600, f0 + 5.5), (b, f0, b + 2 / 3600, f0 + 1.2),
            (-b, -f0, -b - 10 / 3600, -f0 - 10), (-b, -f0, -b - 4 / 3600, -f0 - 2.5), (-b, -f0, -b - 3 / 3600, -f0 - 1)]
    steps.write_text("base_rate,base_output,rate,output\n" + "".join(f"{r[0]!r},{r[1]!r},{r[2]!r},{r[3]!r}\n" for r in rows))
    expected = cli_json("resolution", steps, "--scale-factor", "3600")
    result = inertest.resolution(file=str(steps), scale_factor=3600)
    assert result.to_dict() == expected
    assert result.resolution.value == pytest.approx(4.0, rel=1e-9)
    assert result.resolution.unit == "deg/h"


def test_turn_on_time_from_timed_records_is_the_cli_json(tmp_path):
    # The case of src/cli/bias_command_test.cc: error 1, 0.5, 0.2, 0.05, 0.01 deg/h (K = 3600) at
    # t = 1..5 s settles into 0.1 deg/h at 4 s; the column alone at 2 Hz at 2 s.
    timed = tmp_path / "on.csv"
    timed.write_text("t,out\n1,1\n2,0.5\n3,0.2\n4,0.05\n5,0.01\n")
    expected = cli_json("turn-on-time", "--run", f"0:{timed}", "--scale-factor", "3600", "--rest-band", "0.1")
    result = inertest.turn_on_time(run=[(0, str(timed))], scale_factor=3600, rest_band_deg_h=0.1)
    assert result.to_dict() == expected
    column = tmp_path / "on.txt"
    column.write_text("1\n0.5\n0.2\n0.05\n0.01\n")
    by_rate = inertest.warm_up_time(run=[(0, str(column))], sample_rate_hz=2, scale_factor=3600, rest_band_deg_h=0.1)
    assert by_rate.warm_up_time.value == pytest.approx(2.0)


@pytest.mark.parametrize(
    "keywords, message",
    [
        ({"positive": 1.0}, "polarity() needs negative"),
        ({"positive": 1.0, "negative": -1.0, "expected": "up"}, "expected must be one of positive, negative"),
        ({"positive": 1.0, "negative": -1.0, "sign": 1}, "unknown keyword 'sign'"),
        ({"positive": numpy.array([]), "negative": -1.0}, "positive has no samples"),
        ({"positive": "1", "negative": -1.0}, "positive must be a number or an array of samples"),
    ],
)
def test_bad_keywords_raise_inertest_error(keywords, message):
    with pytest.raises(inertest.Error) as raised:
        inertest.polarity(**keywords)
    assert message in str(raised.value)


@pytest.mark.parametrize("number", ["20", None, 20 + 0j, numpy.bool_(True), True])
def test_a_run_whose_number_is_no_number_raises_inertest_error(tmp_path, number):
    """A temperature read by Python's csv module is a string: an inertest.Error naming the run, not
    pybind11's RuntimeError 'Unable to cast Python instance'."""
    points = tmp_path / "points.csv"
    points.write_text("rate,output\n0,0\n10,30\n-10,-30\n0,0\n")
    with pytest.raises(inertest.Error, match=r"run: run 1: its temperature_degC must be a number, got "):
        inertest.scale_factor_temperature(run=[(number, str(points)), (40.0, str(points))])


@pytest.mark.parametrize("positive, dtype", [(numpy.array([1.0 + 1.0j]), "complex128"), (True, "bool")])
def test_samples_of_no_real_numbers_are_refused_naming_their_dtype(positive, dtype):
    """The generated functions' samples pass the arrays' own check: numpy's cast dropped the
    imaginary part, and a bool was a sample of 1."""
    with pytest.raises(TypeError, match="not of dtype " + dtype):
        inertest.polarity(positive=positive, negative=-1.0)


def test_specs_describe_parameters_as_the_plan_names_them():
    specs = {spec["kind"]: spec for spec in inertest.procedure_specs()}
    maximum = specs["maximum_input_rate"]
    assert not maximum["generic_function"]  # its array-based function (issue 10) stays
    names = [parameter["name"] for parameter in maximum["parameters"]]
    assert "nonlinearity_limit_ppm" in names  # the plan key, as the array function takes it
    json.dumps(specs)  # plain data


def test_scale_factor_temperature_from_runs_is_the_cli_json(tmp_path):
    # K = 100, 100.1, 99.7 at 20, 40, -20 degC: Kt = 75 ppm/degC (the CLI test's case).
    rates = [0, 1, -1, 2, -2, 5, -5, 10, -10, 0]
    runs = []
    for temperature, k in [(20, 100.0), (40, 100.1), (-20, 99.7)]:
        path = tmp_path / f"t{temperature}.csv"
        path.write_text("rate,output\n" + "".join(f"{r},{k * r + 0.5!r}\n" for r in rates))
        runs.append((temperature, str(path)))
    listing = tmp_path / "runs.csv"
    listing.write_text("temperature_degC,file\n" + "".join(f"{t},{p}\n" for t, p in runs))
    expected = cli_json("scale-factor-temperature", listing, "--reference-temperature", "20")
    result = inertest.scale_factor_temperature(run=runs, reference_temperature_degC=20)
    assert result.to_dict() == expected
    assert result.scale_factor_temperature_sensitivity.value == pytest.approx(75.0, rel=1e-6)
    with pytest.raises(inertest.Error) as raised:
        inertest.scale_factor_temperature(run=runs, reference_temperature_degC=25)
    assert "matches no run" in str(raised.value)
    with pytest.raises(inertest.Error, match=r"^bias_temperature\(\) needs at least 2 runs in run \(room temperature"):
        inertest.bias_temperature(run=runs[:1], scale_factor=100)
    with pytest.raises(inertest.Error, match=r"^procedure\('bias_temperature'\) needs at least 2 runs in run"):
        inertest.procedure("bias_temperature", run=runs[:1], scale_factor=100)


def test_generated_stubs_name_every_function_class_and_member():
    # The stubs (python/generate_stubs.py, at build time) beside the module: valid Python, a stub for
    # every public name, and every declared field as a member of its procedure's result class.
    import ast
    import pathlib

    stubs = pathlib.Path(inertest.__file__).with_name("inertest.pyi").read_text(encoding="utf-8")
    tree = ast.parse(stubs)
    defined = {node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    defined |= {node.target.id for node in tree.body if isinstance(node, ast.AnnAssign)}
    public = {name for name in vars(inertest) if not name.startswith("_")} | {"__version__"}
    assert public <= defined, f"no stub for {sorted(public - defined)}"
    classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}
    members = {name: {item.target.id for item in node.body if isinstance(item, ast.AnnAssign)}
               for name, node in classes.items()}
    assert {"message", "file", "line", "column"} <= members["Error"]
    assert {"tau", "oadev", "noise", "warnings"} <= members["AllanResult"]
    for spec in inertest.procedure_specs():
        function = next(node for node in tree.body if isinstance(node, ast.FunctionDef) and node.name == spec["kind"])
        # A function made from the spec: each keyword's default is the Python literal of the spec's
        # (True, not JSON's true).
        defaults = dict(zip((a.arg for a in function.args.kwonlyargs), function.args.kw_defaults))
        for parameter in spec["parameters"] if spec["generic_function"] else []:
            if defaults.get(parameter["name"]) is not None:
                assert ast.literal_eval(defaults[parameter["name"]]) == (parameter["default"]), (spec["kind"], parameter)
        result = ast.unparse(function.returns)
        if result != "ProcedureResult":
            assert set(spec["fields"]) | {"procedure"} <= members[result], spec["kind"]
    figure = next(item for item in classes["ScaleFactorResult"].body
                  if isinstance(item, ast.AnnAssign) and item.target.id == "scale_factor")
    assert ast.unparse(figure.annotation) == "Figure"


def test_temperature_model_with_several_sensors_is_the_cli_json(source_dir):
    # A list of texts (ParameterType.texts): the repeated --temperature-column is a list of str.
    record = source_dir / "examples" / "temperature_model" / "ramp.csv"
    options = ["--scale-factor", "36000", "--interval", "60", "--stability-window", "600", "--rate-window", "600"]
    expected = cli_json("temperature-model", record, "--temperature-column", "coil", "--temperature-column", "chamber",
                        *options)
    result = inertest.temperature_model(file=str(record), temperature_column=["coil", "chamber"], scale_factor=36000,
                                        interval_s=60, stability_window_s=600, rate_window_s=600)
    assert result.to_dict() == expected
    assert [row["sensor"] for row in expected["sensors"]] == ["coil", "chamber"]
    with pytest.raises(inertest.Error, match="temperature_column must be a list"):
        inertest.temperature_model(file=str(record), temperature_column="coil", scale_factor=36000)


def test_a_bad_cell_in_a_plan_step_keeps_its_place(tmp_path):
    """run_campaign's Error named points.csv:3:3 in its message, with file, line and column None."""
    (tmp_path / "points.csv").write_text("rate,output\n0,1\n5,x\n")
    plan = tmp_path / "plan.toml"
    plan.write_text('[instrument]\nid = "FOG-1"\noutput_unit = "pulse/s"\n\n'
                    '[[procedure]]\nkind = "scale_factor"\nname = "sf"\nfile = "points.csv"\n')
    with pytest.raises(inertest.Error) as raised:
        inertest.run_campaign(str(plan), str(tmp_path / "out"))
    assert (raised.value.file, raised.value.line, raised.value.column) == (str(tmp_path / "points.csv"), 3, 3)
    assert "procedure 'sf'" in str(raised.value)
    assert not (tmp_path / "out" / "results.json").exists()


def test_pulse_counts_of_a_generic_function_are_the_cli_json(tmp_path):
    # turn_on_time's case above, as counts per 0.5 s interval (the rates 1, 0.5, 0.2, 0.05, 0.01
    # pulse/s settle into 0.1 at 2 s; the counts taken as pulse/s would at 1.5 s); a table of mean
    # outputs (resolution's steps) is taken per second.
    timed = tmp_path / "on.csv"
    timed.write_text("t,out\n0.5,0.5\n1,0.25\n1.5,0.1\n2,0.025\n2.5,0.005\n")
    expected = cli_json("turn-on-time", "--run", f"0:{timed}", "--scale-factor", "3600", "--rest-band", "0.1",
                        "--output-unit", "pulse")
    result = inertest.turn_on_time(run=[(0, str(timed))], scale_factor=3600, rest_band_deg_h=0.1, output_unit="pulse")
    assert result.to_dict() == expected
    assert result.turn_on_time.value == pytest.approx(2.0)
    steps = tmp_path / "steps.csv"
    b, f0 = 10.0, 36007.0
    rows = [(b, f0, b + 10 / 3600, f0 + 10), (b, f0, b + 5 / 3600, f0 + 5.5), (b, f0, b + 2 / 3600, f0 + 1.2),
            (-b, -f0, -b - 10 / 3600, -f0 - 10), (-b, -f0, -b - 4 / 3600, -f0 - 2.5), (-b, -f0, -b - 3 / 3600, -f0 - 1)]
    steps.write_text("base_rate,base_output,rate,output\n" + "".join(f"{r[0]!r},{r[1]!r},{r[2]!r},{r[3]!r}\n" for r in rows))
    per_second = inertest.resolution(file=str(steps), scale_factor=3600, output_unit="pulse/s").to_dict()
    assert inertest.resolution(file=str(steps), scale_factor=3600, output_unit="pulse").to_dict() == per_second


def test_procedure_reaches_every_input_of_a_kind_with_an_array_function(tmp_path):
    # scale_factor's array function takes points; inertest.procedure takes its spec's every input:
    # one long record at 100 Hz (K = 100 pulse/s per deg/s, 10 s at each rate), as rates and as counts.
    rates = [0.0, 10.0, -10.0, 20.0, -20.0, 50.0, -50.0, 0.0]
    record, counts = tmp_path / "long.csv", tmp_path / "counts.csv"
    rows = [(rate, 100.0 * rate * (1.0 + 1e-5 * rate) + 0.3 + 0.01 * (k % 7)) for rate in rates for k in range(1000)]
    record.write_text("rate,output\n" + "".join(f"{rate!r},{output!r}\n" for rate, output in rows))
    counts.write_text("rate,output\n" + "".join(f"{rate!r},{output / 100.0!r}\n" for rate, output in rows))
    expected = cli_json("scale-factor", "--record", str(record), "--sample-rate", "100", "--output-unit", "pulse/s")
    result = inertest.procedure("scale_factor", record=str(record), sample_rate_hz=100, output_unit="pulse/s")
    assert result.to_dict() == expected
    assert result.scale_factor.value == pytest.approx(100.0, rel=1e-3)
    assert inertest.procedure("scale_factor", record=str(counts), sample_rate_hz=100, output_unit="pulse").to_dict() == (
        cli_json("scale-factor", "--record", str(counts), "--sample-rate", "100", "--output-unit", "pulse"))
    # A generic function's kind runs alike either way.
    assert inertest.procedure("polarity", positive=-3, negative=3.0).to_dict() == inertest.polarity(
        positive=-3, negative=3.0).to_dict()
    with pytest.raises(inertest.Error, match="no declared procedure 'scale_factors'"):
        inertest.procedure("scale_factors", record=str(record))
    with pytest.raises(inertest.Error, match=r"procedure\('scale_factor'\) got an unknown keyword 'rates'"):
        inertest.procedure("scale_factor", rates=[1.0])
    with pytest.raises(inertest.Error, match="sample_rate_hz"):
        inertest.procedure("scale_factor", record=str(record))
