"""The synthesis options on the command line: one set of flags, named one way, for every command that
synthesises (synthesize, experiment, sweep, clutter), and one function that turns them into SynthesisOptions.

Every flag is optional: a flag not given leaves the base options' value (the library's defaults for
`synthesize`, the preset's for `experiment`). Switches are --NAME/--no-NAME. `--set PART.FIELD=VALUE` reaches
every other setting of SynthesisOptions (graspmix_cli synthesize --list-settings prints them). A value for an
expert that is off (--stand-off with --no-clear-approach's options, --friction with the paper's) turns it on.
"""

from __future__ import annotations

import argparse
import json

from ..model.options import COLLISION_MODELS, SynthesisOptions, options_field_names
from .common import CliError, box
from .common import seed as seed_type

_D = SynthesisOptions()  # the defaults, for the help texts

# (flag, option path, argparse keywords); a switch's path is a part (on/off) or a boolean field.
VALUE_FLAGS = (
    ("--samples", "sampling.n_samples", dict(type=int, help="grasps sampled and ranked")),
    ("--optimise-top", "sampling.n_optimise", dict(type=int, help="best grasps annealed")),
    ("--query-samples", "query.n_samples", dict(type=int, help="samples per link (N_Q)")),
    ("--query-components", "query.n_components", dict(type=int, help="K_Q of GMM's Q_i")),
    ("--annealing-iterations", "annealing.iterations", dict(type=int, help="per grasp")),
    (
        "--table-clearance",
        "segmentation.table_clearance",
        dict(type=float, help="m: points this close above the support plane (or below it) are the table"),
    ),
    (
        "--workspace",
        "segmentation.workspace",
        dict(
            type=box,
            metavar="X0,Y0,Z0,X1,Y1,Z1",
            help="m: the box in the world frame the cloud or image is cropped to before anything ([]: none)",
        ),
    ),
    (
        "--collision",
        "collision.model",
        dict(
            choices=list(COLLISION_MODELS),
            help="the collision expert: surface (the cloud's points) or occupancy (what the cameras saw free; "
            "unseen space is solid)",
        ),
    ),
    (
        "--stand-off",
        "approach.stand_off",
        dict(type=float, help="m: where the clear approach starts, back along the approach axis"),
    ),
    (
        "--approach-clearance",
        "approach.clearance",
        dict(
            type=float,
            help="m: the radius of the balls the points become for the open hand's approach (it may enter them by collision.contact_tolerance, 1 mm by default)",
        ),
    ),
    (
        "--friction",
        "contact_quality.friction",
        dict(type=float, help="Coulomb friction coefficient of the contact-quality test"),
    ),
)
SWITCHES = (
    ("optimise", "sampling.optimise", "anneal the best grasps"),
    ("find-plane", "segmentation.find_plane", "search the cloud for the support plane (off: objects only)"),
    (
        "clear-approach",
        "approach",
        "the hard clear-approach expert: the open hand reaches its pre-grasp along its approach axis from the "
        "stand-off without touching anything",
    ),
    (
        "contact-quality",
        "contact_quality",
        "the soft contact-quality expert: the fingers close from the pre-grasp onto the object, the contacts "
        "scored by the antipodal friction-cone test",
    ),
    (
        "grasp-depth",
        "grasp_depth",
        "the soft grasp-depth expert: grasps whose fingertips reach less than grasp_depth.min_depth back into the "
        "object (its points between the fingers) are charged",
    ),
    (
        "completion",
        "completion",
        "complete the unseen side of every object from what the camera saw (mirror or rotation symmetry, else the "
        "footprint extruded to the table) and grasp the completed objects",
    ),
)


def _default_of(path: str):
    value = _D
    for part in path.split("."):
        value = getattr(value, part) if value is not None else None
    return value


def add_synthesis_arguments(
    parser: argparse.ArgumentParser, *, base: str = "the library's default", seed: bool = True
) -> None:
    """The synthesis flags, in a group of their own; `base` says in the help where an absent flag's value comes
    from; seed: a --seed flag for the synthesis' seed (the experiment's --seed is its protocol's base seed)."""
    g = parser.add_argument_group("synthesis options (graspmix.SynthesisOptions)")
    if seed:
        g.add_argument(
            "--seed", dest="synthesis__seed", type=seed_type, default=None, help="seeds everything random (0)"
        )
    for flag, path, kw in VALUE_FLAGS:
        kw = dict(kw, help=f"{kw['help']} ({path}; default: {base}, {_default_of(path)})")
        g.add_argument(flag, dest=_dest(path), default=None, **kw)
    for name, path, text in SWITCHES:
        g.add_argument(
            f"--{name}",
            dest=_dest(path),
            action=argparse.BooleanOptionalAction,
            default=None,
            help=f"{text} ({path}; default: {base})",
        )
    g.add_argument(
        "--set",
        dest="synthesis_set",
        action="append",
        metavar="PART.FIELD=VALUE",
        help="any other synthesis setting, e.g. --set query.max_iter=50 --set approach.step=0.01 (VALUE as JSON: "
        "numbers, true/false, null, [x,y,z]; else text); repeatable; graspmix_cli synthesize --list-settings lists "
        "the names",
    )


def _dest(path: str) -> str:
    return "synthesis__" + path.replace(".", "__")


def synthesis_options(args: argparse.Namespace, base: SynthesisOptions | None = None) -> SynthesisOptions:
    """`base` (default: the library's defaults) with the synthesis flags given on the command line applied, the
    --set ones last; CliError naming the flag for a bad name or value (the bounds are the options' own)."""
    changes, flags = {}, {}  # option path -> value; option path -> the flag that gave it
    given = [(flag, path) for flag, path, _ in VALUE_FLAGS] + [(f"--{name}", path) for name, path, _ in SWITCHES]
    for flag, path in given + [("--seed", "seed")]:
        value = getattr(args, _dest(path), None)
        if value is not None:
            changes[path], flags[path] = value, flag
    for text in getattr(args, "synthesis_set", None) or []:
        name, sep, value = text.partition("=")
        if not sep or not name.strip():
            raise CliError(f"--set: expected PART.FIELD=VALUE, got {text!r}")
        changes[name.strip()], flags[name.strip()] = _parse_value(value.strip()), f"--set {text}"
    try:
        return (base or SynthesisOptions()).updated(changes)
    except ValueError as e:
        named = [flag for path, flag in flags.items() if path in str(e)]
        raise CliError(f"{named[-1] if named else '--set'}: {e}") from None


def _parse_value(text: str):
    try:
        return json.loads(text)
    except ValueError:
        return text


def list_settings() -> str:
    """Every settable name with its default, one a line (what --set takes)."""
    lines = []
    for name in options_field_names():
        lines.append(f"{name} = {_default_of(name)!r}")
    return "\n".join(lines)
