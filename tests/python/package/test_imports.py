"""What `import graspmix` and a synthesis from the command line load (issue 15: a lean import path), each in a
fresh interpreter: the layers above the model, matplotlib, pybullet, scipy and importlib.metadata load when
first used, and everything they export is still reachable from the package."""

import json
import os
import subprocess
import sys

import graspmix
import pytest
from graspmix.io import data_path

HEAVY = [
    "matplotlib",
    "pybullet",
    "scipy",
    "importlib.metadata",
    "hashlib",
    "subprocess",
    "graspmix.sim",
    "graspmix.viz",
    "graspmix.experiment",
]


def _loaded_after(code: str) -> dict:
    """{module: loaded?} for HEAVY after running `code` in a fresh interpreter with this one's path."""
    probe = f"{code}\nimport json, sys\nprint(json.dumps({{m: m in sys.modules for m in {HEAVY!r}}}))"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p)}
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_graspmix_loads_no_layer_above_the_model():
    loaded = _loaded_after("import graspmix")
    assert not any(loaded.values()), loaded


def test_cli_synthesis_loads_neither_pictures_nor_simulator(tmp_path):
    code = (
        "from graspmix.cli.main import main\n"
        f"assert main(['synthesize', '--cloud', {str(data_path('mug.pcd'))!r}, '--out', "
        f"{str(tmp_path / 'g.json')!r}, '--samples', '50', '--optimise-top', '2']) == 0"
    )
    loaded = _loaded_after(code)
    assert not any(loaded[m] for m in ("matplotlib", "pybullet", "graspmix.viz", "graspmix.experiment")), loaded
    assert json.loads((tmp_path / "g.json").read_text())["grasps"]


def _thread_settings(extra_env: dict) -> dict:
    """numpy's BLAS threads (threadpoolctl, which reads the loaded library) and OMP_WAIT_POLICY after `import
    graspmix` in a fresh interpreter whose environment has none of the variables but extra_env."""
    probe = (
        "import graspmix, os, json\n"
        "from threadpoolctl import threadpool_info\n"
        "blas = [i['num_threads'] for i in threadpool_info() if i['internal_api'] == 'openblas']\n"
        "print(json.dumps({'blas': blas, 'wait': os.environ.get('OMP_WAIT_POLICY')}))"
    )
    env = {
        k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_WAIT_POLICY")
    }
    env.update(extra_env, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), OMP_NUM_THREADS="2")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_keeps_blas_on_one_thread_and_openmp_waiting_passively_unless_the_user_chose():
    # numpy's OpenBLAS threads spin on a core the C++ core's OpenMP threads need (docs/performance.md)
    chosen = _thread_settings({})
    assert chosen["blas"] and set(chosen["blas"]) == {1}
    assert chosen["wait"] == "PASSIVE"
    user = _thread_settings({"OPENBLAS_NUM_THREADS": "2", "OMP_WAIT_POLICY": "ACTIVE"})
    assert set(user["blas"]) == {2}
    assert user["wait"] == "ACTIVE"


def test_star_import_loads_neither_simulator_nor_pictures():
    loaded = _loaded_after("from graspmix import *")
    assert not any(loaded[m] for m in ("matplotlib", "pybullet", "graspmix.sim", "graspmix.experiment")), loaded


def test_star_import_gives_the_package_names_and_no_simulator():
    names = {}
    exec("from graspmix import *", names)  # noqa: S102
    assert {"GraspModel", "Grasp", "learn", "segment_scene", "data_path", "plot_grasps", "viz"} <= set(names)
    assert not {"sim", "experiment", "clutter"} & set(names)


@pytest.mark.parametrize("name", ["sim", "viz", "experiment", "clutter", "plot_grasps", "plot_grasps_html"])
def test_lazy_names_are_reachable(name):
    assert getattr(graspmix, name) is not None
    assert name in dir(graspmix)


def test_unknown_attribute_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no_such_thing"):
        graspmix.no_such_thing  # noqa: B018


def test_version_is_the_distributions_or_the_cores():
    assert graspmix.__version__ == graspmix.io.package_version()
    assert graspmix.__version__.count(".") >= 2


def test_every_command_group_declares_the_commands_it_adds():
    import argparse

    from graspmix.cli.main import GROUPS, build_parser

    for group in GROUPS:
        sub = argparse.ArgumentParser().add_subparsers()
        group.add_parsers(sub)
        assert tuple(sub.choices) == group.COMMANDS, group.__name__
    everything = build_parser()._subparsers._group_actions[0].choices
    assert sorted(everything) == sorted(c for g in GROUPS for c in g.COMMANDS)
    only = build_parser("synthesize")._subparsers._group_actions[0].choices
    assert sorted(only) == sorted(next(g for g in GROUPS if "synthesize" in g.COMMANDS).COMMANDS)
