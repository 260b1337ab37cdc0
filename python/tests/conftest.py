"""Shared helpers of the pytest suite: the repository root and the CLI binary to compare with."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def cli_binary() -> Path:
    """The `dyncontact` binary: $DYNCONTACT_BIN (scripts/test-all.sh sets it to the one
    `cargo test` built), else target/release or target/debug."""
    env = os.environ.get("DYNCONTACT_BIN")
    candidates = [Path(env)] if env else [ROOT / "target/release/dyncontact", ROOT / "target/debug/dyncontact"]
    for c in candidates:
        if c.is_file():
            return c
    pytest.fail(f"no dyncontact binary (looked at {', '.join(map(str, candidates))}); build it with cargo build")


def cli_json(*args: str, cwd: Path = ROOT) -> dict:
    """Runs the CLI with `--json` and returns its JSON output."""
    out = subprocess.run(
        [str(cli_binary()), *args, "--json"], cwd=cwd, capture_output=True, text=True, timeout=600
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)
