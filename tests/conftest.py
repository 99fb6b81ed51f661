"""Shared test set-up: the independent references (tests/independent.py) and mission
builders (tests/helpers.py) are importable from every test folder."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
