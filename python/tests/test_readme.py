"""The README's Python example runs as written (its output folder moved to a temporary one)."""

import re

from conftest import SOURCE


def test_the_readme_s_python_example_runs(tmp_path):
    readme = (SOURCE / "README.md").read_text()
    section = readme[readme.index("\n## Python\n"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert code.count('"exp2-out"') == 1
    code = code.replace('"exp2-out"', repr(str(tmp_path / "exp2-out")))
    names = {}
    exec(compile(code, "README.md (## Python)", "exec"), names)
    assert (tmp_path / "exp2-out" / "timeline.csv").exists()
