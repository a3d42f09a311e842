"""The synthesis flags: one set, named one way, for synthesize, experiment and clutter, each flag changing exactly
the option it names; --set reaches every other setting; bad values are one line and exit status 2."""

import json

import pytest
from graspmix import SynthesisOptions, data_path
from graspmix.cli import build_parser, main
from graspmix.cli.synthesis_flags import SWITCHES, VALUE_FLAGS, synthesis_options
from graspmix.model.options import options_field_names

SUB = build_parser()._subparsers._group_actions[0].choices
# A value of each flag's type that differs from its default.
VALUES = {
    "--samples": "17",
    "--optimise-top": "3",
    "--query-samples": "250",
    "--query-components": "4",
    "--annealing-iterations": "20",
    "--table-clearance": "0.01",
    "--collision": "occupancy",
    "--stand-off": "0.15",
    "--approach-clearance": "0.004",
    "--friction": "0.8",
    "--workspace": "0,0.1,0,0.2,0.3,0.4",
}
# The option's value of a flag's text, where it is not the default's type applied to the text.
PARSED = {"--workspace": [0.0, 0.1, 0.0, 0.2, 0.3, 0.4]}


def _get(options, path):
    value = options
    for part in path.split("."):
        value = getattr(value, part)
    return value


@pytest.mark.parametrize("command", ["synthesize", "experiment", "clutter"])
def test_every_command_takes_the_same_flags(command):
    flags = {o for a in SUB[command]._actions for o in a.option_strings}
    for flag, _, _ in VALUE_FLAGS:
        assert flag in flags, (command, flag)
    for name, _, _ in SWITCHES:
        assert {f"--{name}", f"--no-{name}"} <= flags, (command, name)
    assert "--set" in flags


@pytest.mark.parametrize("flag, path", [(f, p) for f, p, _ in VALUE_FLAGS])
def test_a_value_flag_changes_its_option_and_nothing_else(flag, path):
    args = SUB["synthesize"].parse_args(["--cloud", "x.pcd", flag, VALUES[flag]])
    got = synthesis_options(args)
    value = PARSED[flag] if flag in PARSED else type(_get(SynthesisOptions(), path))(VALUES[flag])
    expected = SynthesisOptions().updated({path: value})
    assert got == expected and got != SynthesisOptions()


@pytest.mark.parametrize("name, path", [(n, p) for n, p, _ in SWITCHES])
def test_a_switch_turns_its_option_off_and_on(name, path):
    off = synthesis_options(SUB["synthesize"].parse_args(["--cloud", "x", f"--no-{name}"]))
    assert off == SynthesisOptions().updated({path: False})
    # On over a base that had it off: the paper's options have no clear approach and no contact quality.
    on = synthesis_options(SUB["synthesize"].parse_args(["--cloud", "x", f"--{name}"]), SynthesisOptions.paper())
    assert _get(on, path) not in (None, False)


def test_set_reaches_any_field_and_parses_its_value():
    argv = ["--cloud", "x", "--set", "query.max_iter=50", "--set", "approach.hand_axis=[1,0,0]"]
    argv += ["--set", "collision.model=occupancy", "--set", "kinematic=null", "--set", "seed=4"]
    o = synthesis_options(SUB["synthesize"].parse_args(argv))
    assert o.query.max_iter == 50 and list(o.approach.hand_axis) == [1, 0, 0]
    assert o.collision.model == "occupancy" and o.kinematic is None and o.seed == 4
    assert "query.max_iter" in options_field_names()


def test_list_settings_prints_every_name(capsys):
    assert main(["synthesize", "--list-settings"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert [line.split(" = ")[0] for line in lines] == options_field_names()


@pytest.mark.parametrize(
    "extra, named",
    [
        (["--set", "sampling.bogus=1"], "sampling.bogus"),
        (["--set", "nothing"], "--set"),
        (["--set", "query.n_samples=many"], "query.n_samples"),
        (["--friction", "0"], "--friction"),
        (["--stand-off", "-1"], "--stand-off"),
        (["--collision", "voxels"], "--collision"),
    ],
)
def test_bad_flags_are_one_line_and_status_2(extra, named, capsys, tmp_path):
    rc = main(["synthesize", "--cloud", str(data_path("mug.pcd")), "--out", str(tmp_path / "g.json"), *extra])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and named in err


def test_the_experiment_records_the_flags_in_its_protocol(tmp_path, capsys):
    """--preset paper plus flags: the protocol's options are the preset's with the flags applied."""
    objs = tmp_path / "objects.txt"
    objs.write_text("cube_small.urdf\n")
    out = tmp_path / "run"
    argv = ["experiment", "--preset", "paper", "--objects", str(objs), "--trials", "1", "--conditions", "C"]
    argv += ["--methods", "gmm", "--samples", "20", "--contact-quality", "--out", str(out), "--quiet"]
    assert main(argv) == 0
    capsys.readouterr()
    recorded = json.loads((out / "protocol.json").read_text())["protocol"]["synthesis"]
    expected = SynthesisOptions.paper().updated({"sampling.n_samples": 20, "contact_quality": True})
    assert SynthesisOptions.from_dict(recorded) == expected
