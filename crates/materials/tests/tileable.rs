//! Every material's base-colour map tiles without a visible seam: the step across the wrap
//! edge (last column to first, last row to first) is no larger than the largest step between
//! two neighbouring columns or rows inside the map. Boards, rings and threads put sharp edges
//! inside a map, and the wrap edge may fall on one, so the wrap is compared with the roughest
//! edge inside rather than a typical one. The same measure finds a seam where two rows that
//! are not neighbours are put side by side in most maps, so the check can fail. (The four
//! seams an earlier form of this check reported — `ebony`, `rough_timber`, `oak_floorboards`,
//! `wool` — were ring, board and thread edges that happen to lie on the wrap, compared with a
//! smooth row in the middle of the map.)

use scenethesis_materials::{by_id, library, maps, resolve, LibraryMaterial, TEXTURE_SIZE};

const GROUNDS: [&str; 4] = ["sand", "grass", "gravel", "paving"];

/// A map's texel at (x, y) in one channel.
struct Channel<'a> {
    texels: &'a [u8],
    channel: usize,
}

impl Channel<'_> {
    fn at(&self, x: usize, y: usize) -> i32 {
        let n = TEXTURE_SIZE as usize;
        i32::from(self.texels[(y * n + x) * 3 + self.channel])
    }

    /// The summed step between column `a` and column `b`.
    fn columns_apart(&self, a: usize, b: usize) -> i32 {
        let n = TEXTURE_SIZE as usize;
        (0..n).map(|y| (self.at(a, y) - self.at(b, y)).abs()).sum()
    }

    /// The summed step between row `a` and row `b`.
    fn rows_apart(&self, a: usize, b: usize) -> i32 {
        let n = TEXTURE_SIZE as usize;
        (0..n).map(|x| (self.at(x, a) - self.at(x, b)).abs()).sum()
    }
}

/// Whether a step of `step` stands out against the roughest neighbour step `roughest` (a
/// texel of rounding allowed per row).
fn stands_out(step: i32, roughest: i32) -> bool {
    step > roughest + TEXTURE_SIZE as i32
}

/// The seams of `material`'s base-colour map, one line each.
fn seams(material: &LibraryMaterial) -> Vec<String> {
    let n = TEXTURE_SIZE as usize;
    let texels = &maps(material).base_color;
    let mut found = Vec::new();
    for channel in 0..3 {
        let map = Channel { texels, channel };
        let inside_u = (0..n - 1)
            .map(|x| map.columns_apart(x, x + 1))
            .max()
            .unwrap_or(0);
        let inside_v = (0..n - 1)
            .map(|y| map.rows_apart(y, y + 1))
            .max()
            .unwrap_or(0);
        let (across_u, across_v) = (map.columns_apart(n - 1, 0), map.rows_apart(n - 1, 0));
        if stands_out(across_u, inside_u) || stands_out(across_v, inside_v) {
            found.push(format!(
                "{} channel {channel}: u {across_u} vs {inside_u}, v {across_v} vs {inside_v}",
                material.id
            ));
        }
    }
    found
}

#[test]
fn every_base_colour_map_wraps_seamlessly() {
    let found: Vec<String> = library().iter().flat_map(seams).collect();
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn rows_that_are_not_neighbours_stand_out_as_a_seam() {
    let n = TEXTURE_SIZE as usize;
    let mut caught = 0;
    let mut patterned = 0;
    for material in library() {
        let texels = &maps(material).base_color;
        let map = Channel { texels, channel: 1 };
        let inside_v = (0..n - 1)
            .map(|y| map.rows_apart(y, y + 1))
            .max()
            .unwrap_or(0);
        let far = map.rows_apart(n - 1, n / 3);
        // A plain colour has no rows to tell apart.
        if far > 4 * n as i32 {
            patterned += 1;
            caught += usize::from(stands_out(far, inside_v));
        }
    }
    assert!(patterned >= 20, "only {patterned} patterned maps");
    // Maps with edges as sharp as two unrelated rows inside them (boards, tiles, threads)
    // hide a spliced seam from this measure; it must still catch one in most maps (16 of 27
    // when this was written).
    assert!(
        caught * 2 > patterned,
        "a spliced seam stands out in only {caught} of {patterned} maps"
    );
}

/// Smooth noise grounds meet a stricter bound: the wrap step is no larger than twice the
/// step between the two middle columns (rows), plus rounding.
#[test]
fn ground_base_colour_maps_wrap_seamlessly() {
    let n = TEXTURE_SIZE as usize;
    let mut seams = Vec::new();
    for material in GROUNDS.map(|id| by_id(id).unwrap_or_else(|| panic!("{id}"))) {
        let texels = &maps(material).base_color;
        for channel in 0..3 {
            let map = Channel { texels, channel };
            let (across_u, across_v) = (map.columns_apart(n - 1, 0), map.rows_apart(n - 1, 0));
            let inside_u = map.columns_apart(n / 2, n / 2 + 1);
            let inside_v = map.rows_apart(n / 2, n / 2 + 1);
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
