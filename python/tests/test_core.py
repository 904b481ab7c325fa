"""Figures, units, records and errors."""

import decimal
import json

import numpy as np
import pytest

import inertest


def test_figure_holds_value_unit_uncertainty_and_converts():
    figure = inertest.Figure(1.0, "deg/h", 0.5)
    assert (figure.value, figure.unit, figure.uncertainty) == (1.0, "deg/h", 0.5)
    in_rad_s = figure.to("rad/s")
    assert in_rad_s.unit == "rad/s"
    assert in_rad_s.value == pytest.approx(np.pi / 180 / 3600, rel=1e-15)
    assert in_rad_s.uncertainty == pytest.approx(0.5 * np.pi / 180 / 3600, rel=1e-15)
    assert figure.to_dict() == {"value": 1.0, "unit": "deg/h", "uncertainty": 0.5}
    assert inertest.Figure(2.0, "ppm").to_dict() == {"value": 2.0, "unit": "ppm"}
    assert float(figure) == 1.0


def test_a_figures_annotations_survive_its_conversion_and_its_dict():
    # A noise term the fit did not identify: its upper bound is all it says (to() and to_dict() lost it).
    arw = np.random.default_rng(4).normal(size=20000)
    term = inertest.allan_variance(arw, sample_rate_hz=100.0).noise.rate_ramp
    assert term.identified is False and term.upper_bound > 0.0
    in_deg_s = term.to("deg/s/s")
    assert in_deg_s.identified is False
    assert in_deg_s.upper_bound == pytest.approx(term.upper_bound / 3600.0**2, rel=1e-14)
    assert term.to_dict() == {"value": None, "unit": term.unit, "identified": False, "upper_bound": term.upper_bound}


def test_figure_equals_only_an_equal_figure():
    figure = inertest.Figure(1.0, "deg/h", 0.5)
    assert figure == inertest.Figure(1.0, "deg/h", 0.5)
    assert figure != inertest.Figure(1.0, "deg/h")
    assert figure != None  # noqa: E711 (a TypeError before)
    assert figure not in [None, 1.0, "1.0 deg/h"]


def test_figure_with_unknown_unit_is_an_error():
    with pytest.raises(ValueError, match="furlong"):
        inertest.Figure(1.0, "furlong")


def test_convert_numbers_and_arrays():
    assert inertest.convert(1.0, "deg/s", "deg/h") == pytest.approx(3600.0, rel=1e-15)
    converted = inertest.convert(np.array([1.0, 2.0]), "deg", "arcsec")
    np.testing.assert_allclose(converted, [3600.0, 7200.0], rtol=1e-15)
    with pytest.raises(inertest.Error):
        inertest.convert(1.0, "deg/s", "m")


def test_error_is_a_value_error_with_location():
    with pytest.raises(ValueError) as raised:
        inertest.scale_factor([0.0, 1.0, -1.0], [0.0, 1.0, -1.0], source="points.csv")
    error = raised.value
    assert isinstance(error, inertest.Error)
    assert error.file == "points.csv"
    assert error.line is None
    assert str(error) == "points.csv: " + error.message


def test_record_attributes_are_the_json_members():
    result = inertest.scale_factor([0, 0, 1, 2, -1, -2, 0, 0], [1, 1, 11, 21, -9, -19, 1, 1])
    assert set(result.keys()) == set(result.to_dict())
    assert "scale_factor" in result
    assert isinstance(result.scale_factor, inertest.Figure)
    assert result["scale_factor"] == result.scale_factor
    assert isinstance(result.nonlinearity_curve[0], inertest.Record)
    assert json.loads(result.json()) == result.to_dict()
    assert "scale_factor" in dir(result)
    with pytest.raises(AttributeError, match="no member 'missing'"):
        result.missing  # noqa: B018


def test_module_documents_itself():
    assert "GJB 2426A-2004 5.8.1-5.8.3" in inertest.scale_factor.__doc__
    assert inertest.__version__.count(".") == 2


def test_convert_takes_numpy_scalars_and_arrays_of_any_shape():
    """np.int64(1), np.float32(1) and an IMU's (N, 3) array were refused as 'not a one-dimensional array'."""
    expected = inertest.convert(1.0, "deg/h", "rad/s")
    for value in (np.int64(1), np.float32(1), np.array(1.0)):
        assert inertest.convert(value, "deg/h", "rad/s") == expected
    triad = np.arange(6.0).reshape(2, 3)
    converted = inertest.convert(triad, "deg", "arcsec")
    assert converted.shape == (2, 3)
    np.testing.assert_array_equal(converted, triad * 3600.0)
    np.testing.assert_array_equal(inertest.convert(np.asfortranarray(triad), "deg", "arcsec"), triad * 3600.0)
    # A bool is no quantity, as an array of them is none, and a complex value none (the arrays' caster).
    for value, dtype in ((True, "bool"), (np.array([True, False]), "bool"), (np.array([1.0j]), "complex128")):
        with pytest.raises(TypeError, match="not of dtype " + dtype):
            inertest.convert(value, "deg", "arcsec")
    assert inertest.convert(decimal.Decimal("0.5"), "deg", "arcsec") == 1800.0
