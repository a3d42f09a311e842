"""The interactive view of grasps (plotly HTML) renders in a real browser: headless Chromium opens the
file with no network and its screenshot shows the hands of exactly the grasps drawn; graspmix_cli plot
writes it and the picture from a grasps file."""

import json
import re
import shutil
import subprocess

import graspmix
import numpy as np
import pytest
from graspmix import cli
from graspmix.model import GraspSet

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def grasps_file(tmp_path_factory):
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    grasps = model.synthesize(
        graspmix.data_path("mug.pcd"),
        graspmix.SynthesisOptions().updated({"sampling.n_samples": 40, "sampling.n_optimise": 3, "seed": 1}),
    )
    path = tmp_path_factory.mktemp("grasps") / "grasps.json"
    grasps.save(path)
    return path


def _screenshot(html, out):
    # --no-sandbox: the tests may run as root, where Chromium's sandbox refuses to start.
    subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--window-size=900,700",
            "--virtual-time-budget=5000",
            f"--screenshot={out}",
            html.resolve().as_uri(),
        ],
        check=True,
        capture_output=True,
        timeout=180,
    )
    return np.asarray(graspmix.viz.pyplot().imread(out))[..., :3]


def _hue_pixels(img, rgb):
    """Pixels of the 3D scene (left of the legend, below the title) near the hue of an opaque colour drawn
    half transparent over white or grey: the channel order of rgb holds, with clear margins."""
    scene = img[60:, : int(img.shape[1] * 0.68)]
    order = np.argsort(rgb)  # lowest, middle, highest channel of the colour
    lo, mid, hi = (scene[..., i] for i in order)
    return int(np.sum((hi - lo > 0.25) & (hi - mid > 0.08)))


def test_html_is_self_contained(grasps_file, tmp_path):
    html = GraspSet.load(grasps_file).plot(tmp_path / "g.html", top=2)
    text = html.read_text()
    assert "Plotly.newPlot" in text and len(text) > 1_000_000  # plotly.js is inside the page
    assert not re.search(r"<script[^>]+src=[\"']https?://", text)  # and nothing is fetched


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (Debian package chromium, scripts/install.sh)")
def test_html_view_renders_in_chromium(grasps_file, tmp_path):
    loaded = GraspSet.load(grasps_file)
    one = _screenshot(loaded.plot(tmp_path / "one.html", top=1), tmp_path / "one.png")
    two = _screenshot(loaded.plot(tmp_path / "two.html", top=2), tmp_path / "two.png")
    # Not blank: the cloud, the table and the hand differ from the white page.
    assert one.std() > 0.05 and np.mean(one.min(axis=2) < 0.9) > 0.05
    blue, orange = (0x1F / 255, 0x77 / 255, 0xB4 / 255), (1.0, 0x7F / 255, 0x0E / 255)
    # The best grasp's hand (blue) is drawn in both; the second's (orange) only when two are drawn.
    assert _hue_pixels(one, blue) > 2000 and _hue_pixels(two, blue) > 2000
    assert _hue_pixels(one, orange) < 50 < 2000 < _hue_pixels(two, orange)


def test_cli_plot_writes_png_and_html(grasps_file, tmp_path, capsys):
    png, html = tmp_path / "g.png", tmp_path / "g.html"
    argv = ["plot", "--grasps", str(grasps_file), "--top", "2", "--png", str(png), "--html", str(html)]
    assert cli.main(argv) == 0
    assert png.stat().st_size > 20_000 and html.stat().st_size > 1_000_000
    assert "the best 2 of 40 grasps" in capsys.readouterr().out
    mug = str(graspmix.data_path("mug.pcd"))
    assert cli.main(["plot", "--grasps", str(grasps_file), "--cloud", mug, "--png", str(tmp_path / "c.png")]) == 0
    # Bad input: one line on stderr, status 2.
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"format": "graspmix.grasps/1", "grasps": [{"T_world_wrist": [0, 0]}]}))
    for argv in (
        ["plot", "--grasps", str(grasps_file)],
        ["plot", "--grasps", str(bad), "--png", str(png)],
        ["plot", "--grasps", str(tmp_path / "missing.json"), "--png", str(png)],
        ["plot", "--grasps", str(grasps_file), "--top", "0", "--png", str(png)],
    ):
        capsys.readouterr()
        assert cli.main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and err.startswith("graspmix_cli plot"), err


def test_plot_refuses_a_cloud_or_depth_image_replaced_since(tmp_path, capsys):
    """A grasps file records the SHA-256 of the cloud file or depth image it was synthesised on; `plot`, which reads
    that file again, draws it while it is unchanged and refuses it in one line (exit 2) once it was replaced (a
    camera driver writing depth.png again: before, the grasps were drawn over the new scene without a word);
    `--cloud` draws what it is given."""
    from PIL import Image

    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    opts = graspmix.SynthesisOptions().updated({"sampling.n_samples": 20, "sampling.n_optimise": 2, "seed": 1})
    cloud, grasps, png = tmp_path / "view.pcd", str(tmp_path / "g.json"), str(tmp_path / "p.png")
    shutil.copy(graspmix.data_path("mug.pcd"), cloud)
    model.synthesize(str(cloud), opts).save(grasps)
    depth = np.full((480, 640), 800, np.uint16)
    depth[200:280, 280:360] = 760  # a box 4 cm tall under a camera 0.8 m above the table, looking down
    image, d_grasps = tmp_path / "depth.png", str(tmp_path / "d.json")
    Image.fromarray(depth).save(image)
    model.synthesize(depth=str(image), intrinsics=(579.41, 579.41, 320, 239), camera_pose=[0, 0, 0.8, 1, 0, 0, 0],
                     options=opts).save(d_grasps)  # fmt: skip
    for file, replaced_by, made in (
        (cloud, graspmix.data_path("scenes", "packed4.pcd"), grasps),
        (image, None, d_grasps),
    ):
        assert cli.main(["plot", "--grasps", made, "--png", png]) == 0
        if replaced_by is None:
            Image.fromarray(np.roll(depth, 100, axis=1)).save(image)  # the box moved
        else:
            shutil.copy(replaced_by, file)
        capsys.readouterr()
        assert cli.main(["plot", "--grasps", made, "--png", png]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and file.name in err and "changed since" in err, err
    assert cli.main(["plot", "--grasps", grasps, "--cloud", str(cloud), "--png", png]) == 0
