"""Bad option values of every graspmix_cli subcommand: integers out of range or not integers, numbers that
are not finite or out of range, outputs that cannot be written (a missing folder, a folder, a name too
long), input paths that are missing, too long or not UTF-8. Each error must come before the work (the
outputs are checked when the command line is parsed)."""

from __future__ import annotations

from cases import BOX_URDF, DATA, MUG, cli, dumps, grasps_doc, run_folder

LONG = "n" * 300  # a file name over 255 bytes
NOT_UTF8 = "\udcff.json"  # what Python makes of the bytes b"\xff.json" in argv (surrogateescape)

# A cheap valid invocation of every subcommand, with {out} where its output file goes.
BASE = {
    "fit-gmm": ("fit-gmm", "--out", "{out}"),
    "features": ("features", "--cloud", MUG, "--out", "{out}"),
    "learn": ("learn", "--out", "{out}"),
    "synthesize": ("synthesize", "--cloud", MUG, "--samples", "5", "--optimise-top", "0", "--out", "{out}"),
    "acquire": ("acquire", "--object", BOX_URDF, "--out", "{out}"),
    "demo": (
        "demo",
        "--wrist",
        "0,0,0.2185,1,0,0,0",
        "--pregrasp",
        "finger_left_joint=0.05",
        "--close",
        "finger_left_joint=0.0",
        "--out",
        "{out}",
    ),
    "execute": ("execute", "--object", BOX_URDF, "--grasps", "{tmp}/grasps.json"),
    "plot": ("plot", "--grasps", "{tmp}/grasps.json", "--png", "{tmp}/p.png"),
    "hand": ("hand", "--urdf", str(DATA / "hands" / "wsg50.urdf")),
    "experiment": ("experiment", "--preset", "smoke", "--out", "{out}"),
    "benchmark": ("benchmark", "--limit", "1", "--out", "{out}"),
}
OUT_NAME = {
    "fit-gmm": "g.json",
    "features": "f.npz",
    "learn": "m.json",
    "synthesize": "g.json",
    "acquire": "c.pcd",
    "demo": "d.json",
    "experiment": "run",
    "benchmark": "bench",
}
GRASPS = {"grasps.json": dumps(grasps_doc())}
GRASPS_COMMANDS = ("execute", "plot")  # the commands that read {tmp}/grasps.json


def _argv(cmd: str, out: str | None = None, extra=()) -> tuple:
    out = out if out is not None else "{tmp}/" + OUT_NAME.get(cmd, "x")
    return tuple(a.replace("{out}", out) for a in BASE[cmd]) + tuple(extra)


def integer_cases():
    """Integers beyond what C++ takes, not integers, negative seeds."""
    opts = [
        ("fit-gmm", "--seed"),
        ("fit-gmm", "-k"),
        ("fit-gmm", "--max-iter"),
        ("fit-gmm", "--n-init"),
        ("features", "--seed"),
        ("features", "--min-neighbours"),
        ("learn", "--seed"),
        ("learn", "--components"),
        ("synthesize", "--seed"),
        ("synthesize", "--samples"),
        ("synthesize", "--query-samples"),
        ("synthesize", "--top"),
        ("plot", "--top"),
        ("acquire", "--seed"),
        ("demo", "--seed"),
        ("execute", "--rank"),
        ("experiment", "--trials"),
        ("experiment", "--jobs"),
        ("experiment", "--seed"),
        ("benchmark", "--samples"),
        ("benchmark", "--limit"),
    ]
    values = {"2p63": str(2**63), "3e9": "3e9", "huge": "9" * 30, "1.5": "1.5", "minus": "-1", "text": "ten"}
    cases = []
    for i, (cmd, opt) in enumerate(opts):
        # Every option gets 2**63 and one other value, in turn, so every value class meets several commands.
        keys = ["2p63", list(values)[1 + i % (len(values) - 1)]]
        for k in keys:
            if k == "minus" and opt == "--top":
                continue
            files = GRASPS if cmd in GRASPS_COMMANDS else None
            cases.append(cli(f"cli/{cmd}{opt}={k}", *_argv(cmd, extra=(opt, values[k])), names=(opt,), files=files))
    cases.append(
        cli("cli/fit-gmm--seed=max-ok", "fit-gmm", "--seed", str(2**63 - 1), "--out", "{tmp}/g.json", expect="ok")
    )
    return cases


def number_cases():
    """Numbers that are not finite or out of their range."""
    opts = [
        ("features", "--radius", ("nan", "-0.01", "0")),
        ("features", "--voxel-size", ("-1", "nan")),
        ("features", "--crop", ("nan",)),
        ("features", "--viewpoint", ("inf",)),
        ("fit-gmm", "--tol", ("nan", "-1")),
        ("learn", "--max-distance", ("nan", "-1")),
        ("acquire", "--voxel-size", ("-0.003", "nan")),
        ("demo", "--force", ("nan", "0", "-5")),
        ("execute", "--hold-time", ("1e7", "nan", "-1", "inf")),
        ("execute", "--grip-force", ("nan", "-1")),
        ("execute", "--lift-height", ("inf", "0")),
    ]
    cases = []
    for cmd, opt, vals in opts:
        for v in vals:
            n = {"--crop": 6, "--viewpoint": 3}.get(opt, 1)
            args = (opt,) + (v,) + ("0",) * (n - 1)
            cases.append(
                cli(
                    f"cli/{cmd}{opt}={v}",
                    *_argv(cmd, extra=args),
                    names=(opt,),
                    files=GRASPS if cmd == "execute" else None,
                )
            )
    cases.append(
        cli(
            "cli/features--crop=min-above-max",
            *_argv("features", extra=("--crop", "1", "0", "0", "0", "1", "1")),
            names=("--crop",),
        )
    )
    cases.append(
        cli(
            "cli/execute--lift-height=1e6",
            *_argv("execute", extra=("--lift-height", "1e6")),
            names=("lift_height",),
            files=GRASPS,
        )
    )
    for opt, text in (
        ("--wrist", "0,0,nan,1,0,0,0"),
        ("--wrist", "0,0,1"),
        ("--pregrasp", "finger_left_joint=nan"),
        ("--close", "finger_left_joint"),
        ("--pregrasp", "=0.1"),
    ):
        argv = list(_argv("demo"))
        argv[argv.index(opt) + 1] = text
        cases.append(cli(f"cli/demo{opt}={text}", *argv, names=(opt,)))
    cases.append(
        cli(
            "cli/synthesize--approach-axis=nan",
            *_argv("synthesize", extra=("--approach-axis", "0,nan,1")),
            names=("--approach-axis",),
        )
    )
    cases.append(
        cli("cli/execute--hold-time=60-ok", *_argv("execute", extra=("--hold-time", "60")), expect="ok", files=GRASPS)
    )
    return cases


def output_cases():
    """Outputs that cannot be written: checked before the work, so no result is lost."""
    cases = []
    for cmd in OUT_NAME:
        name = OUT_NAME[cmd]
        if cmd in ("experiment", "benchmark"):  # folders: a file in the way, a folder under a file
            cases.append(
                cli(f"cli/{cmd}--out=a-file", *_argv(cmd, "{tmp}/file"), files={"file": "x"}, names=("--out", "file"))
            )
            cases.append(
                cli(
                    f"cli/{cmd}--out=under-a-file", *_argv(cmd, "{tmp}/file/run"), files={"file": "x"}, names=("--out",)
                )
            )
            continue
        cases.append(
            cli(f"cli/{cmd}--out=missing-folder", *_argv(cmd, "{tmp}/nowhere/" + name), names=("--out", "nowhere"))
        )
        cases.append(
            cli(
                f"cli/{cmd}--out=a-folder",
                *_argv(cmd, "{tmp}/folder"),
                files={"folder/x": ""},
                names=("--out", "folder"),
            )
        )
        cases.append(cli(f"cli/{cmd}--out=name-too-long", *_argv(cmd, "{tmp}/" + LONG), names=("--out", "255")))
    cases.append(
        cli("cli/experiment--out=not-utf8", *_argv("experiment", "{tmp}/" + NOT_UTF8), names=("--out", "UTF-8"))
    )
    for cmd, opt, name in (
        ("synthesize", "--png", "p.png"),
        ("acquire", "--picture", "p.png"),
        ("demo", "--cloud-out", "c.pcd"),
        ("features", "--plot", "p.png"),
        ("plot", "--html", "p.html"),
        ("hand", "--png", "p.png"),
        ("demo", "--png", "p.png"),
    ):
        cases.append(
            cli(
                f"cli/{cmd}{opt}=missing-folder",
                *_argv(cmd, extra=(opt, "{tmp}/nowhere/" + name)),
                names=(opt, "nowhere"),
                files=GRASPS if cmd in GRASPS_COMMANDS else None,
            )
        )
    cases.append(cli("cli/synthesize--png=a-folder", *_argv("synthesize", extra=("--png", "{tmp}")), names=("--png",)))
    return cases


def input_cases():
    """Input paths that are missing, folders, too long, not UTF-8."""
    opts = [
        ("features", "--cloud"),
        ("fit-gmm", "--data"),
        ("learn", "--demo"),
        ("synthesize", "--cloud"),
        ("synthesize", "--model"),
        ("synthesize", "--hand"),
        ("acquire", "--object"),
        ("execute", "--grasps"),
        ("execute", "--object"),
        ("execute", "--hand"),
        ("plot", "--grasps"),
        ("plot", "--cloud"),
        ("demo", "--object"),
        ("demo", "--hand"),
        ("experiment", "--objects"),
        ("experiment", "--model"),
        ("benchmark", "--objects"),
        ("hand", "--urdf"),
    ]
    cases = []
    for i, (cmd, opt) in enumerate(opts):
        argv = list(_argv(cmd))
        files = GRASPS if cmd in GRASPS_COMMANDS else None
        for label, value, names in (
            ("missing", "{tmp}/absent.file", ("absent.file",)),
            ("too-long", "{tmp}/" + LONG, ("255",)),
            ("not-utf8", "{tmp}/" + NOT_UTF8, ("UTF-8",)),
            ("a-folder", "{tmp}", ()),
        ):
            if (label == "a-folder") != (i % 3 == 0) and label in ("a-folder", "not-utf8"):
                continue  # folders for a third of the options, non-UTF-8 names for the others
            a = (
                argv + [opt, value]
                if opt not in argv
                else [value if j > 0 and argv[j - 1] == opt else x for j, x in enumerate(argv)]
            )
            cases.append(cli(f"cli/{cmd}{opt}={label}", *a, names=names or (), files=files))
    for label, value in (
        ("missing", "{tmp}/norun"),
        ("a-file", "{tmp}/file"),
        ("too-long", "{tmp}/" + LONG),
        ("empty-folder", "{tmp}/empty"),
    ):
        cases.append(cli(f"cli/report={label}", "report", value, files={"file": "x", "empty/.keep": ""}))
    cases.append(cli("cli/report=ok", "report", "{tmp}/run", files=run_folder(), expect="ok", timeout=120))
    cases.append(
        cli(
            "cli/experiment--objects=empty-list",
            *_argv("experiment", extra=("--objects", "{tmp}/objs.txt")),
            files={"objs.txt": "# nothing\n"},
            names=("objs.txt",),
        )
    )
    cases.append(
        cli(
            "cli/experiment--objects=not-found",
            *_argv("experiment", extra=("--objects", "{tmp}/objs.txt")),
            files={"objs.txt": "nowhere/x.urdf\n"},
            names=("nowhere/x.urdf",),
        )
    )
    cases.append(
        cli(
            "cli/experiment--conditions=Z", *_argv("experiment", extra=("--conditions", "A,Z")), names=("--conditions",)
        )
    )
    cases.append(cli("cli/no-command"))
    cases.append(cli("cli/unknown-command", "frobnicate", names=("frobnicate",)))
    cases.append(
        cli("cli/unknown-option", "learn", "--out", "{tmp}/m.json", "--frobnicate", "1", names=("--frobnicate",))
    )
    cases.append(cli("cli/missing-required", "synthesize", names=("--cloud",)))
    cases.append(cli("cli/ok-unicode-names", "fit-gmm", "--out", "{tmp}/données_é.json", expect="ok"))
    return cases


CASES = integer_cases() + number_cases() + output_cases() + input_cases()
