//! Polygons in the (x, z) plane: rectangles, regular polygons and discs for footprints and support surfaces.

/// A regular polygon of `sides` corners with circumradius `radius` around `center` in (x, z),
/// counter-clockwise seen from above.
pub fn regular_polygon(center: [f32; 2], radius: f32, sides: u32) -> Vec<[f32; 2]> {
    let n = sides.max(3);
    (0..n)
        .map(|i| {
            let a = -(i as f32) / n as f32 * std::f32::consts::TAU;
            [center[0] + radius * a.cos(), center[1] + radius * a.sin()]
        })
        .collect()
}

/// A rectangle in (x, z), counter-clockwise seen from above.
pub fn rect(x0: f32, z0: f32, x1: f32, z1: f32) -> Vec<[f32; 2]> {
    vec![[x0, z0], [x0, z1], [x1, z1], [x1, z0]]
}

/// A regular polygon of `n` corners inscribed in a circle, counter-clockwise seen from above,
/// starting at +X. The same polygon as [`regular_polygon`] but for the last bit of rounding
/// (the angle is computed as `TAU · i / n` rather than `−(i / n) · TAU`); the item generators'
/// support surfaces are defined by this rounding, so the two are kept apart.
pub fn disc(center: [f32; 2], radius: f32, n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            [center[0] + radius * a.cos(), center[1] - radius * a.sin()]
        })
        .collect()
}
