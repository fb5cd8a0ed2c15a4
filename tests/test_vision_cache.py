"""What vision saw is handed to the other trials of a run that see the same image: the same
detections, vision asked once per image (in a process, or across processes through the run's
folder), and nothing left behind."""

from __future__ import annotations

import os

import numpy as np
import pytest

from aileen.experiments import vision_cache
from aileen.perception.perceiver import Detection


class _Counting:
    """A perceiver whose answer depends on the image, counting the images it was asked about."""

    def __init__(self) -> None:
        self.asked = 0

    def __call__(self, image: np.ndarray) -> list[Detection]:
        self.asked += 1
        v = float(image.sum())
        return [Detection(("cv_box", "cv_red", "cv_medium"), (v, 0.0, v + 1, 1.0), (0.0, 0.0, 8.0, 8.0)),
                Detection(("cv_cone", "cv_blue", "cv_small"), (0.5, 0.5, 0.6, 0.6), (1.0, 1.0, 2.0, 2.0), 1, 0.05)]


@pytest.fixture(autouse=True)
def _empty_memory():
    vision_cache._MEMORY.clear()
    yield
    vision_cache._MEMORY.clear()


def _images(n: int, seed: int = 0) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    return [rng.integers(0, 256, size=(16, 16, 3), dtype=np.uint8) for _ in range(n)]


def test_an_image_seen_again_is_answered_as_the_first_time() -> None:
    live = _Counting()
    seen = vision_cache.SharedVision(live)
    imgs = _images(3)
    first = [seen(i) for i in imgs]
    again = [seen(i.copy()) for i in reversed(imgs)]  # equal bytes, other arrays
    assert live.asked == 3
    assert again[::-1] == first == [_Counting()(i) for i in imgs]
    first[0].clear()  # a caller's list is its own
    assert seen(imgs[0]) == again[-1]


def test_another_process_reads_what_one_wrote_and_the_folder_goes_at_the_end() -> None:
    imgs = _images(4, seed=1)
    with vision_cache.shared() as folder:
        assert os.environ[vision_cache.ENV] == str(folder)
        a_live = _Counting()
        a = vision_cache.SharedVision(a_live, os.environ[vision_cache.ENV])
        expected = [a(i) for i in imgs]
        assert len(list(folder.glob("*.pickle"))) == 4 and not list(folder.glob(".part-*"))
        vision_cache._MEMORY.clear()  # as a fresh worker process
        b_live = _Counting()
        b = vision_cache.SharedVision(b_live, folder)
        assert [b(i) for i in imgs] == expected
        assert b_live.asked == 0
    assert not folder.exists()
    assert vision_cache.ENV not in os.environ


def test_an_unreadable_entry_is_seen_again_by_vision(tmp_path) -> None:
    img = _images(1, seed=2)[0]
    (tmp_path / f"{vision_cache.digest(img)}.pickle").write_bytes(b"not a pickle")
    live = _Counting()
    assert vision_cache.SharedVision(live, tmp_path)(img) == _Counting()(img)
    assert live.asked == 1


def test_images_differing_in_one_byte_or_in_shape_are_different_images() -> None:
    img = _images(1, seed=3)[0]
    other = img.copy()
    other[5, 5, 1] ^= 1
    assert vision_cache.digest(img) != vision_cache.digest(other)
    assert vision_cache.digest(img) != vision_cache.digest(img.reshape(8, 32, 3))
