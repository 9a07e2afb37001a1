"""Typed configuration from YAML: a frozen dataclass filled from a mapping, validated with clear
errors.

Every configurable part of naosoccer (server, referee, agents, training) declares its settings as
a frozen dataclass with defaults; this module turns a YAML file or mapping into such an object
and rejects unknown keys and wrong types, naming the key and the file, so a typo never silently
falls back to a default.
"""

from __future__ import annotations

import dataclasses
import types
import typing
from collections.abc import Mapping
from pathlib import Path
from typing import Any, TypeVar

import yaml

T = TypeVar("T")


class ConfigError(ValueError):
    """A configuration file or mapping does not match its dataclass."""


def load_yaml_config(cls: type[T], path: str | Path) -> T:
    """Read ``path`` (YAML mapping) into the dataclass ``cls``."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text()) or {}
    except OSError as exc:
        raise ConfigError(f"cannot read config file {path}: {exc}") from None
    except yaml.YAMLError as exc:
        raise ConfigError(f"{path} is not valid YAML: {exc}") from None
    return config_from_mapping(cls, data, source=str(path))


def apply_overrides(data: dict[str, Any], overrides: list[str], source: str = "<mapping>") -> None:
    """Set each ``dotted.key=value`` of ``overrides`` in the nested mapping ``data`` (the value
    read as YAML, missing levels created), so that comparing two settings is one command line
    (``--set``) rather than a hand-edited copy of a settings file."""
    for item in overrides:
        dotted, sep, text = item.partition("=")
        if not sep or not dotted:
            raise ConfigError(f"a setting is dotted.key=value, got {item!r}")
        *parents, leaf = dotted.split(".")
        node = data
        for name in parents:
            node = node.setdefault(name, {})
            if not isinstance(node, dict):
                raise ConfigError(f"{dotted}: {name} is not a mapping in {source}")
        node[leaf] = yaml.safe_load(text)


def config_from_mapping(cls: type[T], data: Any, source: str = "<mapping>") -> T:
    """Build ``cls`` from ``data``, checking keys and value types."""
    if not isinstance(data, Mapping):
        raise ConfigError(
            f"{source}: expected a mapping for {cls.__name__}, got {type(data).__name__}"
        )
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}
    unknown = sorted(set(data) - set(fields))
    if unknown:
        raise ConfigError(
            f"{source}: unknown key(s) {', '.join(map(str, unknown))} for {cls.__name__}; "
            f"valid keys: {', '.join(fields)}"
        )
    hints = typing.get_type_hints(cls)
    values = {
        name: _coerce(hints[name], value, f"{source}: {cls.__name__}.{name}")
        for name, value in data.items()
    }
    try:
        return cls(**values)
    except (TypeError, ValueError) as exc:
        raise ConfigError(f"{source}: {exc}") from None


def _coerce(hint: Any, value: Any, where: str) -> Any:
    """Check ``value`` against a (simple) type hint; ints are accepted where floats are wanted."""
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        for option in typing.get_args(hint):
            try:
                return _coerce(option, value, where)
            except ConfigError:
                continue
        raise ConfigError(f"{where}: {value!r} is not a valid {hint}")
    if hint is type(None):
        if value is None:
            return None
        raise ConfigError(f"{where}: expected null, got {value!r}")
    if dataclasses.is_dataclass(hint):
        return config_from_mapping(hint, value, where)
    if origin is dict:
        if not isinstance(value, Mapping):
            raise ConfigError(f"{where}: expected a mapping, got {value!r}")
        key_hint, value_hint = typing.get_args(hint) or (Any, Any)
        return {
            _coerce(key_hint, k, where): _coerce(value_hint, v, f"{where}[{k}]")
            for k, v in value.items()
        }
    if origin in (tuple, list):
        if not isinstance(value, (list, tuple)):
            raise ConfigError(f"{where}: expected a list, got {value!r}")
        args = typing.get_args(hint)
        item_hint = args[0] if args else Any
        items = [_coerce(item_hint, item, where) for item in value]
        return tuple(items) if origin is tuple else items
    if hint is Any:
        return value
    if hint is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ConfigError(f"{where}: expected a number, got {value!r}")
        return float(value)
    if hint is bool:
        if not isinstance(value, bool):
            raise ConfigError(f"{where}: expected true or false, got {value!r}")
        return value
    if isinstance(hint, type):
        if hint is int and isinstance(value, bool):
            raise ConfigError(f"{where}: expected an integer, got {value!r}")
        if not isinstance(value, hint):
            raise ConfigError(f"{where}: expected {hint.__name__}, got {value!r}")
    return value
