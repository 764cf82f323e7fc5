"""Tiles: a frame cut into NX x NY windows (gridrt --crop's half-open pixel ranges), and the
order they are handed out in."""
from dataclasses import dataclass


@dataclass(frozen=True)
class Tile:
    x0: int
    y0: int
    x1: int
    y1: int

    def crop(self):
        """The window as gridrt's --crop X0,Y0,X1,Y1."""
        return f"{self.x0},{self.y0},{self.x1},{self.y1}"

    def pixels(self):
        return (self.x1 - self.x0) * (self.y1 - self.y0)


def split(width, height, nx, ny):
    """NX x NY tiles covering width x height exactly, rows from the top; tile edges at
    i*width//nx, so sizes differ by one pixel at most. More tiles than pixels is refused."""
    if nx > width or ny > height:
        raise ValueError(f"{nx}x{ny} tiles do not fit in {width}x{height} pixels")
    xs = [i * width // nx for i in range(nx + 1)]
    ys = [j * height // ny for j in range(ny + 1)]
    return [Tile(xs[i], ys[j], xs[i + 1], ys[j + 1]) for j in range(ny) for i in range(nx)]


def ordered(tiles, width, height, order):
    """raster: as split() gives them; centre: nearest the image's centre first (the
    distance of the tile's centre, in pixels; ties in raster order), for a quick preview."""
    if order == "raster":
        return list(tiles)
    cx, cy = width / 2.0, height / 2.0

    def distance(t):
        return ((t.x0 + t.x1) / 2.0 - cx) ** 2 + ((t.y0 + t.y1) / 2.0 - cy) ** 2
    return sorted(tiles, key=distance)  # sorted() is stable: ties stay in raster order
