"""What the uncertainty scripts (uq_sdel.py, uq_band.py, sensitivity.py) share: their bad-input error (exit 2,
one line naming the file) and how they read a JSON file and OpenTURNS."""
import json


class BadInput(Exception):
    pass


def read_json(path, what):
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        raise BadInput(f"{path}: no such file ({what})")
    except (OSError, json.JSONDecodeError) as e:
        raise BadInput(f"{path}: not readable JSON ({what}): {e}")


def import_openturns():
    try:
        import openturns as ot  # noqa: PLC0415 (a clear message when it is missing)
    except ImportError as e:
        raise BadInput(f"OpenTURNS is not installed ({e}): bash pipelines/install-deps.sh (python3-openturns)")
    return ot
