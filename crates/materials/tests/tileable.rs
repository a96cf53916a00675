//! The outdoor grounds' base-colour maps tile without a visible seam: the jump across the wrap
//! edge is no larger than a typical step between neighbouring texels inside the map. (Over
//! the whole library the same check finds seams in `ebony`, `rough_timber`, `oak_floorboards`
//! and `wool`, not fixed yet.)

use scenethesis_materials::{by_id, maps, resolve, TEXTURE_SIZE};

const GROUNDS: [&str; 4] = ["sand", "grass", "gravel", "paving"];

#[test]
fn ground_base_colour_maps_wrap_seamlessly() {
    let n = TEXTURE_SIZE as usize;
    let mut seams = Vec::new();
    for material in GROUNDS.map(|id| by_id(id).unwrap_or_else(|| panic!("{id}"))) {
        let texels = &maps(material).base_color;
        for channel in 0..3 {
            let at = |x: usize, y: usize| i32::from(texels[(y * n + x) * 3 + channel]);
            let across_u: i32 = (0..n).map(|y| (at(n - 1, y) - at(0, y)).abs()).sum();
            let inside_u: i32 = (0..n)
                .map(|y| (at(n / 2, y) - at(n / 2 + 1, y)).abs())
                .sum();
            let across_v: i32 = (0..n).map(|x| (at(x, n - 1) - at(x, 0)).abs()).sum();
            let inside_v: i32 = (0..n)
                .map(|x| (at(x, n / 2) - at(x, n / 2 + 1)).abs())
                .sum();
            if across_u > 2 * inside_u + n as i32 || across_v > 2 * inside_v + n as i32 {
                seams.push(format!(
                    "{} channel {channel}: u {across_u} vs {inside_u}, v {across_v} vs {inside_v}",
                    material.id
                ));
            }
        }
    }
    assert!(seams.is_empty(), "{}", seams.join("\n"));
}

#[test]
fn outdoor_grounds_are_in_the_library_at_real_size() {
    for (id, size) in GROUNDS.into_iter().zip([1.0, 1.0, 0.5, 1.2]) {
        let m = by_id(id).unwrap_or_else(|| panic!("{id}"));
        assert_eq!(m.tile_size_m, size, "{id}");
        assert_eq!(resolve(id).map(|r| r.id), Some(id));
    }
}
