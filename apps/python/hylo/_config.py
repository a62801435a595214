"""Run configurations from a YAML file, a dict, or both.

A dict is written as YAML (JSON is YAML) and parsed by the same reader as ``hylo map --config``:
the same keys, the same errors naming the key path, the same validation.
"""

import json
import math
import os

from . import _hylo

Config = _hylo.Config


def load_config(config=None, overrides=None):
    """A :class:`Config` from a YAML path, a dict with the YAML's keys, a Config, or None (every
    default). ``overrides``: a dict of keys to change (maps merged key by key), e.g.
    ``{"backend": "sliding_window"}``. ValueError names the key path and the reason; OSError
    when the file cannot be read."""
    if config is None:
        loaded = Config.from_yaml("", "<defaults>")
    elif isinstance(config, Config):
        loaded = config
    elif isinstance(config, dict):
        loaded = Config.from_yaml(yaml_text(config), "<dict>")
    elif isinstance(config, (str, os.PathLike)):
        loaded = Config.load(os.fspath(config))
    else:
        raise TypeError(f"config: expected a path, a dict or a hylo.Config, got {type(config).__name__}")
    if overrides:
        loaded = loaded.with_overrides(yaml_text(overrides), "<overrides>")
    return loaded


def yaml_text(mapping):
    """A dict of configuration keys as YAML text (JSON flow style, which YAML reads)."""
    if not isinstance(mapping, dict):
        raise TypeError(f"expected a dict of configuration keys, got {type(mapping).__name__}")
    return json.dumps(_plain(mapping, ""), allow_nan=False)


def _plain(value, path):
    """Only what YAML holds: dicts with string keys, lists, numbers, strings, bools, null."""
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                raise ValueError(f"{path or 'config'}: key {key!r} is not a string")
            out[key] = _plain(item, f"{path}.{key}" if path else key)
        return out
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(item, path) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return ".nan" if math.isnan(value) else (".inf" if value > 0 else "-.inf")
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    raise ValueError(f"{path}: {type(value).__name__} is not a configuration value")
