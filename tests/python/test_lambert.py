"""Analytic radiance read through numpy: a Lambert plane of albedo a under a normalized distant light
of illuminance E at angle theta reflects L = a / pi * E * cos(theta) (Lambert's cosine law with the
Lambertian BRDF a / pi), times 2^exposure in the colour AOV."""

from __future__ import annotations

import math

import numpy as np
import pytest

import obscura
from lit_plane import ALBEDO, add_lit_plane, add_sun, radiance_tolerance

PIXELS = [(32, 32), (5, 7), (60, 50)]


def expect_radiance(color: np.ndarray, expected: float) -> None:
    for x, y in PIXELS:
        for c in range(3):
            assert color[y, x, c] == pytest.approx(expected, abs=radiance_tolerance(expected, c)), (x, y, c)
        assert color[y, x, 3] == 1.0  # opaque where the plane drew


def test_lambert_plane_under_a_distant_light(delegate: obscura.Delegate) -> None:
    irradiance, theta = 3.0, math.radians(30.0)
    add_lit_plane(delegate)
    add_sun(delegate, irradiance, (math.sin(theta), 0.0, -math.cos(theta)))
    assert delegate.render("/Camera", {"color": "/Buffers/color"}) == obscura.Status.OK
    with delegate.map("/Buffers/color") as mapped:
        assert mapped.array.shape == (64, 64, 4) and mapped.array.dtype == np.float32
        assert not mapped.array.flags.writeable
        expect_radiance(mapped.array, ALBEDO / math.pi * irradiance * math.cos(theta))


def test_exposure_as_a_keyword_argument_scales_the_radiance(delegate: obscura.Delegate) -> None:
    add_lit_plane(delegate)
    add_sun(delegate, 1.0, (0.0, 0.0, -1.0))
    delegate.set_render_settings(exposure=2.0)  # stops
    delegate.render("/Camera", {"color": "/Buffers/color"})
    expect_radiance(delegate.read("/Buffers/color"), ALBEDO / math.pi * 1.0 * 2.0 ** 2.0)


def test_converged_after_the_taa_frames_and_the_final_render(delegate: obscura.Delegate) -> None:
    # docs/INTEGRATION.md: converged stays 0 until taa:frames jittered frames are accumulated; the
    # render after them reports 1. Any change starts again.
    add_lit_plane(delegate)
    add_sun(delegate, 1.0, (0.0, 0.0, -1.0))
    delegate.set_render_settings(taa_frames=4)
    aovs = {"color": "/Buffers/color"}
    assert delegate.render_until_converged("/Camera", aovs) == 5
    delegate.set_render_settings(exposure=1.0)
    delegate.render("/Camera", aovs)
    assert not delegate.converged
    assert delegate.render_until_converged("/Camera", aovs) == 4


def test_unknown_render_setting_raises_with_the_plugins_message(delegate: obscura.Delegate) -> None:
    with pytest.raises(obscura.NotFoundError) as caught:
        delegate.set_render_settings(noSuchSetting=1)
    assert caught.value.status == obscura.Status.NOT_FOUND
    assert "noSuchSetting" in caught.value.message
    with pytest.raises(obscura.InvalidArgumentError, match="taa:frames"):
        delegate.set_render_settings({"taa:frames": 0})  # outside 1-1024
