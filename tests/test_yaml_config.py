"""Typed YAML configuration: values are checked, typos are errors naming the key and file."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import pytest

from world.yaml_config import ConfigError, config_from_mapping, load_yaml_config

CONFIG = Path(__file__).resolve().parents[1] / "config"


@dataclass(frozen=True)
class Inner:
    gain: float = 1.0


@dataclass(frozen=True)
class Outer:
    name: str = "x"
    count: int = 1
    flag: bool = False
    places: dict[int, tuple[float, float]] = field(default_factory=dict)
    inner: Inner = field(default_factory=Inner)
    maybe: float | None = None


def test_nested_values_are_converted():
    config = config_from_mapping(
        Outer, {"count": 3, "places": {1: [1, 2.5]}, "inner": {"gain": 2}, "maybe": 4}
    )
    assert config.places == {1: (1.0, 2.5)}
    assert config.inner == Inner(2.0)
    assert config.maybe == 4.0


@pytest.mark.parametrize(
    ("data", "words"),
    [
        ({"cuont": 3}, ["cuont", "valid keys", "count"]),
        ({"count": "three"}, ["Outer.count", "int"]),
        ({"count": True}, ["Outer.count"]),
        ({"flag": 1}, ["Outer.flag", "true or false"]),
        ({"inner": {"gian": 1}}, ["gian", "gain"]),
        ({"places": {1: "a"}}, ["places"]),
    ],
)
def test_bad_values_name_the_key(data, words):
    with pytest.raises(ConfigError) as info:
        config_from_mapping(Outer, data, source="team.yaml")
    for word in words:
        assert word in str(info.value)
    assert "team.yaml" in str(info.value)


def test_files_in_config_load(tmp_path):
    from agent.team import TeamConfig
    from sim.session import SessionConfig

    assert TeamConfig.from_yaml(CONFIG / "team.yaml").strategy.formation[10] == (-0.6, 0.0)
    assert SessionConfig.from_yaml(CONFIG / "server.yaml").see_interval == 3
    bad = tmp_path / "bad.yaml"
    bad.write_text("robot_types: [0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 2]\n")
    with pytest.raises(ConfigError, match="at most 7"):
        TeamConfig.from_yaml(bad)
    with pytest.raises(ConfigError, match="cannot read"):
        load_yaml_config(Outer, tmp_path / "missing.yaml")


def test_team_file_spells_out_the_built_in_defaults():
    """``naosoccer match`` plays the built-in defaults unless given a team file; the shipped
    config/team.yaml documents them, so the two must not drift apart."""
    from agent.team import TeamConfig

    assert TeamConfig.from_yaml(CONFIG / "team.yaml") == TeamConfig()


def test_match_team_takes_the_file_and_the_name(tmp_path):
    from agent.cli import _match_team

    path = tmp_path / "team.yaml"
    path.write_text("name: Ignored\nstrategy:\n  attack:\n    dribble_kind: dfdl\n")
    team = _match_team("Blue", str(path))
    assert team.name == "Blue"
    assert team.strategy.attack.dribble_kind == "dfdl"
    assert _match_team("Red", None).strategy.attack.dribble_kind == "lfdl"


def test_overrides_set_dotted_keys_and_refuse_bad_ones():
    from world.yaml_config import apply_overrides

    data = {"strategy": {"attack": {"dribble_kind": "lfdl", "stall_s": 4.0}}}
    apply_overrides(data, ["strategy.attack.dribble_kind=dfdl", "strategy.keeper.max_side_m=1"])
    assert data["strategy"]["attack"] == {"dribble_kind": "dfdl", "stall_s": 4.0}
    assert data["strategy"]["keeper"] == {"max_side_m": 1}
    with pytest.raises(ConfigError, match=r"dotted\.key=value"):
        apply_overrides(data, ["strategy.attack.stall_s"])
    with pytest.raises(ConfigError, match="not a mapping"):
        apply_overrides(data, ["strategy.attack.stall_s.deep=1"], "team.yaml")
