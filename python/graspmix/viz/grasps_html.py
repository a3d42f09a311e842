"""An interactive 3D view of grasps as one self-contained HTML file (plotly, with plotly.js inside: it
opens in any browser without a network): the cloud, the support plane, the hands of the best grasps as
their links' collision meshes, and each grasp's tool centre point with its rank, log-likelihood and opening
on hover."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .plots import COLOURS, grasp_drawing

# matplotlib's tab10 colours of plots.COLOURS, as plotly takes them.
_RGB = {
    "tab:blue": "#1f77b4",
    "tab:orange": "#ff7f0e",
    "tab:green": "#2ca02c",
    "tab:red": "#d62728",
    "tab:purple": "#9467bd",
}


def _mesh(go, W, T, colour, opacity, name, legend):
    return go.Mesh3d(
        x=W[:, 0],
        y=W[:, 1],
        z=W[:, 2],
        i=T[:, 0],
        j=T[:, 1],
        k=T[:, 2],
        color=colour,
        opacity=opacity,
        name=name,
        legendgroup=name,
        showlegend=legend,
        flatshading=True,
        hoverinfo="name",
    )


def grasps_figure(
    grasps,
    hand=None,
    *,
    cloud=None,
    plane=None,
    top: int = 3,
    max_points: int = 20000,
    seed: int = 0,
    title: str | None = None,
):
    """The plotly Figure of plot_grasps_html (same arguments but path)."""
    import plotly.graph_objects as go

    d = grasp_drawing(grasps, hand, cloud=cloud, plane=plane, top=top, max_points=max_points, seed=seed)
    traces = []
    if d.plane_patch is not None:
        square = np.array([[0, 1, 2], [0, 2, 3]])
        traces.append(_mesh(go, d.plane_patch, square, "#9a9a9a", 0.35, "support plane", True))
    if len(d.points):
        traces.append(
            go.Scatter3d(
                x=d.points[:, 0],
                y=d.points[:, 1],
                z=d.points[:, 2],
                mode="markers",
                marker={"size": 1, "color": "#505050"},
                name="cloud",
                hoverinfo="skip",
            )
        )
    for k, meshes in enumerate(d.hands):
        colour = _RGB[COLOURS[k % len(COLOURS)]]
        for n, (W, T) in enumerate(meshes):
            traces.append(_mesh(go, W, T, colour, 0.75 if k == 0 else 0.45, d.labels[k], n == 0))
        if d.tcps[k] is not None:
            t = d.tcps[k]
            traces.append(
                go.Scatter3d(
                    x=[t[0]],
                    y=[t[1]],
                    z=[t[2]],
                    mode="markers",
                    marker={"size": 4, "color": "black"},
                    name=f"TCP {d.labels[k]}",
                    legendgroup=d.labels[k],
                    showlegend=False,
                    hovertext=[f"TCP {d.labels[k]}"],
                    hoverinfo="text",
                )
            )
    fig = go.Figure(traces)
    fig.update_layout(
        title=title or "graspmix: the best grasps (drag to rotate, scroll to zoom)",
        scene={"aspectmode": "data", "xaxis_title": "x (m)", "yaxis_title": "y (m)", "zaxis_title": "z (m)"},
        margin={"l": 0, "r": 0, "t": 40, "b": 0},
        paper_bgcolor="white",
    )
    return fig


def plot_grasps_html(grasps, hand=None, path=None, **options) -> Path:
    """Writes the grasps as a self-contained interactive HTML page (plotly.js included: no network is needed
    to open it) and returns its path. grasps, hand and the options: as graspmix.viz.plot_grasps (top,
    cloud, plane, max_points, seed, title)."""
    if path is None:
        raise ValueError("plot_grasps_html: give the path of the .html file to write")
    fig = grasps_figure(grasps, hand, **options)
    fig.write_html(str(path), include_plotlyjs=True, full_html=True)
    return Path(path)


def plot_grasp_set(grasp_set, path=None, *, cloud=None, **options):
    """What GraspSet.plot calls: an .html path gets the interactive view, any other path (or None) the
    matplotlib picture (plots.plot_grasps)."""
    from .plots import plot_grasps

    if path is not None and Path(path).suffix.lower() in (".html", ".htm"):
        return plot_grasps_html(grasp_set, path=path, cloud=cloud, **options)
    return plot_grasps(grasp_set, path=path, cloud=cloud, **options)
