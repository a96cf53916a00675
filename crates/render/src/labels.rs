//! Room labels on a plan view: each room's id written at its centre in a small built-in bitmap
//! font (5 × 7 pixel glyphs, drawn at an integer scale on a light plate), so a top view of a
//! house reads as a floor plan.

use image::{Rgba, RgbaImage};
use nalgebra::{Point2, Point3};
use scenethesis_imagery::Camera;
use scenethesis_scene_graph::{Architecture, RoomArea};

/// Glyph width and height in font pixels.
const GLYPH: (u32, u32) = (5, 7);
/// Font pixels between glyphs and around the text on its plate.
const SPACING: u32 = 1;
/// Colour of the text.
const INK: Rgba<u8> = Rgba([24, 28, 36, 255]);
/// Colour of the plate behind the text.
const PLATE: Rgba<u8> = Rgba([250, 248, 240, 255]);

/// The rows of a glyph, top first, each the low 5 bits (bit 4 the leftmost pixel); `None`
/// for a character the font does not have (drawn as a blank).
fn glyph(c: char) -> Option<[u8; 7]> {
    let rows = match c.to_ascii_lowercase() {
        'a' => [0x00, 0x00, 0x0e, 0x01, 0x0f, 0x11, 0x0f],
        'b' => [0x10, 0x10, 0x1e, 0x11, 0x11, 0x11, 0x1e],
        'c' => [0x00, 0x00, 0x0e, 0x10, 0x10, 0x10, 0x0e],
        'd' => [0x01, 0x01, 0x0f, 0x11, 0x11, 0x11, 0x0f],
        'e' => [0x00, 0x00, 0x0e, 0x11, 0x1f, 0x10, 0x0e],
        'f' => [0x06, 0x08, 0x1c, 0x08, 0x08, 0x08, 0x08],
        'g' => [0x00, 0x0f, 0x11, 0x11, 0x0f, 0x01, 0x0e],
        'h' => [0x10, 0x10, 0x1e, 0x11, 0x11, 0x11, 0x11],
        'i' => [0x04, 0x00, 0x0c, 0x04, 0x04, 0x04, 0x0e],
        'j' => [0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0c],
        'k' => [0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12],
        'l' => [0x0c, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e],
        'm' => [0x00, 0x00, 0x1a, 0x15, 0x15, 0x15, 0x15],
        'n' => [0x00, 0x00, 0x1e, 0x11, 0x11, 0x11, 0x11],
        'o' => [0x00, 0x00, 0x0e, 0x11, 0x11, 0x11, 0x0e],
        'p' => [0x00, 0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10],
        'q' => [0x00, 0x0f, 0x11, 0x11, 0x0f, 0x01, 0x01],
        'r' => [0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10],
        's' => [0x00, 0x00, 0x0f, 0x10, 0x0e, 0x01, 0x1e],
        't' => [0x08, 0x08, 0x1c, 0x08, 0x08, 0x09, 0x06],
        'u' => [0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0d],
        'v' => [0x00, 0x00, 0x11, 0x11, 0x11, 0x0a, 0x04],
        'w' => [0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0a],
        'x' => [0x00, 0x00, 0x11, 0x0a, 0x04, 0x0a, 0x11],
        'y' => [0x00, 0x11, 0x11, 0x11, 0x0f, 0x01, 0x0e],
        'z' => [0x00, 0x00, 0x1f, 0x02, 0x04, 0x08, 0x1f],
        '0' => [0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e],
        '1' => [0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e],
        '2' => [0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f],
        '3' => [0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e],
        '4' => [0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02],
        '5' => [0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e],
        '6' => [0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e],
        '7' => [0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e],
        '9' => [0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c],
        '_' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f],
        '-' => [0x00, 0x00, 0x00, 0x0e, 0x00, 0x00, 0x00],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c],
        _ => return None,
    };
    Some(rows)
}

/// The font scale for an image `width` pixels wide: 1 up to 320 px, one more per 320 px.
fn scale_for(width: u32) -> u32 {
    (width / 320).max(1)
}

/// Writes `text` centred on pixel (`cx`, `cy`) of `image` on a plate, clipped to the image.
pub fn draw_label(image: &mut RgbaImage, text: &str, cx: f64, cy: f64) {
    let s = scale_for(image.width());
    let n = text.chars().count() as u32;
    let (gw, gh) = GLYPH;
    let text_w = n * (gw + SPACING) * s;
    let plate_w = text_w + SPACING * s;
    let plate_h = (gh + 2 * SPACING) * s;
    let left = cx.round() as i64 - i64::from(plate_w / 2);
    let top = cy.round() as i64 - i64::from(plate_h / 2);
    fill(image, left, top, plate_w, plate_h, PLATE);
    for (k, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else {
            continue;
        };
        let x0 = left + i64::from((SPACING + k as u32 * (gw + SPACING)) * s);
        let y0 = top + i64::from(SPACING * s);
        for (row, bits) in rows.iter().enumerate() {
            for col in 0..gw {
                if (bits >> (gw - 1 - col)) & 1 == 1 {
                    let (x, y) = (x0 + i64::from(col * s), y0 + (row as i64) * i64::from(s));
                    fill(image, x, y, s, s, INK);
                }
            }
        }
    }
}

/// Fills the `w` × `h` rectangle at (`x`, `y`) with `colour`, clipped to the image.
fn fill(image: &mut RgbaImage, x: i64, y: i64, w: u32, h: u32, colour: Rgba<u8>) {
    let (iw, ih) = (i64::from(image.width()), i64::from(image.height()));
    for py in y.max(0)..(y + i64::from(h)).min(ih) {
        for px in x.max(0)..(x + i64::from(w)).min(iw) {
            image.put_pixel(px as u32, py as u32, colour);
        }
    }
}

/// The point a room's label goes at: of a 9 × 9 grid over its outline's box, the point inside
/// the room farthest from its walls (an L's label sits in one of its arms, not in the missing
/// corner).
fn label_point(room: &RoomArea) -> Option<(f64, f64)> {
    let (lo, hi) = room.bounds()?;
    let steps = 8;
    let grid = (0..=steps).flat_map(|i| {
        (0..=steps).map(move |j| {
            let (u, v) = (
                f64::from(i) / f64::from(steps),
                f64::from(j) / f64::from(steps),
            );
            Point2::new(lo.x + (hi.x - lo.x) * u, lo.y + (hi.y - lo.y) * v)
        })
    });
    grid.filter(|p| room.contains_xz(p.x, p.y))
        .map(|p| (edge_distance(room, &p), p))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, p)| (p.x, p.y))
}

/// Distance from `p` to the nearest edge of the room's outline.
fn edge_distance(room: &RoomArea, p: &Point2<f64>) -> f64 {
    let poly = &room.polygon;
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let ab = b - a;
            let t = ((p - a).dot(&ab) / ab.norm_squared().max(1e-12)).clamp(0.0, 1.0);
            (p - (a + ab * t)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Writes each room's id at its centre on `image`, a view taken by `camera` (a top view of the
/// house): the labels that make a plan of it. Rooms whose centre is behind the camera are
/// left out.
pub fn label_rooms(image: &mut RgbaImage, camera: &Camera, architecture: &Architecture) {
    for room in &architecture.rooms {
        let Some((x, z)) = label_point(room) else {
            continue;
        };
        if let Some(p) = camera.project(&Point3::new(x, 0.0, z)) {
            draw_label(image, &room.id, p.pixel.x, p.pixel.y);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_character_has_a_glyph_of_five_columns() {
        for c in ('a'..='z').chain('0'..='9').chain(['_', '-', '.']) {
            let rows = glyph(c).unwrap_or_else(|| panic!("no glyph for {c:?}"));
            assert!(rows.iter().all(|r| *r < 32), "{c:?} is wider than 5");
            assert!(rows.iter().any(|r| *r != 0), "{c:?} is blank");
        }
        assert_eq!(glyph('B'), glyph('b'));
        assert_eq!(glyph('#'), None);
    }

    #[test]
    fn a_label_draws_ink_on_a_plate_at_its_centre() {
        let mut image = RgbaImage::from_pixel(100, 40, Rgba([0, 0, 0, 255]));
        draw_label(&mut image, "ab", 50.0, 20.0);
        let count = |c: Rgba<u8>| image.pixels().filter(|p| **p == c).count();
        assert!(count(INK) > 10 && count(PLATE) > 10);
        assert_eq!(
            *image.get_pixel(5, 5),
            Rgba([0, 0, 0, 255]),
            "outside the plate"
        );
        // Clipped at the border, not a panic.
        draw_label(&mut image, "bedroom_1", 0.0, 0.0);
    }

    #[test]
    fn an_l_shaped_room_is_labelled_inside_it() {
        let room = RoomArea {
            id: "l".into(),
            room_type: "living room".into(),
            polygon: [
                (0.0, 0.0),
                (4.0, 0.0),
                (4.0, 1.0),
                (1.0, 1.0),
                (1.0, 4.0),
                (0.0, 4.0),
            ]
            .iter()
            .map(|&(x, z)| Point2::new(x, z))
            .collect(),
        };
        let (x, z) = label_point(&room).unwrap();
        assert!(room.contains_xz(x, z), "({x}, {z})");
    }
}
