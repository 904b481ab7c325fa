"""The example of python/README.md runs as written, from the top of the source tree."""

import os
import re

import inertest  # noqa: F401  (the example imports it too)


def test_readme_example_runs(source_dir, capsys):
    text = (source_dir / "python" / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.DOTALL)
    assert blocks, "python/README.md has no ```python block"
    previous = os.getcwd()
    os.chdir(source_dir)
    try:
        for block in blocks:
            exec(compile(block, "python/README.md", "exec"), {})
    finally:
        os.chdir(previous)
    printed = capsys.readouterr().out
    assert "pulse/s/(deg/s)" in printed
