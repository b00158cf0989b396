# SPDX-License-Identifier: Apache-2.0
# Types of `import artcam` (the extension artcam._artcam, re-exported). Docstrings: help(artcam.X).
from os import PathLike
from typing import Any, Literal, Sequence

import numpy as np
import numpy.typing as npt

__version__: str

Filter = Literal["nearest", "bilinear", "bicubic"]
Edge = Literal["transparent", "extend", "black"]
PixelArray = npt.NDArray[np.uint8] | npt.NDArray[np.uint16] | npt.NDArray[np.float32]

class Camera:
    """An ARTcam value: read, fitted or made; maps points and warps images."""
    @property
    def kind(self) -> Literal["single", "chained", "attributed", "layered", "piecewise"]: ...
    @property
    def layers(self) -> int: ...
    @property
    def patches(self) -> int: ...
    @property
    def source_size(self) -> tuple[int, int]: ...
    @property
    def target_size(self) -> tuple[int, int]: ...
    @property
    def frames(self) -> dict[str, tuple[int, int]]: ...
    @property
    def frame(self) -> Literal["sensor", "upright"] | None: ...
    @property
    def name(self) -> str: ...
    def to_json(self) -> str:
        """The camera as .artcam JSON text."""
    def write(self, path: str) -> None:
        """Writes the camera atomically; OSError naming the file and the cause."""
    def map(self, points: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """N×2 source pixels → N×2 target pixels (N×L×2 for L layers); NaN without an image."""
    def warp(self, image: PixelArray, *, depth: npt.ArrayLike | None = None,
             size: tuple[int, int] | None = None, filter: Filter = "bilinear",
             edge: Edge = "transparent", alpha: bool = False, threads: int = 0,
             out: PixelArray | None = None, finish: str | None = None) -> PixelArray:
        """Renders `image` (read in place) through the camera, as `artcam warp` does."""

class Image:
    """A photo as artcam reads it: stored numbers, upright, and what the file said."""
    @property
    def pixels(self) -> PixelArray: ...
    @property
    def info(self) -> dict[str, Any]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def channels(self) -> int: ...

def finishes() -> list[tuple[str, str]]:
    """The finishing marks warp(finish=...) applies: (name, description)."""
def read(path: str) -> Camera:
    """Reads a .artcam file (FileNotFoundError, ValueError naming the place)."""
def from_json(text: str, name: str = "<camera>") -> Camera:
    """A camera from .artcam JSON text."""
def read_image(path: str) -> Image:
    """Reads a photo as `artcam warp` does (FileNotFoundError, ValueError)."""
def write_image(path: str, pixels: PixelArray, *, like: Image | None = None,
                quality: int | None = None, subsampling: str | None = None,
                bit_depth: str | None = None, colourspace: str | None = None,
                colourspace_out: str | None = None) -> None:
    """Writes `pixels` atomically, keeping `like`'s metadata, profile and quality."""

def plan_frames(inputs: Sequence[str], folder: str, *, suffix: str = "", format: str = "",
                first: int | None = None, frames: str | None = None,
                chunk: str | None = None) -> list[tuple[int | None, str, str]]:
    """The (frame, input, output) triples `artcam batch` would work through."""
def check_outputs(outputs: Sequence[str], inputs: Sequence[str], *,
                  overwrite: bool = False) -> None:
    """Refuses outputs as `artcam batch` does (OSError)."""
def warp_files_options_check(options: dict[str, Any]) -> None:
    """Raises ValueError for an option warp_files would refuse."""
def warp_files(camera: Camera, items: Sequence[tuple[str, str]],
               options: dict[str, Any] = ...) -> list[dict[str, Any]]:
    """Each (input, output) through `camera` as `artcam batch` does; one row each."""

def warp(camera: Camera | str, image: PixelArray, **options: Any) -> PixelArray:
    """camera.warp(image, **options), the camera given or read from a path."""

Size = tuple[int, int]
PathArg = str | PathLike[str]
Report = dict[str, Any]

def preset(name: str, **params: Any) -> Camera:
    """A camera from the effects tables or a view camera, as `artcam preset NAME --PARAM V`."""
def presets() -> list[str]:
    """The names preset() takes."""
def preset_listing() -> str:
    """`artcam preset list`: every preset with its parameters, defaults and ranges."""
def compose(first: Camera, second: Camera, *more: Camera) -> Camera:
    """One camera applying each in turn, as `artcam compose`."""

def fit(src: npt.ArrayLike | PathArg, dst: npt.ArrayLike | None = None,
        size: Size | None = None, *, target_size: Size | None = None,
        model: Literal["auto", "translation", "similarity", "affine", "homography",
                       "quadratic"] = "auto",
        robust: bool = False, threshold: float | None = None, refine: bool = True,
        allow_poles: bool = False, enabled: Sequence[bool] | None = None
        ) -> tuple[Camera, Report]:
    """A camera fitted to N×2 (or N×3) matches, and `artcam fit --json`'s report."""
def fit_lines(lines: Sequence[npt.ArrayLike] | dict[str, npt.ArrayLike] | PathArg, size: Size, *,
              pairs_src: npt.ArrayLike | None = None, pairs_dst: npt.ArrayLike | None = None,
              target_size: Size | None = None,
              model: Literal["auto", "radial", "quadratic"] = "auto") -> tuple[Camera, Report]:
    """A lens camera that straightens traced lines, as `artcam fit --lines`."""
def fit_stmap(path: str, *, size: Size | None = None, layer: str = "",
              model: str = "auto", robust: bool = False) -> tuple[Camera, Report]:
    """A camera fitted to an ST map, as `artcam fit --stmap`."""
def fit_colour(src: npt.ArrayLike, dst: npt.ArrayLike, size: Size, *,
               model: Literal["auto", "linear", "affine", "quadratic"] = "auto",
               robust: bool = False, threshold: float | None = None, srgb: bool = False,
               enabled: Sequence[bool] | None = None) -> tuple[Camera, Report]:
    """A colour camera fitted to N×3 colour samples, as `artcam fit --block colour`."""

def export_map(camera: Camera, size: Size, *, convention: Literal["stmap", "opencv"] = "stmap",
               source_size: Size | None = None,
               path: PathArg | None = None) -> npt.NDArray[np.float32]:
    """The camera's inverse map (H×W×4 STMap or H×W×2 cv::remap maps), as `artcam export-map`."""
def export_project(project: str, out: str, **options: Any) -> Report:
    """A studio project rendered into `out`, as `artcam export` (the studio's File > Export)."""

def lens_search(text: str, *, limit: int = 50) -> list[dict[str, Any]]:
    """Lenses of the lensfun database, as `artcam lens search`."""
def lens_camera(lens: str | None = None, focal: float | None = None, size: Size | None = None,
                *, photo: PathArg | None = None, crop: float | None = None,
                distort: bool = False, tca: bool = True,
                max_error: float | None = None) -> tuple[Camera, Report]:
    """The camera correcting (or simulating) a lens, as `artcam lens camera`."""
