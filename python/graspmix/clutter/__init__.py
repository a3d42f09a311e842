"""The clutter-removal protocol (Breyer et al. 2020, VGN; Jiang et al. 2021, GIGA) in graspmix's Bullet
simulation, and the top-down baseline planner.

    from graspmix import clutter
    p = clutter.ClutterProtocol(objects=5, scenes=40, modes=["pile", "packed"], methods=["gmm", "topdown"])
    clutter.run_clutter(p, "runs/clutter", jobs=2)   # clutter.json, clutter_attempts.csv, summary.json,
                                                     # report.md, clutter.png; running again resumes

Per scene (make_scene: N objects from the object list, pile or packed, a seed from the run's seed and the
scene index, shared by every method), repeat: observe (acquire_scene), plan (a method's model with target
"all", or plan_topdown on segment_scene's objects), execute the best grasp in the scene, go on with the
scene that remains; stop when the table is clear, after 2 failures in a row, or when the planner finds
no grasp (VGN's rules). Modules: protocol (settings, seeds, CSV columns), rounds (the loop with injectable
stages, the real stages), runner, report (GSR, DR with Wilson intervals), topdown (the baseline).

ClutterProtocol(task="named", targets=K) measures instead what a user asks for most: per scene, K objects
named by a point on their visible surface, each lifted or not on the untouched scene (modules named: the
target rule, the point, the outcome "wrong object", the unit; named_report: its summary and report).
"""

from .protocol import (
    CLUTTER_CSV,
    CLUTTER_CSV_NAME,
    CLUTTER_NAME,
    MAX_CONSECUTIVE_FAILURES,
    MODES,
    OUTCOMES,
    PLANNERS,
    STOPS,
    ClutterProtocol,
    default_object_list,
    load_clutter_protocol,
)
from .report import build_clutter_report, results_table, summarize
from .rounds import Plan, Stages, real_stages, run_round, run_scene
from .runner import done_rounds, run_clutter
from .topdown import check_hand, narrowest_axis, plan_topdown, topdown_grasp

__all__ = [
    "CLUTTER_CSV",
    "CLUTTER_CSV_NAME",
    "CLUTTER_NAME",
    "MAX_CONSECUTIVE_FAILURES",
    "MODES",
    "OUTCOMES",
    "PLANNERS",
    "STOPS",
    "ClutterProtocol",
    "default_object_list",
    "load_clutter_protocol",
    "build_clutter_report",
    "results_table",
    "summarize",
    "Plan",
    "Stages",
    "real_stages",
    "run_round",
    "run_scene",
    "done_rounds",
    "run_clutter",
    "check_hand",
    "narrowest_axis",
    "plan_topdown",
    "topdown_grasp",
]
