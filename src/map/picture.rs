//! A map as a picture file: the grey levels of map_server's trinary maps (254 free, 0
//! occupied, 205 unknown), north up, each cell a square of pixels, so that a notebook or a
//! file viewer shows small maps large enough to read.

use super::{CellState, GridMap};

/// The largest side a picture is enlarged to (a map already larger keeps one pixel per cell).
const ENLARGE_TO_PX: usize = 480;

/// The grey level of a cell state (map_server's trinary values).
pub fn grey(state: CellState) -> u8 {
    match state {
        CellState::Free => 254,
        CellState::Occupied => 0,
        CellState::Unknown => 205,
    }
}

/// Pixels per cell edge for `map`: as many as keep its longer side at most `ENLARGE_TO_PX`
/// (at least one).
pub fn pixels_per_cell(map: &GridMap) -> usize {
    (ENLARGE_TO_PX / map.rows().max(map.cols()).max(1)).max(1)
}

/// The map as a greyscale PNG file, row 0 of the picture at the map's top (largest y).
pub fn png(map: &GridMap) -> Vec<u8> {
    let k = pixels_per_cell(map);
    let (w, h) = (map.cols() * k, map.rows() * k);
    let mut pixels = Vec::with_capacity(w * h);
    for py in 0..h {
        let row = map.rows() - 1 - py / k;
        pixels.extend((0..w).map(|px| grey(map.state(row, px / k))));
    }
    crate::io::png::encode(&pixels, w as u32, h as u32, crate::io::png::Channels::Grey)
        .expect("a PNG of one byte per pixel encodes into memory")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;

    #[test]
    fn a_small_map_is_enlarged_north_up() {
        // 3 × 2 cells: the bottom-left cell occupied, the top-right unknown.
        let cells = vec![
            CellState::Occupied,
            CellState::Free,
            CellState::Free,
            CellState::Free,
            CellState::Free,
            CellState::Unknown,
        ];
        let map = GridMap::new("tiny", 3, 2, 0.5, Point::origin(), cells).unwrap();
        let k = pixels_per_cell(&map);
        assert_eq!(k, 160);
        let picture = image::load_from_memory(&png(&map)).unwrap().to_luma8();
        assert_eq!(picture.dimensions(), (3 * 160, 2 * 160));
        assert_eq!(picture.get_pixel(0, 2 * 160 - 1).0, [0], "bottom-left: occupied");
        assert_eq!(picture.get_pixel(3 * 160 - 1, 0).0, [205], "top-right: unknown");
        assert_eq!(picture.get_pixel(200, 100).0, [254]);
    }
}
