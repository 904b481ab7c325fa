"""The readers hand their buffers to numpy without copies."""

import numpy as np
import pytest

import inertest


def test_text_table_columns_by_name_and_position(tmp_path):
    path = tmp_path / "record.csv"
    path.write_text("# comment\ntime,rate\n0,1.5\n1,2.5\n2,3.5\n")
    table = inertest.read_text_table(str(path))
    assert table.names == ["time", "rate"]
    assert len(table) == 3
    np.testing.assert_array_equal(table["rate"], [1.5, 2.5, 3.5])
    np.testing.assert_array_equal(table[0], [0.0, 1.0, 2.0])
    np.testing.assert_array_equal(table.row_lines, [3, 4, 5])
    assert not table["rate"].flags.owndata  # a view of the reader's vector
    only = inertest.read_text_table(str(path), columns=[2])
    np.testing.assert_array_equal(only[0], [1.5, 2.5, 3.5])
    with pytest.raises(KeyError, match="no column 'missing'"):
        table["missing"]


def test_text_table_bad_cell_names_file_line_and_column(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("rate,output\n1,2\n3,x\n")
    with pytest.raises(inertest.Error) as raised:
        inertest.read_text_table(str(path))
    assert (raised.value.file, raised.value.line, raised.value.column) == (str(path), 3, 3)


def test_binary_record_reads_one_channel(tmp_path):
    path = tmp_path / "record.f32"
    frames = np.arange(12, dtype="<f4").reshape(6, 2)
    frames.tofile(path)
    samples = inertest.read_binary_record(str(path), "f32", channels=2, channel=1)
    np.testing.assert_array_equal(samples, frames[:, 1])
    assert samples.dtype == np.float64


def test_binary_record_of_partial_frames_is_an_error(tmp_path):
    path = tmp_path / "record.f64"
    path.write_bytes(b"\0" * 12)
    with pytest.raises(ValueError, match="4"):
        inertest.read_binary_record(str(path))


def test_paths_may_be_pathlib_paths(tmp_path, source_dir):
    """pathlib.Path, as open() takes it, was a pybind11 TypeError in every reader but the generated ones."""
    path = tmp_path / "record.csv"
    path.write_text("time,rate\n0,1.5\n1,2.5\n")
    np.testing.assert_array_equal(inertest.read_text_table(path)["rate"], [1.5, 2.5])
    np.testing.assert_array_equal(inertest.read_rate_record(path, "csv", "rate"), [1.5, 2.5])
    binary = tmp_path / "record.f64"
    np.arange(3.0).tofile(binary)
    np.testing.assert_array_equal(inertest.read_binary_record(binary), [0.0, 1.0, 2.0])
    plan = source_dir / "examples" / "scale_factor" / "plan.toml"
    assert inertest.validate_plan(plan)["instrument"]["id"] == inertest.validate_plan(str(plan))["instrument"]["id"]


def test_to_dict_keeps_every_column_of_a_file_without_header(tmp_path):
    """Every name of a headerless file is '': to_dict() kept the last column alone."""
    path = tmp_path / "bare.csv"
    path.write_text("1,2\n3,4\n")
    table = inertest.read_text_table(path)
    assert table.names == ["", ""]
    columns = table.to_dict()
    assert list(columns) == ["1", "2"]
    np.testing.assert_array_equal(columns["1"], [1.0, 3.0])
    np.testing.assert_array_equal(columns["2"], [2.0, 4.0])


def test_first_calls_on_threads_before_numpy_is_imported():
    """import inertest without numpy, then first calls on three threads at once: a deadlock in importlib."""
    import subprocess
    import sys

    script = (
        "import threading, inertest\n"
        "done = []\n"
        "def work(): done.append(inertest.scale_factor([0, 1, -1, 2, -2, 0], [0, 1, -1, 2, -2, 0]))\n"
        "threads = [threading.Thread(target=work) for _ in range(3)]\n"
        "[t.start() for t in threads]\n"
        "[t.join() for t in threads]\n"
        "print(len(done))\n"
    )
    completed = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, check=False)
    assert completed.returncode == 0, completed.stderr
    assert completed.stdout.strip() == "3"
