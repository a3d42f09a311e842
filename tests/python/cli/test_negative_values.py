"""Option values that start with a minus sign: a comma-separated list of numbers (a pose or a point whose first
coordinate is negative) is a value, as a single negative number is to argparse, not an unknown option."""

import pytest
from graspmix.cli.common import NEGATIVE_NUMBERS
from graspmix.cli.main import build_parser


@pytest.mark.parametrize("text", ["-1", "-.5", "-0.004,0,0.258,1,0,0,0", "-1e-3,+2,-3.5E2", "-0.05,-0.1,0.06"])
def test_negative_number_lists_are_values(text):
    assert NEGATIVE_NUMBERS.match(text)


@pytest.mark.parametrize("text", ["-x", "--out", "-0.1,a", "-1,", "-1,,2", "-"])
def test_other_dashed_words_are_not(text):
    assert not NEGATIVE_NUMBERS.match(text)


def test_demo_takes_a_wrist_with_a_negative_x():
    argv = ["demo", "--wrist", "-0.004,0,0.258,1,0,0,0", "--pregrasp", "finger_left_joint=0.05"]
    args = build_parser("demo").parse_args([*argv, "--close", "finger_left_joint=0", "--out", "d.json"])
    assert args.wrist == "-0.004,0,0.258,1,0,0,0"


def test_a_missing_value_is_still_an_error(capsys):
    with pytest.raises(SystemExit) as e:
        build_parser("demo").parse_args(["demo", "--wrist", "--out", "d.json"])
    assert e.value.code == 2
    assert "--wrist: expected one argument" in capsys.readouterr().err


def test_a_joint_given_twice_is_an_error():
    from graspmix.cli.common import CliError, parse_joints

    assert parse_joints("a=0.05,b=-1", "--pregrasp") == {"a": 0.05, "b": -1.0}
    with pytest.raises(CliError, match="'a' is given twice"):
        parse_joints("a=0.05,a=0.01", "--pregrasp")
