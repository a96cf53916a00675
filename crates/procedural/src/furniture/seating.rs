//! The seat family: legs or a base, a seat, an optional back and arms; plus the seats that are
//! not chairs (bean bag, ottoman, log bench, wheelchair).
//!
//! Every seat faces +Z (the sitter looks toward +Z); the back is at −Z. Seat heights are the
//! top of the seat surface, in metres.

use std::f32::consts::{PI, TAU};

use rand_chacha::ChaCha8Rng;

use super::{mat, mat_either, SCALE};
use crate::materials::Palette;
use crate::random::{coin, int, uniform, uniform3};
use scenethesis_primitives::{
    beam, box_yaw, cylinder, disc_surface, ellipsoid, frustum, hexahedron, prism_x, rect_surface,
    rod, strut, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// What a chair stands on.
#[derive(Debug, Clone, Copy)]
enum Base {
    /// Four legs of square `section`, splayed outward by `splay` metres at the floor, with
    /// optional stretchers at `stretcher` height.
    Legs {
        section: f32,
        splay: f32,
        stretcher: Option<f32>,
    },
    /// A central gas column on a star of `arms` feet ending in casters.
    Star { arms: u32, radius: f32 },
}

/// The parameters of a chair-like seat.
#[derive(Debug, Clone, Copy)]
struct Chair {
    width: f32,
    depth: f32,
    seat_height: f32,
    seat_thickness: f32,
    base: Base,
    /// Height of the back above the seat (0 for none) and its lean at the top toward −Z.
    back: Option<(f32, f32)>,
    /// Armrest height above the seat.
    arms: Option<f32>,
    /// A round seat of this radius instead of a rectangle.
    round: Option<f32>,
}

/// Materials of a chair: frame, seat, back.
#[derive(Debug, Clone, Copy)]
struct ChairMaterials {
    frame: usize,
    seat: usize,
    back: usize,
}

/// The thickness of a chair's back slab, whose front the seat surface stops short of.
const BACK_THICKNESS: f32 = 0.03;

fn build_chair(b: &mut AssetBuilder, c: &Chair, m: ChairMaterials) {
    chair_seat(b, c, m.seat);
    match c.base {
        Base::Legs {
            section,
            splay,
            stretcher,
        } => chair_legs(b, c, m.frame, section, splay, stretcher),
        Base::Star { arms, radius } => star_base(b, c, m.frame, arms, radius),
    }
    if let Some((height, lean)) = c.back {
        chair_back(b, c, m, height, lean);
    }
    if let Some(arm_height) = c.arms {
        chair_arms(b, c, m.frame, arm_height);
    }
    chair_seat_surface(b, c);
}

/// The seat: a round slab or a rectangular one.
fn chair_seat(b: &mut AssetBuilder, c: &Chair, material: usize) {
    let (hw, hd) = (0.5 * c.width, 0.5 * c.depth);
    let seat_bottom = c.seat_height - c.seat_thickness;
    match c.round {
        Some(r) => {
            b.part(cylinder(
                "seat",
                material,
                [0.0, 0.0],
                r,
                seat_bottom,
                c.seat_height,
                24,
            ));
        }
        None => b.cuboid(
            "seat",
            material,
            [-hw, seat_bottom, -hd],
            [hw, c.seat_height, hd],
        ),
    }
}

/// Four splayed legs from under the seat to the floor, the stretchers between them, and the
/// space under the seat when it is tall enough to hold something.
fn chair_legs(
    b: &mut AssetBuilder,
    c: &Chair,
    frame: usize,
    section: f32,
    splay: f32,
    stretcher: Option<f32>,
) {
    let (hw, hd) = (0.5 * c.width, 0.5 * c.depth);
    let seat_bottom = c.seat_height - c.seat_thickness;
    let (lx, lz) = match c.round {
        Some(r) => (0.62 * r, 0.62 * r),
        None => (hw - 0.6 * section, hd - 0.6 * section),
    };
    let feet: Vec<([f32; 3], [f32; 3])> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(sx, sz)| {
            (
                [sx * lx, seat_bottom + 0.005, sz * lz],
                [sx * (lx + splay), 0.0, sz * (lz + splay)],
            )
        })
        .collect();
    for (i, (top, foot)) in feet.iter().enumerate() {
        b.part(strut(
            &format!("leg_{i}"),
            frame,
            *foot,
            *top,
            [section, section],
        ));
    }
    if let Some(h) = stretcher {
        let t = h / seat_bottom;
        let at = |(top, foot): &([f32; 3], [f32; 3])| -> [f32; 3] {
            std::array::from_fn(|k| foot[k] + t * (top[k] - foot[k]))
        };
        for i in 0..4 {
            let (p, q) = (at(&feet[i]), at(&feet[(i + 1) % 4]));
            b.part(beam(
                &format!("stretcher_{i}"),
                frame,
                p,
                q,
                [0.6 * section, 0.6 * section],
            ));
        }
    }
    let under = seat_bottom - 0.02;
    if under > 0.2 && c.round.is_none() {
        let (ix, iz) = (lx - 0.5 * section, lz - 0.5 * section);
        b.surface(rect_surface(
            "under",
            SurfaceKind::Under,
            [-ix, -iz],
            [ix, iz],
            0.0,
            Some(stretcher.map_or(under, |h| under.min(h - 0.02))),
            0.02,
        ));
    }
}

/// An office chair's base: a gas column on a hub with a star of feet ending in casters.
fn star_base(b: &mut AssetBuilder, c: &Chair, frame: usize, arms: u32, radius: f32) {
    let seat_bottom = c.seat_height - c.seat_thickness;
    let caster = 0.03;
    let column_top = seat_bottom + 0.005;
    b.part(cylinder(
        "column",
        frame,
        [0.0, 0.0],
        0.028,
        0.08,
        column_top,
        16,
    ));
    b.part(cylinder(
        "hub",
        frame,
        [0.0, 0.0],
        0.05,
        2.0 * caster,
        0.12,
        16,
    ));
    for i in 0..arms {
        let a = i as f32 / arms as f32 * TAU + 0.5 * PI;
        let (x, z) = (radius * a.cos(), radius * a.sin());
        b.part(beam(
            &format!("foot_{i}"),
            frame,
            [0.0, 2.0 * caster + 0.025, 0.0],
            [x, 2.0 * caster + 0.015, z],
            [0.04, 0.03],
        ));
        b.part(ellipsoid(
            &format!("caster_{i}"),
            frame,
            [x, caster, z],
            [0.022, caster, 0.03],
            6,
            10,
        ));
    }
}

/// The back: a slab leaning back from the seat's rear edge, on a post for a star base.
fn chair_back(b: &mut AssetBuilder, c: &Chair, m: ChairMaterials, height: f32, lean: f32) {
    let hd = 0.5 * c.depth;
    let seat_bottom = c.seat_height - c.seat_thickness;
    let hw = 0.5 * c.width;
    let y0 = c.seat_height - 0.01;
    let y1 = c.seat_height + height;
    let z0 = -hd;
    let bw = match c.round {
        Some(r) => 0.8 * r,
        None => hw,
    };
    let bz = match c.round {
        Some(r) => -r,
        None => z0,
    };
    // A slab leaning back: bottom edge on the seat's rear edge, top edge `lean` further back.
    let corners = std::array::from_fn(|i| {
        let x = if i & 1 == 0 { -bw } else { bw };
        let top = i & 2 != 0;
        let y = if top { y1 } else { y0 };
        let z = bz - if top { lean } else { 0.0 } + if i & 4 == 0 { 0.0 } else { BACK_THICKNESS };
        [x, y, z]
    });
    b.part(hexahedron("back", m.back, corners));
    if let Base::Star { .. } = c.base {
        b.part(beam(
            "back_post",
            m.frame,
            [0.0, seat_bottom, bz - 0.01],
            [0.0, y0 + 0.5 * height, bz - 0.5 * lean - 0.01],
            [0.05, 0.02],
        ));
    }
}

/// Two armrests on posts, `arm_height` above the seat.
fn chair_arms(b: &mut AssetBuilder, c: &Chair, frame: usize, arm_height: f32) {
    let (hw, hd) = (0.5 * c.width, 0.5 * c.depth);
    let y = c.seat_height + arm_height;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.025);
        b.cuboid(
            &format!("armrest_{i}"),
            frame,
            [x - 0.025, y - 0.03, -hd + 0.03],
            [x + 0.025, y, hd - 0.04],
        );
        b.cuboid(
            &format!("arm_post_{i}"),
            frame,
            [x - 0.015, c.seat_height - 0.02, 0.2 * hd - 0.015],
            [x + 0.015, y - 0.02, 0.2 * hd + 0.015],
        );
    }
}

/// The seat's support surface: between the arms and in front of the back.
fn chair_seat_surface(b: &mut AssetBuilder, c: &Chair) {
    let (hw, hd) = (0.5 * c.width, 0.5 * c.depth);
    let inner = if c.arms.is_some() { hw - 0.05 } else { hw };
    let back_front = -hd + BACK_THICKNESS + 0.01;
    match c.round {
        Some(r) => {
            b.surface(disc_surface(
                "seat",
                SurfaceKind::Top,
                [0.0, if c.back.is_some() { 0.1 * r } else { 0.0 }],
                0.7 * r,
                c.seat_height,
                None,
                8,
            ));
        }
        None => {
            b.top_surface(
                "seat",
                [-inner, back_front],
                [inner, hd],
                c.seat_height,
                0.03,
            );
        }
    }
}

fn chair_materials(
    rng: &mut ChaCha8Rng,
    b: &mut AssetBuilder,
    upholstered: bool,
) -> ChairMaterials {
    let wooden = coin(rng, 0.6);
    let frame = mat(
        b,
        if wooden {
            Palette::Wood
        } else {
            Palette::CoatedMetal
        },
        rng,
    );
    let seat = if upholstered {
        mat(
            b,
            if coin(rng, 0.7) {
                Palette::Fabric
            } else {
                Palette::Leather
            },
            rng,
        )
    } else if wooden {
        frame
    } else {
        mat(b, Palette::Plastic, rng)
    };
    ChairMaterials {
        frame,
        seat,
        back: seat,
    }
}

/// Sofa: width 1.6–2.4, height 0.75–0.95, depth 0.82–1.0; seat 0.42–0.47 high.
pub(super) fn sofa(rng: &mut ChaCha8Rng) -> Asset {
    upholstered_seat(rng, 1.6, 2.4, true)
}

/// Armchair: width 0.75–0.98, height 0.75–0.95, depth 0.78–0.95; seat 0.42–0.47 high.
pub(super) fn armchair(rng: &mut ChaCha8Rng) -> Asset {
    upholstered_seat(rng, 0.75, 0.98, false)
}

fn upholstered_seat(rng: &mut ChaCha8Rng, w_lo: f32, w_hi: f32, sofa: bool) -> Asset {
    let mut b = AssetBuilder::new();
    let cover = mat_either(&mut b, 0.75, Palette::Fabric, Palette::Leather, rng);
    let feet = mat(&mut b, Palette::Wood, rng);
    let w = uniform(rng, w_lo, w_hi);
    let d = uniform(
        rng,
        if sofa { 0.82 } else { 0.78 },
        if sofa { 1.0 } else { 0.95 },
    );
    let seat_h = uniform(rng, 0.42, 0.47);
    let top_h = uniform(rng, 0.75, 0.95);
    let arm_w = uniform(rng, 0.1, 0.2);
    let arm_h = uniform(rng, 0.55, 0.66).min(top_h - 0.05);
    let foot_h = uniform(rng, 0.04, 0.12);
    let back_d = uniform(rng, 0.16, 0.24);
    let cushion_t = uniform(rng, 0.1, 0.15);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    for (i, (sx, sz)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .enumerate()
    {
        b.part(frustum(
            &format!("foot_{i}"),
            feet,
            [sx * (hw - 0.06), sz * (hd - 0.06)],
            0.022,
            0.03,
            0.0,
            foot_h + 0.01,
            10,
        ));
    }
    let frame_top = seat_h - cushion_t;
    b.cuboid("frame", cover, [-hw, foot_h, -hd], [hw, frame_top, hd]);
    b.cuboid(
        "back",
        cover,
        [-hw, frame_top - 0.01, -hd],
        [hw, top_h, -hd + back_d],
    );
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x0 = if sx < 0.0 { -hw } else { hw - arm_w };
        b.cuboid(
            &format!("arm_{i}"),
            cover,
            [x0, foot_h, -hd],
            [x0 + arm_w, arm_h, hd],
        );
    }
    let inner = hw - arm_w;
    let seats = if sofa { int(rng, 2, 3) } else { 1 };
    let cw = 2.0 * inner / seats as f32;
    let back_lean = uniform(rng, 0.0, 0.06);
    let back_cushion_t = uniform(rng, 0.1, 0.16);
    let cushion_front = -hd + back_d + back_cushion_t;
    for i in 0..seats {
        let x0 = -inner + i as f32 * cw;
        b.cuboid(
            &format!("seat_cushion_{i}"),
            cover,
            [x0 - 0.002, frame_top - 0.01, cushion_front - 0.01],
            [x0 + cw + 0.002, seat_h, hd],
        );
        let corners = std::array::from_fn(|k| {
            let x = if k & 1 == 0 { x0 } else { x0 + cw };
            let top = k & 2 != 0;
            let y = if top { top_h - 0.03 } else { seat_h - 0.01 };
            let z_back = -hd + back_d - 0.01 - if top { back_lean } else { 0.0 };
            let z = if k & 4 == 0 {
                z_back
            } else {
                z_back + back_cushion_t
            };
            [x, y, z]
        });
        b.part(hexahedron(&format!("back_cushion_{i}"), cover, corners));
    }
    b.top_surface("seat", [-inner, cushion_front], [inner, hd], seat_h, 0.03);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x0 = if sx < 0.0 { -hw } else { hw - arm_w };
        if arm_w >= 0.15 {
            b.top_surface(
                &format!("arm_{i}"),
                [x0, -hd + back_d],
                [x0 + arm_w, hd],
                arm_h,
                0.02,
            );
        }
    }
    b.finish(Placement::Floor, SCALE)
}

/// Chair: width 0.42–0.52, height 0.78–1.0, depth 0.44–0.54; seat 0.43–0.48 high.
pub(super) fn chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let upholstered = coin(rng, 0.3);
    let m = chair_materials(rng, &mut b, upholstered);
    let seat_height = uniform(rng, 0.43, 0.48);
    let c = Chair {
        width: uniform(rng, 0.42, 0.52),
        depth: uniform(rng, 0.44, 0.52),
        seat_height,
        seat_thickness: uniform(rng, 0.025, 0.05),
        base: Base::Legs {
            section: uniform(rng, 0.025, 0.04),
            splay: uniform(rng, 0.0, 0.02),
            stretcher: None,
        },
        back: Some((uniform(rng, 0.35, 0.5), uniform(rng, 0.02, 0.06))),
        arms: None,
        round: None,
    };
    build_chair(&mut b, &c, m);
    b.finish(Placement::Floor, SCALE)
}

/// Dining chair: width 0.44–0.54, height 0.85–1.05, depth 0.48–0.58; seat 0.44–0.48 high,
/// upholstered seat, optional arms.
pub(super) fn dining_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = chair_materials(rng, &mut b, true);
    let arms = coin(rng, 0.25);
    let c = Chair {
        width: uniform(rng, 0.44, 0.52),
        depth: uniform(rng, 0.48, 0.55),
        seat_height: uniform(rng, 0.44, 0.48),
        seat_thickness: uniform(rng, 0.04, 0.07),
        base: Base::Legs {
            section: uniform(rng, 0.03, 0.045),
            splay: uniform(rng, 0.0, 0.015),
            stretcher: None,
        },
        back: Some((uniform(rng, 0.4, 0.54), uniform(rng, 0.03, 0.07))),
        arms: arms.then(|| uniform(rng, 0.2, 0.24)),
        round: None,
    };
    build_chair(&mut b, &c, m);
    b.finish(Placement::Floor, SCALE)
}

/// Office chair: width 0.58–0.7 (the star base), height 0.9–1.2, depth 0.58–0.72; seat
/// 0.42–0.52 high on a five-star caster base.
pub(super) fn office_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.7, Palette::CoatedMetal, Palette::Metal, rng);
    let seat = mat_either(&mut b, 0.6, Palette::Fabric, Palette::Leather, rng);
    let radius = uniform(rng, 0.29, 0.35);
    let c = Chair {
        width: uniform(rng, 0.46, 0.54),
        depth: uniform(rng, 0.44, 0.5),
        seat_height: uniform(rng, 0.42, 0.52),
        seat_thickness: uniform(rng, 0.06, 0.09),
        base: Base::Star { arms: 5, radius },
        back: Some((uniform(rng, 0.45, 0.65), uniform(rng, 0.03, 0.08))),
        arms: coin(rng, 0.7).then(|| uniform(rng, 0.18, 0.24)),
        round: None,
    };
    build_chair(
        &mut b,
        &c,
        ChairMaterials {
            frame,
            seat,
            back: seat,
        },
    );
    b.finish(Placement::Floor, SCALE)
}

fn round_stool(
    rng: &mut ChaCha8Rng,
    seat_lo: f32,
    seat_hi: f32,
    back: bool,
    footrest: bool,
    base_star: bool,
) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.5, Palette::Wood, Palette::CoatedMetal, rng);
    let seat = if coin(rng, 0.5) {
        frame
    } else {
        mat_either(&mut b, 0.5, Palette::Leather, Palette::Plastic, rng)
    };
    let r = uniform(rng, 0.15, 0.2);
    let seat_height = uniform(rng, seat_lo, seat_hi);
    let base = if base_star {
        Base::Star {
            arms: 5,
            radius: uniform(rng, 0.26, 0.3),
        }
    } else {
        Base::Legs {
            section: uniform(rng, 0.022, 0.035),
            splay: uniform(rng, 0.03, 0.08),
            stretcher: footrest.then(|| uniform(rng, 0.22, 0.32)),
        }
    };
    let c = Chair {
        width: 2.0 * r,
        depth: 2.0 * r,
        seat_height,
        seat_thickness: uniform(rng, 0.03, 0.06),
        base,
        back: back.then(|| (uniform(rng, 0.18, 0.3), uniform(rng, 0.0, 0.04))),
        arms: None,
        round: Some(r),
    };
    build_chair(
        &mut b,
        &c,
        ChairMaterials {
            frame,
            seat,
            back: seat,
        },
    );
    if base_star && footrest {
        // A foot ring on spokes around the column.
        let y = uniform(rng, 0.2, 0.3);
        let ring_r = 0.9 * r + 0.05;
        let n = 12;
        for i in 0..n {
            let (a0, a1) = (i as f32 / n as f32 * TAU, (i + 1) as f32 / n as f32 * TAU);
            b.part(beam(
                &format!("foot_ring_{i}"),
                frame,
                [ring_r * a0.cos(), y, ring_r * a0.sin()],
                [ring_r * a1.cos(), y, ring_r * a1.sin()],
                [0.018, 0.018],
            ));
        }
        for i in 0..3 {
            let a = i as f32 / 3.0 * TAU;
            b.part(beam(
                &format!("ring_spoke_{i}"),
                frame,
                [0.0, y, 0.0],
                [ring_r * a.cos(), y, ring_r * a.sin()],
                [0.015, 0.015],
            ));
        }
    }
    b.finish(Placement::Floor, SCALE)
}

/// Stool: width 0.34–0.58, height 0.44–0.53, depth 0.34–0.58; round seat, splayed legs.
pub(super) fn stool(rng: &mut ChaCha8Rng) -> Asset {
    let footrest = coin(rng, 0.4);
    round_stool(rng, 0.44, 0.5, false, footrest, false)
}

/// Bar stool: width 0.34–0.6, height 0.64–1.12, depth 0.34–0.6; seat 0.64–0.8 high with a
/// foot rest, optional low back.
pub(super) fn bar_stool(rng: &mut ChaCha8Rng) -> Asset {
    let back = coin(rng, 0.4);
    round_stool(rng, 0.64, 0.8, back, true, false)
}

/// Lab stool: width 0.52–0.6 (star base), height 0.55–0.76, depth 0.52–0.6; round seat
/// 0.55–0.75 high on a caster base with a foot ring.
pub(super) fn lab_stool(rng: &mut ChaCha8Rng) -> Asset {
    round_stool(rng, 0.55, 0.75, false, true, true)
}

/// Bench: width 0.9–1.8, height 0.42–0.48, depth 0.32–0.45; room underneath.
pub(super) fn bench(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let upholstered = coin(rng, 0.3);
    let m = chair_materials(rng, &mut b, upholstered);
    let c = Chair {
        width: uniform(rng, 0.9, 1.8),
        depth: uniform(rng, 0.32, 0.45),
        seat_height: uniform(rng, 0.42, 0.48),
        seat_thickness: uniform(rng, 0.03, 0.06),
        base: Base::Legs {
            section: uniform(rng, 0.035, 0.055),
            splay: 0.0,
            stretcher: None,
        },
        back: None,
        arms: None,
        round: None,
    };
    build_chair(&mut b, &c, m);
    b.finish(Placement::Floor, SCALE)
}

/// Piano bench: width 0.75–0.95, height 0.48–0.52, depth 0.33–0.4; a lidded box seat on legs.
pub(super) fn piano_bench(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.6, Palette::PaintedWood, Palette::Wood, rng);
    let pad = if coin(rng, 0.5) {
        mat(&mut b, Palette::Leather, rng)
    } else {
        wood
    };
    let (w, d, h) = uniform3(rng, [0.75, 0.95], [0.33, 0.4], [0.48, 0.52]);
    let box_h = uniform(rng, 0.08, 0.12);
    let c = Chair {
        width: w,
        depth: d,
        seat_height: h,
        seat_thickness: 0.04,
        base: Base::Legs {
            section: uniform(rng, 0.04, 0.055),
            splay: 0.0,
            stretcher: None,
        },
        back: None,
        arms: None,
        round: None,
    };
    build_chair(
        &mut b,
        &c,
        ChairMaterials {
            frame: wood,
            seat: pad,
            back: pad,
        },
    );
    b.cuboid(
        "storage_box",
        wood,
        [-0.5 * w, h - 0.04 - box_h, -0.5 * d],
        [0.5 * w, h - 0.035, 0.5 * d],
    );
    // The storage box lowers the room underneath.
    let under_top = h - 0.04 - box_h - 0.02;
    for s in b.surfaces_mut() {
        if s.kind == SurfaceKind::Under {
            s.clearance = Some(under_top);
        }
    }
    b.finish(Placement::Floor, SCALE)
}

/// Kids' chair: width 0.3–0.38, height 0.5–0.66, depth 0.3–0.38; seat 0.26–0.34 high, bright
/// plastic or painted wood.
pub(super) fn kids_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(
        &mut b,
        0.7,
        Palette::BrightPlastic,
        Palette::PaintedWood,
        rng,
    );
    let c = Chair {
        width: uniform(rng, 0.3, 0.38),
        depth: uniform(rng, 0.3, 0.36),
        seat_height: uniform(rng, 0.26, 0.34),
        seat_thickness: uniform(rng, 0.02, 0.035),
        base: Base::Legs {
            section: uniform(rng, 0.025, 0.035),
            splay: uniform(rng, 0.0, 0.015),
            stretcher: None,
        },
        back: Some((uniform(rng, 0.22, 0.3), uniform(rng, 0.0, 0.03))),
        arms: None,
        round: None,
    };
    build_chair(
        &mut b,
        &c,
        ChairMaterials {
            frame: body,
            seat: body,
            back: body,
        },
    );
    b.finish(Placement::Floor, SCALE)
}

/// Bean bag: width 0.7–1.0, height 0.6–0.9, depth 0.7–1.0; a squashed sack with a raised back,
/// flat where it rests on the floor.
pub(super) fn bean_bag(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cover = mat_either(&mut b, 0.6, Palette::Fabric, Palette::BrightPlastic, rng);
    let (w, d) = (uniform(rng, 0.7, 1.0), uniform(rng, 0.7, 1.0));
    let h = uniform(rng, 0.6, 0.9);
    let base_h = 0.5 * h;
    b.part(ellipsoid(
        "sack",
        cover,
        [0.0, 0.5 * base_h, 0.0],
        [0.5 * w, 0.5 * base_h, 0.5 * d],
        12,
        20,
    ));
    b.part(ellipsoid(
        "back_bulge",
        cover,
        [0.0, 0.5 * h, -0.22 * d],
        [0.42 * w, 0.5 * h, 0.26 * d],
        12,
        20,
    ));
    // The filling spreads the sack's bottom flat where it meets the floor: a sack resting on
    // the lowest points of its two rounded halves alone would rock.
    b.part(cylinder(
        "flat_bottom",
        cover,
        [0.0, 0.0],
        0.3 * w.min(d),
        0.0,
        0.06,
        20,
    ));
    // A flattened seat hollow on top of the sack, in front of the back bulge.
    let pad_top = base_h + 0.02;
    b.part(cylinder(
        "seat_hollow",
        cover,
        [0.0, 0.15 * d],
        0.22 * w,
        base_h - 0.12,
        pad_top,
        20,
    ));
    b.top_surface(
        "seat",
        [-0.15 * w, 0.06 * d],
        [0.15 * w, 0.15 * d + 0.15 * w],
        pad_top,
        0.01,
    );
    b.finish(Placement::Floor, SCALE)
}

/// Ottoman: width 0.45–0.9, height 0.38–0.46, depth 0.45–0.7; an upholstered block or drum on
/// short feet.
pub(super) fn ottoman(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cover = mat_either(&mut b, 0.6, Palette::Fabric, Palette::Leather, rng);
    let feet = mat(&mut b, Palette::Wood, rng);
    let h = uniform(rng, 0.38, 0.46);
    let foot = uniform(rng, 0.03, 0.07);
    if coin(rng, 0.5) {
        let r = uniform(rng, 0.23, 0.35);
        b.part(cylinder("drum", cover, [0.0, 0.0], r, foot, h, 28));
        for i in 0..4 {
            let a = i as f32 * 0.5 * PI + 0.25 * PI;
            b.part(cylinder(
                &format!("foot_{i}"),
                feet,
                [0.7 * r * a.cos(), 0.7 * r * a.sin()],
                0.02,
                0.0,
                foot + 0.01,
                8,
            ));
        }
        b.surface(disc_surface(
            "top",
            SurfaceKind::Top,
            [0.0, 0.0],
            r - 0.04,
            h,
            None,
            12,
        ));
    } else {
        let (w, d) = (uniform(rng, 0.45, 0.9), uniform(rng, 0.45, 0.7));
        b.cuboid(
            "block",
            cover,
            [-0.5 * w, foot, -0.5 * d],
            [0.5 * w, h, 0.5 * d],
        );
        for (i, (sx, sz)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .enumerate()
        {
            b.part(cylinder(
                &format!("foot_{i}"),
                feet,
                [sx * (0.5 * w - 0.05), sz * (0.5 * d - 0.05)],
                0.02,
                0.0,
                foot + 0.01,
                8,
            ));
        }
        b.top_surface("top", [-0.5 * w, -0.5 * d], [0.5 * w, 0.5 * d], h, 0.04);
    }
    b.finish(Placement::Floor, SCALE)
}

/// Camping chair: width 0.5–0.66, height 0.8–0.95, depth 0.5–0.6; folding X legs, a sling seat
/// 0.4–0.46 high and armrests.
pub(super) fn camping_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let cloth = mat_either(&mut b, 0.5, Palette::Fabric, Palette::BrightPlastic, rng);
    let (w, d) = (uniform(rng, 0.5, 0.62), uniform(rng, 0.5, 0.58));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let seat_h = uniform(rng, 0.4, 0.46);
    let top = uniform(rng, 0.8, 0.92);
    let arm_h = seat_h + uniform(rng, 0.18, 0.22);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * hw;
        b.part(strut(
            &format!("x_leg_a_{i}"),
            frame,
            [x, 0.0, -hd],
            [x, arm_h, hd - 0.02],
            [0.02, 0.02],
        ));
        b.part(strut(
            &format!("x_leg_b_{i}"),
            frame,
            [x, 0.0, hd],
            [x, arm_h, -hd + 0.02],
            [0.02, 0.02],
        ));
        b.cuboid(
            &format!("armrest_{i}"),
            frame,
            [x - 0.03, arm_h, -hd],
            [x + 0.03, arm_h + 0.02, hd],
        );
        b.part(beam(
            &format!("back_post_{i}"),
            frame,
            [x, seat_h - 0.05, -hd],
            [x, top, -hd - 0.08],
            [0.02, 0.02],
        ));
    }
    b.cuboid(
        "seat_sling",
        cloth,
        [-hw + 0.01, seat_h - 0.02, -hd + 0.02],
        [hw - 0.01, seat_h, hd - 0.02],
    );
    let corners = std::array::from_fn(|k| {
        let x = if k & 1 == 0 { -hw + 0.01 } else { hw - 0.01 };
        let up = k & 2 != 0;
        let y = if up { top - 0.02 } else { seat_h - 0.02 };
        let z = if up { -hd - 0.08 } else { -hd } + if k & 4 == 0 { 0.0 } else { 0.015 };
        [x, y, z]
    });
    b.part(hexahedron("back_sling", cloth, corners));
    b.top_surface(
        "seat",
        [-hw + 0.04, -hd + 0.04],
        [hw - 0.04, hd - 0.04],
        seat_h,
        0.02,
    );
    b.finish(Placement::Floor, SCALE)
}

/// Log bench: width 1.0–2.0, height 0.4–0.48, depth 0.28–0.42; a split log with a flat top on
/// two stumps.
pub(super) fn log_bench(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let bark = mat(&mut b, Palette::Wood, rng);
    let len = uniform(rng, 1.0, 2.0);
    let r = uniform(rng, 0.14, 0.21);
    let h = uniform(rng, 0.4, 0.48);
    let flat = 0.3 * r;
    // Half-log: the lower part of a circle of radius r cut flat at `flat` above its centre.
    let cy = h - flat;
    let n = 12;
    let top_angle = (flat / r).asin();
    // From the right top corner down around the bottom to the left top corner.
    let profile: Vec<[f32; 2]> = (0..=n)
        .map(|i| {
            let a = top_angle - (i as f32 / n as f32) * (PI + 2.0 * top_angle);
            [r * a.cos(), cy + r * a.sin()]
        })
        .collect();
    let half_chord = (r * r - flat * flat).sqrt();
    b.part(prism_x("log", bark, &profile, -0.5 * len, 0.5 * len));
    let stump_r = uniform(rng, 0.12, 0.18).min(r);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.part(cylinder(
            &format!("stump_{i}"),
            bark,
            [sx * 0.32 * len, 0.0],
            stump_r,
            0.0,
            cy - 0.5 * r,
            12,
        ));
    }
    b.top_surface(
        "seat",
        [-0.5 * len, -half_chord],
        [0.5 * len, half_chord],
        h,
        0.03,
    );
    b.finish(Placement::Floor, [0.85, 1.2])
}

/// Wheelchair: width 0.6–0.7, height 0.88–0.98, depth 0.8–1.0; two large wheels, casters, a
/// sling seat 0.46–0.52 high, armrests and foot plates.
/// The sizes a wheelchair's parts are laid out from: half width, seat height, wheel radius,
/// height of the back, seat depth and the wheels' axle position along z.
#[derive(Debug, Clone, Copy)]
struct WheelchairSize {
    hw: f32,
    seat_h: f32,
    wheel_r: f32,
    top: f32,
    seat_d: f32,
    wheel_z: f32,
}

/// One side of a wheelchair (`sx` −1 left, +1 right): drive wheel and caster, the frame's fork,
/// rail, back cane and push handle, leg rest and foot plate, armrest on its post.
fn wheelchair_side(
    b: &mut AssetBuilder,
    size: &WheelchairSize,
    frame: usize,
    tyre: usize,
    i: usize,
    sx: f32,
) {
    let WheelchairSize {
        hw,
        seat_h,
        wheel_r,
        top,
        seat_d,
        wheel_z,
    } = *size;
    b.part(rod(
        &format!("wheel_{i}"),
        tyre,
        [sx * (hw - 0.035), wheel_r, wheel_z],
        [sx * hw, wheel_r, wheel_z],
        wheel_r,
        wheel_r,
        24,
    ));
    b.part(rod(
        &format!("caster_{i}"),
        tyre,
        [sx * (hw - 0.1), 0.07, 0.36],
        [sx * (hw - 0.07), 0.07, 0.36],
        0.07,
        0.07,
        12,
    ));
    let x = sx * (hw - 0.06);
    b.part(beam(
        &format!("caster_fork_{i}"),
        frame,
        [x, 0.07, 0.36],
        [x, seat_h - 0.04, 0.3],
        [0.025, 0.025],
    ));
    b.part(beam(
        &format!("side_rail_{i}"),
        frame,
        [x, seat_h - 0.04, -0.5 * seat_d],
        [x, seat_h - 0.04, 0.5 * seat_d],
        [0.025, 0.025],
    ));
    b.part(beam(
        &format!("back_cane_{i}"),
        frame,
        [x, seat_h - 0.06, -0.5 * seat_d],
        [x, top, -0.5 * seat_d - 0.06],
        [0.025, 0.025],
    ));
    b.part(beam(
        &format!("push_handle_{i}"),
        frame,
        [x, top - 0.015, -0.5 * seat_d - 0.06],
        [x, top - 0.015, -0.5 * seat_d - 0.16],
        [0.028, 0.028],
    ));
    b.part(beam(
        &format!("leg_rest_{i}"),
        frame,
        [x, seat_h - 0.04, 0.5 * seat_d - 0.02],
        [x, 0.1, 0.5 * seat_d + 0.12],
        [0.022, 0.022],
    ));
    b.cuboid(
        &format!("foot_plate_{i}"),
        frame,
        [
            x.min(0.0) + if sx < 0.0 { 0.0 } else { -0.16 },
            0.08,
            0.5 * seat_d + 0.06,
        ],
        [
            x.max(0.0) + if sx < 0.0 { 0.16 } else { 0.0 },
            0.1,
            0.5 * seat_d + 0.2,
        ],
    );
    b.cuboid(
        &format!("armrest_{i}"),
        frame,
        [x - 0.025, seat_h + 0.2, -0.5 * seat_d + 0.02],
        [x + 0.025, seat_h + 0.23, 0.5 * seat_d - 0.08],
    );
    b.part(beam(
        &format!("arm_post_{i}"),
        frame,
        [x, seat_h - 0.04, -0.1],
        [x, seat_h + 0.21, -0.1],
        [0.02, 0.02],
    ));
}

pub(super) fn wheelchair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.5, Palette::Metal, Palette::CoatedMetal, rng);
    let tyre = mat(&mut b, Palette::Rubber, rng);
    let cloth = mat_either(&mut b, 0.5, Palette::Leather, Palette::Fabric, rng);
    let w = uniform(rng, 0.6, 0.7);
    let hw = 0.5 * w;
    let seat_h = uniform(rng, 0.46, 0.52);
    let wheel_r = uniform(rng, 0.28, 0.31);
    let top = uniform(rng, 0.88, 0.96);
    let size = WheelchairSize {
        hw,
        seat_h,
        wheel_r,
        top,
        seat_d: 0.42,
        wheel_z: -0.08,
    };
    let seat_d = size.seat_d;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        wheelchair_side(&mut b, &size, frame, tyre, i, sx);
    }
    let sx = hw - 0.06;
    b.cuboid(
        "seat_sling",
        cloth,
        [-sx, seat_h - 0.02, -0.5 * seat_d],
        [sx, seat_h, 0.5 * seat_d],
    );
    let corners = std::array::from_fn(|k| {
        let x = if k & 1 == 0 { -sx } else { sx };
        let up = k & 2 != 0;
        let y = if up { top - 0.06 } else { seat_h + 0.02 };
        let z =
            -0.5 * seat_d - if up { 0.055 } else { 0.005 } + if k & 4 == 0 { -0.012 } else { 0.0 };
        [x, y, z]
    });
    b.part(hexahedron("back_sling", cloth, corners));
    b.part(box_yaw(
        "cross_brace",
        frame,
        [0.0, 0.0],
        [sx, 0.012],
        0.12,
        0.15,
        0.0,
    ));
    b.top_surface(
        "seat",
        [-sx, -0.5 * seat_d + 0.02],
        [sx, 0.5 * seat_d],
        seat_h,
        0.03,
    );
    b.finish(Placement::Floor, SCALE)
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;

    use super::*;

    #[test]
    fn log_bench_top_is_flat_at_the_seat_height() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let asset = log_bench(&mut rng);
        let seat = &asset.info.support_surfaces[0];
        assert!((seat.height - asset.info.size[1]).abs() < 1e-4);
        assert!(asset.mesh.parts.iter().all(|p| p.is_closed_and_oriented()));
    }
}
