"""Shared fixtures of the Python module's tests: the source tree and the built CLI.

ctest sets INERTEST_SOURCE_DIR and INERTEST_CLI (python/CMakeLists.txt); run by hand, the defaults
are this checkout and build/bin/inertest.
"""

import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("INERTEST_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = pathlib.Path(os.environ.get("INERTEST_CLI", SOURCE_DIR / "build" / "bin" / "inertest"))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


def run_cli(*arguments):
    """Runs the CLI; returns (exit status, stdout, stderr)."""
    completed = subprocess.run([str(CLI), *map(str, arguments)], capture_output=True, text=True, check=False)
    return completed.returncode, completed.stdout, completed.stderr


def cli_json(*arguments):
    """The CLI's --json output, parsed; the command must succeed."""
    status, stdout, stderr = run_cli(*arguments, "--json")
    assert status == 0, stderr
    return json.loads(stdout)


def cli_error(*arguments):
    """The CLI's message after 'inertest: error: '; the command must fail with status 2."""
    status, _, stderr = run_cli(*arguments)
    assert status == 2, stderr
    prefix = "inertest: error: "
    assert stderr.startswith(prefix), stderr
    return stderr[len(prefix) :].rstrip("\n")
